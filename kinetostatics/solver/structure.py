"""Structural analysis: a driver plus dyads (Assur groups of class II).

Seed 000 ch. 2 and seed 002 s. 2.3: a mechanism with one degree of freedom built of
a driving element and dyads is statically determinate group by group (3 n = 2 C5 for
each dyad: n = 2 bodies, C5 = 3 lower pairs). Starting from the ground and the
driver, a dyad is a pair of still unknown bodies joined to each other by one joint
(the inner joint) and each joined to the known set by exactly one joint (the outer
joints). Solving order: the order found; reactions are solved in reverse order.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

from ..model.errors import StructureError
from ..model.scene import GROUND, Joint, Scene
from .kinematics import choose_assembly


@dataclass(frozen=True)
class Dyad:
    """A dyad: bodies ``(b1, b2)``, outer joints ``(j1, j2)`` and the inner joint.

    ``kind`` reads outer1-inner-outer2 with R (revolute) or T (prismatic), e.g. RRT.
    """

    index: int
    bodies: tuple[str, str]
    outer: tuple[Joint, Joint]
    inner: Joint

    @property
    def kind(self) -> str:
        return self.outer[0].kind + self.inner.kind + self.outer[1].kind

    @property
    def label(self) -> str:
        return f"{self.kind}({self.bodies[0]}, {self.bodies[1]})"


@dataclass(frozen=True)
class Structure:
    """The driver and the dyads in solving order, and each dyad's assembly.

    ``assembly`` holds, per dyad, the seed's indicator k = +-1 (seed 000 eqs 6.1, 8.1) of
    the assembly chosen once, at the scene's first row, from the ``[near]`` hints; every
    later evaluation of the mechanism (any batch of driver positions, in any order) solves
    that same assembly. Empty until chosen (:func:`analyse` chooses it).
    """

    driver: str
    driver_joint: Joint
    dyads: tuple[Dyad, ...]
    assembly: tuple[int, ...] = ()

    def describe(self) -> list[str]:
        """One line per group, e.g. ``dyad 1: RRR bodies coupler, rocker; joints B, C, D``."""
        lines = [f"driver: {self.driver} ({'crank' if self.driver_joint.kind == 'R' else 'slider'}"
                 f", joint {self.driver_joint.name})"]
        for d in self.dyads:
            lines.append(f"dyad {d.index + 1}: {d.kind}  bodies {d.bodies[0]}, {d.bodies[1]};"
                         f"  outer joints {d.outer[0].name}, {d.outer[1].name};"
                         f"  inner joint {d.inner.name}"
                         + (f";  assembly k = {self.assembly[d.index]:+d}"
                            if len(self.assembly) == len(self.dyads) else ""))
        return lines


def analyse(scene: Scene, assemble: bool = True) -> Structure:
    """Decompose the scene into the driver and dyads in solving order, and choose each
    dyad's assembly at the scene's first row.

    Parameters
    ----------
    scene : Scene
        The checked scene.
    assemble : bool
        Choose the assemblies (the default); ``False`` gives the decomposition alone.

    Raises
    ------
    StructureError
        When the chain is not a driver plus dyads, naming the bodies left over.
    AssemblyError
        When a dyad cannot close at the first row, or no hint settles its assembly.
    """
    joints = list(scene.joints.values())
    driver = scene.driver.body
    djoint = scene.joints[scene.driver.joint]
    for j in joints:
        if j is not djoint and set(j.bodies) == {driver, GROUND}:
            raise StructureError(f"joint {j.name!r} joins the driver {driver!r} to the ground a "
                                 f"second time (besides {djoint.name!r}): the driver is locked")
    known = {GROUND, driver}
    used = {djoint.name}
    dyads: list[Dyad] = []
    unknown = [b for b in scene.bodies if b != driver]
    progress = True
    while unknown and progress:
        progress = False
        free = [j for j in joints if j.name not in used]
        for inner in free:
            b1, b2 = inner.bodies
            if b1 in known or b2 in known:
                continue
            o1 = [j for j in free if j is not inner and b1 in j.bodies and j.other(b1) in known]
            o2 = [j for j in free if j is not inner and b2 in j.bodies and j.other(b2) in known]
            if len(o1) != 1 or len(o2) != 1:
                continue
            if inner.kind == "T" and o1[0].kind == "T" and o2[0].kind == "T":
                raise StructureError(f"bodies {b1!r} and {b2!r} form a TTT group (three "
                                     "prismatic joints): it is not a dyad and cannot be solved")
            dyads.append(Dyad(len(dyads), (b1, b2), (o1[0], o2[0]), inner))
            used.update((inner.name, o1[0].name, o2[0].name))
            known.update((b1, b2))
            unknown = [b for b in unknown if b not in known]
            progress = True
            break
    if unknown:
        raise StructureError(
            f"the chain is not a driver plus dyads: bodies {', '.join(unknown)} are left over "
            f"after {len(dyads)} dyad(s) (each dyad is two bodies joined to each other and, by "
            "one joint each, to bodies already placed)")
    extra = [j.name for j in joints if j.name not in used]
    if extra:
        raise StructureError(f"joints {', '.join(extra)} are left over: with them the mechanism "
                             "is over-constrained (a driver plus dyads uses every joint once)")
    structure = Structure(driver, djoint, tuple(dyads))
    if not assemble:
        return structure
    return replace(structure, assembly=choose_assembly(scene, structure))
