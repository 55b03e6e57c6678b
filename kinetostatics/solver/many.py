"""Many mechanisms at once: :func:`solve_many`.

Every exercise checks many variants of one mechanism, and a design study sweeps
hundreds; solved one by one, each pays the solver's cost per scene (reading, structure,
assembly, a few hundred small array operations). :func:`solve_many` groups the scenes
by structure (:func:`~kinetostatics.solver.stack.signature`) and solves each group as
one scene over all its rows (:mod:`~kinetostatics.solver.stack`; groups of at most about
``CHUNK_ROWS`` rows), a run of whole scenes of about ``RUN_ROWS`` rows at a time (the
solver's cost per pass is spread over many scenes while its arrays stay in the cache),
and cuts each run's result into one scene's arrays (:class:`CutSolved`) per scene
(no array over all the rows is gathered: a scene's rows lie in one run). On the compiled
path a crank and one dyad keep every run's Me, flags and closeness from one fused
kernel call over the whole group, each run a view of them
(:func:`~kinetostatics.solver.fast.stacked.solve_group_kept`). Each holds exactly the
numbers :func:`~kinetostatics.solve` gives that scene alone: the same
elementwise operations run on every row. A scene that cannot be stacked (joint
friction, a mass model), or whose run the stacked pass refuses, is solved alone; a
``resist`` or ``when = "resisting"`` load takes its threshold from each scene's own rows.

What costs per scene in a solve is done for all the scenes at once (each scene is read
by :func:`~kinetostatics.model.scene.load_scene`, as solve reads it): what stacking needs
of a scene (its signature's label, its numbers packed, whether its positions increase:
:func:`~kinetostatics.solver.stack.stack_record`) is told once per scene object and kept
while it lives, every scene's numbers read from one array
(:class:`~kinetostatics.solver.stack.Stacker`), the assembly chosen per scene vectorised
(:func:`~kinetostatics.solver.stack.assemblies`), the finite check left to the
floating-point trap per run (:mod:`~kinetostatics.solver.trap`),
and the dead points of every scene screened in one probe solve
(:func:`~kinetostatics.solver.deadpoints.dead_points_stacked`). Each scene's arrays
hold its scene and structure from the start, and its ``Me``/``Fe`` and flags (views of
its run's, cut when first read). A run keeps nothing else: its kinematics and joint
reactions are solved again, for all its scenes at once, when one scene's are first read
(the same rows and assemblies: the same numbers), as a long sweep's are
(:class:`~kinetostatics.solver.blocks.LeanSolved`). Keeping every run's arrays cost
about as much as the solve that made them (measured for 1000 four-bars of 361 rows:
about 290 MB of fresh pages; 75-150 ms a call, against 60-75 ms lean). Its loads, as a
solve's, are computed again from its kinematics when asked for.
"""

from __future__ import annotations

import gc
import math
import warnings
from collections.abc import Iterator
from concurrent.futures import Executor
from contextlib import contextmanager
from dataclasses import replace
from functools import partial
from operator import itemgetter
from typing import Any

import numpy as np

from ..common.lazy import moved_names
from ..model.errors import UnitWarning, WorkbenchError
from ..model.memory import check_memory
from ..model.scene import Scene, load_scene
from . import blocks
from .blocks import Kept, LeanSolved
from .cut import CutSolved, RunAgain, cut_scenes, run_values, splitter
from .deadpoints import SCANS, dead_points_stacked, kin_measure2, measure2
from .fast import solve_run_stacked, wanted
from .fast.geometry import not_covered
from .fast.screen import compiled_scan, stack_clear, stack_probe
from .fast.solve import KeptRun
from .fast.stacked import release, solve_group_kept
from .footprint import columns, solve_bytes
from .kinematics import solve_kinematics
from .pipeline import check_distinct, solve_arrays, solve_block
from .probes import probe_closeness
from .reactions import DriverReaction
from .solved import Solved
from .stack import Stacker, assemblies, stack_record, stack_records
from .structure import analyse
from .trap import first_trapped, positions_tame

