"""What the solver works out once per scene object, kept while the scene lives.

A :class:`~kinetostatics.model.scene.Scene` is frozen: what follows from it alone (its
structure, each dyad's assembly at its first row, the compiled kernels' geometry) is the
same at every solve of it. A caller that solves one scene again and again (other
positions, a loop, a simulation's steps) gets them from here; a scene read anew (from a
dict, a file) is a new object with a record of its own. The record goes with its scene
(a weak reference: nothing here keeps a scene alive), or sooner: the last
:data:`KEPT` scenes' records are kept.
"""

from __future__ import annotations

import weakref

_RECORDS: dict[int, tuple[weakref.ref, dict]] = {}
# The records of the last few scenes solved, not of every scene alive: a program holding
# thousands of scenes (solve_many's input, solved one by one first) would keep thousands
# of structures, which every full pass of the garbage collector then walks (measured
# 2026-11-29: solve_many of 1000 four-bars 80 -> 90 ms after a loop of solve over them)
KEPT = 64


def record_of(scene: object) -> dict:
    """The record kept for ``scene`` (a dict, empty at first), while ``scene`` lives."""
    key = id(scene)
    entry = _RECORDS.get(key)
    if entry is not None and entry[0]() is scene:
        return entry[1]
    record: dict = {}
    if len(_RECORDS) >= KEPT:
        forget_oldest(_RECORDS)

    def gone(ref: weakref.ref, key: int = key) -> None:
        if _RECORDS.get(key, (None,))[0] is ref:
            _RECORDS.pop(key, None)
    _RECORDS[key] = (weakref.ref(scene, gone), record)
    return record


def forget_oldest(kept: dict) -> None:
    """Drop the oldest entry of ``kept`` (another thread changing it at the same moment
    may make it one more or one less: no harm)."""
    try:
        kept.pop(next(iter(kept)), None)
    except (StopIteration, RuntimeError):
        pass
