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


class Kept:
    """Values kept per live object, by identity (a weak reference: nothing here keeps an
    object alive), for the last ``size`` objects given one; an object gone takes its value
    with it, and a new object at a dead one's address never gets the dead one's value."""

    def __init__(self, size: int) -> None:
        self.size = size
        self.entries: dict[int, tuple[weakref.ref, object]] = {}

    def get(self, obj: object) -> object | None:
        """The value kept for ``obj``, or None."""
        entry = self.entries.get(id(obj))
        return entry[1] if entry is not None and entry[0]() is obj else None

    def put(self, obj: object, value: object) -> None:
        """Keep ``value`` for ``obj`` while it lives (the oldest entry dropped when full)."""
        key, entries = id(obj), self.entries
        if len(entries) >= self.size:
            forget_oldest(entries)

        def gone(ref: weakref.ref, key: int = key) -> None:
            if entries.get(key, (None,))[0] is ref:
                entries.pop(key, None)
        entries[key] = (weakref.ref(obj, gone), value)


# The records of the last few scenes solved, not of every scene alive: a program holding
# thousands of scenes (solve_many's input, solved one by one first) would keep thousands
# of structures, which every full pass of the garbage collector then walks (measured
# 2026-11-29: solve_many of 1000 four-bars 80 -> 90 ms after a loop of solve over them)
KEPT = 64
_RECORDS = Kept(KEPT)


def record_of(scene: object) -> dict:
    """The record kept for ``scene`` (a dict, empty at first), while ``scene`` lives."""
    record = _RECORDS.get(scene)
    if record is None:
        record = {}
        _RECORDS.put(scene, record)
    return record


def forget_oldest(kept: dict) -> None:
    """Drop the oldest entry of ``kept`` (another thread changing it at the same moment
    may make it one more or one less: no harm)."""
    try:
        kept.pop(next(iter(kept)), None)
    except (StopIteration, RuntimeError):
        pass


def interned(table: dict, key: object, size: int = 64) -> object:
    """The first object met equal to ``key`` (kept in ``table``, emptied when it holds
    ``size``), so that equal keys are one object and are told alike by identity: the
    sweep keys of a stack's records, the dyads of a structure (measured 2026-11-30, 1000
    four-bars x 361: counting the first scene's sweep key among 1000 equal ones, each its
    own tuple, 0.3-1.2 ms a call of solve_many; the same object: 3 us)."""
    got = table.get(key)
    if got is None:
        if len(table) >= size:
            table.clear()       # (an equal key met again after: a new object, no harm)
        got = table[key] = key
    return got