# rows of whole scenes solved at a time: the arrays of a run stay in the cache (as
# blocks.BLOCK_ROWS) and, with its last scene's rows, under glibc's mmap threshold of
# 128 KiB (16 384 rows): runs of 16 384 rows and a scene were each array mapped fresh and
# faulted in (about 1800 page faults a call for 1000 scenes of 361 rows, 63-85 ms against
# 61-68 ms fault-free with 11 000-15 500 rows)
RUN_ROWS = 12_288
# the compiled path's runs: its kernels go over blocks of a run (compose.ROWS) whatever
# its length, and keep of it only Me/Fe, the flags and the closeness; longer runs share
# each run's work in Python (the scenes' geometry, the plan) among more scenes
# (measured 2026-11-29, 1000 four-bars x 361: 47 ms a call against 59 in runs of 12 288;
# a crank and one dyad are now solved in one fused call for the whole group, its runs
# only cut from it and solved again when read: _whole_group)
FAST_RUN_ROWS = 49_152
CHUNK_ROWS = 1_048_576  # rows per group (one Stacker, one dead-point screen for all)

# every dead-point screen (a single sweep's too) scans compiled once the kernels are
# loaded: deadpoints cannot import the compiled path's package, which imports it
SCANS.append(compiled_scan)


def solve_all(items: list, executor: Executor | None = None, batch: int | None = None
              ) -> list[Solved | LeanSolved | CutSolved]:
    """The arrays of :func:`kinetostatics.solve_many` (which wraps each in a
    :class:`~kinetostatics.results.Solution`), one per scene, in order; the first scene
    refused raises its error, led by its place in the list (see there)."""
    if executor is None or len(items) <= 1:
        out = solved_outcomes(items)
    else:
        size = batch or max(32, math.ceil(len(items) / 25))
        parts = [items[i:i + size] for i in range(0, len(items), size)]
        # (each scene's arrays are sent back whole, pickled: its runs kept, not solved
        # again)
        out = [r for part in executor.map(partial(solved_outcomes, lean=False), parts)
               for r in part]
    if any(issubclass(kind, Exception) for kind in set(map(type, out))):  # (usually none)
        for i, r in enumerate(out):
            if isinstance(r, WorkbenchError):
                raise type(r)(f"scenes[{i}]: {r}") from None    # which scene, in one line
            if isinstance(r, Exception):
                raise r
    return out


@contextmanager
def collector_paused() -> Iterator[None]:
    """Python's cyclic garbage collector paused while the scenes are read and their
    Solutions made: thousands of small objects (few if any in a cycle) that would
    each time set off collections over every object of the process (measured for 1000
    dicts: 68 young and 6 middle collections and now and then a full one, 7-20 ms of
    about 140); the collector runs again after, if it ran before."""
    was = gc.isenabled()
    gc.disable()
    try:
        yield
    finally:
        if was:
            gc.enable()


def solved_outcomes(items: list[Any], *, lean: bool = True) -> list[Any]:
    """Per scene, its arrays (:class:`~kinetostatics.solver.solved.Solved`,
    :class:`~kinetostatics.solver.blocks.LeanSolved` or :class:`CutSolved`) or the
    exception :func:`~kinetostatics.solve` raises for it (a top-level function: the task
    an executor runs). ``lean``: each run of stacked scenes keeps only Me/Fe and the
    flags, and is solved again when a scene's kinematics or joint reactions are first
    read (:class:`RunAgain`); False keeps every run's arrays, for a caller that reads every
    table (an answer key) or sends the arrays elsewhere (pickled whole)."""
    out: list[Any] = [None] * len(items)
    groups: dict[Any, list] = {}
    alone: list = []
    one = _one_group(items)
    if one is not None:         # (the usual case: read at once)
        columns, rows = one
        _check_memory(len(items), rows, [items[0]])
        if rows < CHUNK_ROWS:   # (one chunk: its members' fields as they were read)
            _solve_group(columns, out, lean)
            return out
        groups[0] = list(zip(*columns, strict=True))
    else:
        rows = _read_each(items, out, groups, alone)
    for i, sc in alone:
        out[i] = _alone(sc)
    for members in groups.values():
        if rows < CHUNK_ROWS:       # (each group one chunk: no pass over its scenes)
            _solve_group(fields_of(members), out, lean)
            continue
        chunk: list = []
        count = 0
        for m in members:
            chunk.append(m)
            count += m[4]
            if count >= CHUNK_ROWS:
                _solve_group(fields_of(chunk), out, lean)
                chunk, count = [], 0
        if chunk:
            _solve_group(fields_of(chunk), out, lean)
    return out


def fields_of(members: list) -> tuple:
    """The members of a group (index, scene, numbers, increasing, rows, sweep and
    assemblies' cell each, :func:`~kinetostatics.solver.stack.stack_record`) as one list
    per field."""
    return tuple(list(f) for f in zip(*members, strict=True))


def _one_group(items: list) -> tuple[tuple, int] | None:
    """The fields of :func:`solved_outcomes`' one group (:func:`fields_of` its members)
    and their rows in all, when every item is a Scene of one signature whose positions
    increase (the usual case), each scene's record
    (:func:`~kinetostatics.solver.stack.stack_records`) taken and spread over the fields
    in C (no tuple per member: measured 2026-11-29, 1000 four-bars, 0.3 ms a call making
    and unzipping them); else None (read one by one, :func:`_read_each`)."""
    if not items or set(map(type, items)) != {Scene}:
        return None
    try:
        labels, numbers, ups, counts, sweeps, cells = zip(*stack_records(items),
                                                          strict=True)
    except Exception:           # (read one by one: each scene's error in its place)
        return None
    if labels[0] is None or labels.count(labels[0]) != len(labels) or not all(ups):
        return None
    return (list(range(len(items))), list(items), list(numbers), list(ups), list(counts),
            list(sweeps), cells), sum(counts)


def _read_each(items: list, out: list, groups: dict, alone: list) -> int:
    """Read the scenes one by one into ``groups`` (members by signature's label) and
    ``alone`` (scenes solved alone), each error :func:`~kinetostatics.solve` would raise
    for a scene in its place in ``out``; then check the memory of them all. Returns
    their rows in all."""
    loaded = 0
    rows = 0            # (every scene's rows, counted as it is read: the memory check)
    record = stack_record
    with warnings.catch_warnings():     # said again by solve_many, naming the scene
        warnings.simplefilter("ignore", UnitWarning)
        for i, src in enumerate(items):
            try:
                sc = load_scene(src)
                loaded += 1
                # its signature's label, its numbers, whether its positions increase
                # (then none repeats), its rows and its sweep, told once per scene object
                label, nums, up, n, sweep, cell = record(sc)
                rows += n
                if not up:
                    q = "angle" if sc.driver.kind == "R" else "length"
                    check_distinct(sc.driver.positions, sc.units.unit(q),
                                   sc.units.file_factor(q))
            except Exception as exc:        # solve would raise it for this scene
                out[i] = exc
                continue
            if label is None:
                alone.append((i, sc))
                continue
            members = groups.get(label)
            if members is None:
                members = groups[label] = []
            members.append((i, sc, nums, up, n, sweep, cell))
    _check_memory(loaded, rows, [m[0][1] for m in groups.values()] + [sc for _, sc in alone])
    return rows


def _check_memory(loaded: int, rows: int, widest: list) -> None:
    """Refuse, before it is spent, the peak memory of solving the ``loaded`` scenes of
    ``rows`` positions in all (the widest scene's columns over all their rows; the scenes
    of one group share theirs: ``widest`` holds a scene of each group and every scene
    solved alone). The memory available is read once
    (:func:`~kinetostatics.model.memory.check_memory`), not per scene."""
    if not loaded or rows < 100_000:
        return
    if not widest:          # (every scene refused: nothing will be solved)
        return
    largest = max(widest, key=columns)
    check_memory(solve_bytes(largest, rows), f"solving {loaded:,} scene(s) of "
                 f"{rows:,} positions in all", "solve fewer scenes or positions at a time")


def _alone(sc) -> Solved | LeanSolved | Exception:
    try:
        return solve_arrays(sc)
    except Exception as exc:
        return exc


def _solve_group(columns: tuple, out: list, lean: bool) -> None:
    """Solve scenes of one signature stacked (``columns``: :func:`fields_of` their
    members); any scene the stacked pass cannot vouch for (or all of them, if it
    refuses) is solved alone."""
    # (each field of the members: index, scene, numbers, increasing, rows, sweep, the
    # cell of its assemblies)
    index, scenes, numbers, ups, counts, sweeps, cells = columns
    if len(index) == 1:
        out[index[0]] = _alone(scenes[0])
        return
    stacker = None
    try:
        structure = analyse(scenes[0], assemble=False)
        one = sweeps[0] is not None and sweeps.count(sweeps[0]) == len(sweeps)
        stacker = Stacker(scenes, numbers, one)
        rows = np.array(counts)
        stacked = stacked_positions(scenes, one)
        ks, ok = kept_assemblies(stacker, structure, stacked[0][np.cumsum(rows) - rows],
                                 cells)
    except Exception:
        ok = np.zeros(len(index), dtype=bool)
    if not ok.all():        # (usually all kept: no pass over the flags, no copy)
        good = ok.tolist()
        for i, sc, g in zip(index, scenes, good, strict=True):
            if not g:
                out[i] = _alone(sc)
        kept = [m for m, g in zip(zip(*columns, strict=True), good, strict=True) if g]
        if len(kept) < 2:
            for i, sc, *_ in kept:
                out[i] = _alone(sc)
            return
        ks = ks[:, ok]
        index, scenes, numbers, ups, counts, _, _ = (list(f) for f in zip(*kept, strict=True))
        stacker, stacked, rows = Stacker(scenes, numbers), None, np.array(counts)
    try:
        sols = _stacked(scenes, structure, ks, stacker, lean, all(ups), rows, stacked)
    except Exception:
        sols = [_alone(sc) for sc in scenes]
    for i, s in zip(index, sols, strict=True):
        out[i] = s


def kept_assemblies(stacker: Stacker, structure, firsts: np.ndarray,
                    cells: list | tuple | None = None) -> tuple[np.ndarray, np.ndarray]:
    """:func:`~kinetostatics.solver.stack.assemblies` of a stack of scene objects (each
    row of ``stacker`` one of ``stacker.scenes``: not variants of one base scene), each
    scene's assemblies and whether they settle told once per scene object and kept in
    its record's cell while it lives (``cells``: those of ``stacker.scenes``, when
    read with their records; a Scene is frozen and its record's label names its
    structure: the same choice, made at its own first row, in any stack), as solve keeps
    each scene's (:mod:`~kinetostatics.solver.memo`). Measured 2026-12-01, 1000
    four-bars stacked again, processor time, best of 21 at a load of 7-8: 0.12 ms a
    call read from the cells that came with the records (one look-up per scene object
    fewer: 0.32-0.40 ms looked up apart by id and weak reference; choosing them
    0.50-0.53)."""
    if cells is None:
        cells = [stack_record(sc)[5] for sc in stacker.scenes]
    nd = len(structure.dyads)
    code = list(map(_HELD, cells))
    if None not in code:    # (each scene's an int: bit 0 whether it settles, bit d + 1 k = -1)
        code = np.array(code, dtype=np.int64)
        bits = np.arange(1, nd + 1, dtype=np.int64)[:, None]
        return 1 - 2 * ((code >> bits) & 1), (code & 1) != 0
    ks, ok = assemblies(stacker, structure, firsts)
    code = ((ks < 0) << np.arange(1, nd + 1)[:, None]).sum(axis=0) + ok
    for cell, c in zip(cells, code.tolist(), strict=True):
        cell[0] = c
    return ks, ok


_HELD = itemgetter(0)       # (what a record's cell holds)


def _stacked(scenes: list, structure, ks: np.ndarray, stacker: Stacker, lean: bool,
             increasing: bool = False, counts: np.ndarray | None = None,
             stacked: tuple | None = None
             ) -> list[CutSolved | Solved | LeanSolved | Exception]:
    """The solve of :func:`kinetostatics.solve` on the stacked scenes, cut per scene.

    The rows are solved in runs of whole scenes of about ``RUN_ROWS`` rows (as
    :mod:`~kinetostatics.solver.blocks` does, the arrays of a run stay in the cache), and
    each scene's Solution is cut from its run's arrays: no array over all the rows is
    gathered (a copy of every kept array, and fresh pages for it). A run the solver
    refuses is solved scene by scene. The dead points of every scene are screened at once
    (:func:`dead_points_stacked`, the probes of all scenes in one solve); each scene's
    Solution is a light view: its Me/Fe and flags cut from its run's when first read,
    its kinematics and joint reactions from the run solved again (:class:`RunAgain`).
    ``increasing``: every scene's positions are known to increase; ``counts``: each
    scene's number of rows, when known; ``stacked``: :func:`stacked_positions` of the
    scenes, when known.
    """
    if counts is None:
        counts = np.array([s.driver.positions.size for s in scenes])
    starts = np.cumsum(counts) - counts
    positions, tame = stacked if stacked is not None else stacked_positions(scenes)
    alone: list[int] = []
    trusty = stacker.tame() and tame
    # the compiled path for the whole group when wanted (numba loaded here, once)
    compiled = not_covered(stacker.base) is None and wanted(positions.size) is not None
    scratch: dict = {}          # (the compiled path's buffers, reused run after run)
    bounds = run_bounds(starts, counts, FAST_RUN_ROWS if compiled else RUN_ROWS)
    # lean on the compiled path: every run's kept arrays in one fused kernel call where
    # the structure has one (each run then a view of them), else run by run
    # (and the rows below the dead-point screen, told by the kernel: None if not)
    whole, below = _whole_group(trusty, stacker, structure, ks, counts, positions) if (
        compiled and lean) else (None, None)
    # (the group's closeness: read by nothing after the screen, its m^2 written over it)
    m2 = (np.empty(positions.size) if whole is None
          else measure2(whole.closeness2, positions.size, spent=True))
    runs: list = []             # (per run: again, its values and path; None if refused)
    for lo, hi in zip(bounds[:-1].tolist(), bounds[1:].tolist(), strict=True):
        a = int(starts[lo])
        b = int(starts[hi - 1] + counts[hi - 1])
        if whole is not None:
            sol = _kept_part(whole, a, b, positions)
        else:
            try:
                sol = _trapped_run(trusty, stacker, structure, ks, lo, hi, counts[lo:hi],
                                   positions[a:b], compiled, lean, scratch)
            except Exception:
                alone.extend(range(lo, hi))
                m2[a:b] = np.inf        # solved alone: nothing of it to probe here
                runs.append(None)
                continue
            m2[a:b] = kin_measure2(sol.kin)
        # lean, the scenes' Solutions keep of the run only Me/Fe and the flags; its
        # other arrays are let go before the next run is solved (which then reuses their
        # memory), and solved again when a scene's kinematics are first read
        again = (RunAgain(_trapped_run, (trusty, stacker, structure, ks, lo, hi,
                                     counts[lo:hi], positions[a:b], compiled))
                 if lean else RunAgain(None, (), splitter(sol)))
        runs.append((again, run_values(sol), getattr(sol, "path", None)))
        del sol

    dead = dead_points_stacked(m2, positions, starts, counts,
                               _probe_at(stacker, structure, ks, compiled), increasing,
                               below=below)
    if whole is not None:
        release(whole)          # (its closeness: read by nothing after the screen)
    out = cut_scenes(scenes, structure, ks, starts, counts, bounds, runs, dead)
    for j in alone:
        out[j] = _alone(scenes[j])
    return out


def _probe_at(stacker: Stacker, structure, ks: np.ndarray, compiled: bool):
    """The dead-point screen's probe ``at(positions, owner)`` of a stack
    (:func:`dead_points_stacked`): on the compiled path, a crank and one RRR dyad in one
    compiled pass (:func:`~kinetostatics.solver.fast.screen.stack_probe`: the same numbers;
    measured 2026-11-29, 1000 four-bars x 361: the screen 2.0 ms a call against 3.9,
    its probes 1.2 against 3.2, best of 15 at a load of 10-11), else numpy's
    :func:`probe_closeness` of the stacked scene at the probes' rows."""
    at = stack_probe(stacker, structure, ks) if compiled else None
    if at is not None:
        return at
    probes: dict = {}           # (the probes' structure per owner: the same each round)

    def numpy_at(where: np.ndarray, who: np.ndarray) -> tuple:
        probe = probes.get(id(who))
        if probe is None or probe[0] is not who:
            probe = probes[id(who)] = (who, replace(structure,
                                                    assembly=tuple(k[who] for k in ks)))
        # (the closeness alone; each scene's links were measured by assemblies)
        return probe_closeness(stacker.scene(who, where), probe[1], measured=True)
    # the intervals the rows prove clear (screen_bound): not probed, as on the compiled
    # path (measured 2026-12-01, numpy path, processor time, best of 9 at a load of 5-6,
    # the same tables: 1000 shapers x 361 208 -> 179 ms a call, slotted levers 116 -> 97)
    clear = stack_clear(stacker, structure, ks)
    if clear is not None:
        numpy_at.clear = clear
    return numpy_at


def stacked_positions(scenes: list, one: bool | None = None) -> tuple[np.ndarray, bool]:
    """Every scene's driver positions one after another, and whether they are tame
    (:func:`~kinetostatics.solver.trap.positions_tame`). Scenes that all sweep as the
    first, read from the same start, stop and count
    (:attr:`~kinetostatics.model.scene_types.Driver.sweep`: the same bits; ``one``, when
    known), share one read-only array, the last one kept: the same stack solved again (a
    design's generations, a study's loads) takes it as it is (measured 2026-11-29, 1000
    four-bars x 361: 2.3 ms a call gathering 1000 sweeps into fresh pages)."""
    key = scenes[0].driver.sweep
    if one is None:
        one = key is not None and all([s.driver.sweep == key for s in scenes])
    if not one:
        positions = np.concatenate([s.driver.positions for s in scenes])
        return positions, positions_tame(positions)
    got = _POSITIONS.get((key, len(scenes)))
    if got is None:
        positions = np.tile(scenes[0].driver.positions, len(scenes))
        positions.flags.writeable = False
        got = (positions, positions_tame(positions))
        _POSITIONS.clear()
        _POSITIONS[(key, len(scenes))] = got
    return got


_POSITIONS: dict[tuple, tuple[np.ndarray, bool]] = {}


def _whole_group(trusty: bool, *args) -> tuple[Kept | None, np.ndarray | None]:
    """:func:`~kinetostatics.solver.fast.stacked.solve_group_kept` (``args``) with the
    finite checks left to the floating-point trap where the stack's numbers are tame (as
    :func:`_trapped_run`): what the runs keep and the rows below the dead-point screen (or
    None: not told), or (None, None): no fused kernel for it, or its kernel refused a row
    (then each run is solved as before, the refused runs' scenes alone)."""
    try:
        got = (first_trapped(solve_group_kept, *args) if trusty
               else solve_group_kept(*args))
    except Exception:
        return None, None
    return (None, None) if got is None else got


def _kept_part(whole: Kept, a: int, b: int, positions: np.ndarray) -> KeptRun:
    """Rows ``a`` to ``b`` of the group's kept arrays, as a run's solve keeps them
    (views)."""
    return KeptRun(Kept(whole.structure, DriverReaction(whole.drive.kind,
                                                        whole.drive.value[a:b]),
                        whole.undefined[a:b], [c[a:b] for c in whole.closeness2],
                        [f[a:b] for f in whole.singular]), positions[a:b])


def run_bounds(starts: np.ndarray, counts: np.ndarray, size: int) -> np.ndarray:
    """Runs of whole scenes of about ``size`` rows: the scene numbers where each run
    begins, and the number of scenes last (a scene joins the run its first row falls
    in, so a run holds at most ``size`` rows plus its last scene's)."""
    run = starts // size
    return np.concatenate([[0], np.flatnonzero(run[1:] != run[:-1]) + 1, [counts.size]])


def _trapped_run(trusty: bool, *args) -> Solved:
    """:func:`_solve_run` with the finite checks left to the floating-point trap
    (:mod:`~kinetostatics.solver.trap`) where the stack's numbers are tame; checked
    (solved again) if the trap is touched."""
    return first_trapped(_solve_run, *args) if trusty else _solve_run(*args)


def _solve_run(stacker: Stacker, structure, ks: np.ndarray, lo: int, hi: int,
               counts: np.ndarray, positions: np.ndarray, compiled: bool = False,
               kept: bool = False, scratch: dict | None = None) -> Solved:
    """The stacked arrays of scenes ``lo`` to ``hi - 1`` (``counts`` rows each, at
    ``positions``), each dyad in its scene's assembly; a run too long for the cache (a
    long sweep) in blocks, gathered (:func:`~kinetostatics.solver.blocks.solve_blocks`),
    unless a load's threshold is its sweep's maximum (``resist``, ``when = "resisting"``:
    then in one pass, each scene's maximum over its own rows). ``compiled``: on the
    compiled path (:mod:`~kinetostatics.solver.fast`; a kernel that meets a row the numpy
    path must judge raises, and the run's scenes are solved one by one); ``kept`` there:
    only what the scenes' cut Solutions keep
    (Me/Fe, the flags, the closeness to a dead centre, in the buffers of ``scratch``,
    :func:`~kinetostatics.solver.fast.stacked.solve_run_stacked`)."""
    if compiled:
        sol = solve_run_stacked(stacker, structure, ks, lo, hi, counts, positions, kept,
                                scratch)
        if sol is not None:
            return sol
    st = replace(structure, assembly=tuple(np.repeat(k[lo:hi], counts) for k in ks))
    if blocks.blockable(stacker.base, positions.size):    # (not a sweep's maxima)
        owner = np.repeat(np.arange(lo, hi), counts)

        def part(rows: slice, _):
            who = owner[rows]
            return (stacker.scene(who, positions[rows]),
                    replace(structure, assembly=tuple(k[who] for k in ks)))
        return blocks.solve_blocks(positions.size, part, solve_block, None, st, positions)
    sc = stacker.runs(lo, hi, counts, positions)
    return solve_block(sc, st, solve_kinematics(sc, st))


# kinetostatics.solver.many.solve_many, deprecated: the public one is
# kinetostatics.solve_many (the results wrap the arrays)
__getattr__ = moved_names(__name__, {"solve_many": ("kinetostatics", "solve_many")})
