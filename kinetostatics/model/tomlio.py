"""Reading and checking TOML tables: shared by the mechanism and balancing scenes.

The helpers turn a loosely typed mapping (from ``tomllib`` or a user's dict) into
checked Python values, raising :class:`~kinetostatics.model.errors.SceneError` with one
line that names the field (``where``) and the fix.
"""

from __future__ import annotations

import difflib
import math
import re
import tomllib
from collections.abc import Iterable, Mapping
from pathlib import Path
from typing import Any

import numpy as np

from .errors import SceneError, WorkbenchError


def read_source(source: Any, kind: str = "scene", bundled: Any = None) -> dict:
    """Return the raw mapping of a scene given as a path, a name, TOML text or a dict.

    Parameters
    ----------
    source : pathlib.Path, str or Mapping
        A path to a ``.toml`` file, a string naming an existing file or a bundled example,
        a string of TOML text, or an already parsed mapping.
    kind : str
        Word used in error messages.
    bundled : BundledScenes, optional
        The package's bundled scenes, so that a bare name (``"four_bar"``) is one.

    Raises
    ------
    SceneError
        "no such file" for a path (or a one-line string without ``=``) that is not a file
        nor a bundled example; "is a directory"; "save it as UTF-8 (line N)"; invalid TOML
        with its line.
    """
    if isinstance(source, Mapping):
        return dict(source)
    if isinstance(source, Path):
        return _read_file(source, kind)
    if isinstance(source, str):
        text = source.strip()
        if "\n" not in text and "=" not in text and not text.startswith("["):
            path = Path(text)
            if not path.exists() and bundled is not None:
                found = bundled.find(text)
                if found is not None:
                    return _read_file(found, kind)
            if not path.exists():
                known = (f", and not a bundled example ({', '.join(bundled.names())})"
                         if bundled is not None else "")
                raise SceneError(f"{text}: no such {kind} file{known}")
            return _read_file(path, kind)
        return parse_toml(source, kind, f"{kind} is not valid TOML")
    raise SceneError(
        f"{kind} must be a path, a TOML string or a dict, not {type(source).__name__}"
    )


def _read_file(path: Path, kind: str) -> dict:
    if path.is_dir():
        raise SceneError(f"{path} is a directory, not a {kind} file")
    if not path.is_file():
        raise SceneError(f"{path}: no such {kind} file")
    try:
        size = path.stat().st_size
        if size > MAX_FILE:
            raise SceneError(
                f"{path}: {size / 1e6:,.0f} MB, more than a {kind} file may hold "
                f"({MAX_FILE / 1e6:.0f} MB: the TOML reader takes minutes and gigabytes on "
                "it); give a long sweep as driver.start, stop and count, or a long list of "
                "positions through the Python API (kinetostatics.solve(scene, positions))")
        data = path.read_bytes()
    except OSError as exc:
        raise SceneError(f"{path}: cannot be read: {exc.strerror or exc}") from None
    try:
        text = data.decode("utf-8")
    except UnicodeDecodeError as exc:
        line = data[:exc.start].count(b"\n") + 1
        raise SceneError(f"{path}: not UTF-8 text (byte {data[exc.start]:#04x} on line "
                         f"{line}); save it as UTF-8 (line {line})") from None
    return parse_toml(text, str(path))


MAX_FILE = 32e6
"""Bytes a scene file may hold: the TOML reader (pure Python) takes about a minute and
a few GB on 1e7 listed positions (127 MB); a scene needs a few kB."""
MAX_DEPTH = 100
"""Levels of nesting (arrays, inline tables, dotted keys) a scene's TOML may have: a scene
needs a few; the reader's cost grows with the square of the depth, and its stack with
the depth."""
_QUOTED = re.compile(r'"""[\s\S]*?"""|\'\'\'[\s\S]*?\'\'\'|"(?:[^"\\\n]|\\.)*"|\'[^\'\n]*\''
                     r"|#[^\n]*")
_DOTTED = re.compile(r"(?:(?:[A-Za-z0-9_-]+|\"\")[ \t]*\.[ \t]*){" + str(MAX_DEPTH) + ",}")


def parse_toml(text: str, what: str = "scene", invalid: str | None = None) -> dict:
    """Parse TOML text, every failure one :class:`SceneError` line naming ``what``:
    invalid TOML with its line, nesting deeper than ``MAX_DEPTH`` (refused before the
    parser spends time and memory on it), a text too large for the memory. ``invalid``:
    the opening of the invalid-TOML message (``"<what>: not valid TOML"`` unless told)."""
    if (text.count("[") + text.count("{") > MAX_DEPTH or text.count(".") > MAX_DEPTH):
        _check_depth(text, what)
    try:
        return tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise SceneError(f"{invalid or f'{what}: not valid TOML'}: {exc}") from None
    except RecursionError:
        raise SceneError(f"{what}: nested too deeply for the TOML reader (a scene needs a "
                         f"few levels)") from None
    except MemoryError:
        raise SceneError(f"{what}: too large to read into memory ({len(text):,} characters)"
                         ) from None


def _check_depth(text: str, what: str) -> None:
    """Refuse nesting deeper than ``MAX_DEPTH`` (strings and comments left out)."""
    bare = _QUOTED.sub('""', text)
    depth = 0
    for m in re.finditer(r"[\[\]{}]", bare):
        depth += 1 if m.group() in "[{" else -1
        if depth > MAX_DEPTH:
            line = bare.count("\n", 0, m.start()) + 1
            raise SceneError(f"{what}: line {line}: arrays or tables nested more than "
                             f"{MAX_DEPTH} levels deep; a scene needs a few")
    m = _DOTTED.search(bare)
    if m:
        line = bare.count("\n", 0, m.start()) + 1
        raise SceneError(f"{what}: line {line}: a dotted key more than {MAX_DEPTH} levels "
                         "deep; a scene needs a few")


def suggest(name: str, known: Iterable[str]) -> str:
    """A ``" (did you mean 'x'?)"`` suffix naming the nearest known key, or ``""``."""
    close = difflib.get_close_matches(str(name), list(known), n=1, cutoff=0.5)
    return f" (did you mean {close[0]!r}?)" if close else ""


_KNOWN_KEYS: dict[tuple, frozenset] = {}     # allowed keys -> as a set, for check_keys


def check_keys(table: Any, allowed: Iterable[str], where: str,
               required: Iterable[str] = ()) -> dict:
    """Check that ``table`` is a mapping with only ``allowed`` keys and all ``required`` ones."""
    if type(table) is dict and type(allowed) is tuple:
        # the common case (a plain table, the keys a constant tuple), told by one set
        # comparison; anything else goes the long way below, which names what is wrong
        known = _KNOWN_KEYS.get(allowed)
        if known is None:
            if len(_KNOWN_KEYS) >= 64:          # tuples built from a user's keys too
                _KNOWN_KEYS.clear()
            known = _KNOWN_KEYS[allowed] = frozenset(allowed)
        if table.keys() <= known and all(k in table for k in required):
            return dict(table)
    if not isinstance(table, Mapping):
        raise SceneError(f"{where} must be a table, not {_typename(table)}")
    allowed = list(allowed)
    for key in table:
        if key not in allowed:
            raise SceneError(
                f"{where}: unknown key {key!r}{suggest(key, allowed)}; "
                f"known keys: {', '.join(allowed)}"
            )
    for key in required:
        if key not in table:
            raise SceneError(f"{where}: missing required key {key!r}")
    return dict(table)


def _typename(value: Any) -> str:
    return {dict: "a table", list: "a list", str: "a string", bool: "a boolean",
            int: "an integer", float: "a number"}.get(type(value), type(value).__name__)


MAX_MAGNITUDE = 1e12
"""Numbers beyond this are refused: no mechanism or rotor needs them, and squares of them
overflow in the formulas."""
MIN_MAGNITUDE = 1e-60
"""The ``smallest`` of :func:`as_float` for a measured magnitude that a method squares or
divides by (an amplitude, a deflection): no measured quantity is that small in any unit,
and below it squares and products (after the unit's factor) underflow to zero."""


def as_float(value: Any, where: str, *, positive: bool = False, nonnegative: bool = False,
             nonzero: bool = False, limit: float = MAX_MAGNITUDE,
             smallest: float | None = None,
             error: type[WorkbenchError] = SceneError) -> float:
    """A finite float of magnitude at most ``limit``, optionally positive / non-negative /
    non-zero; else ``error`` (a :class:`SceneError` unless told) naming ``where``. Python
    and numpy numbers are accepted, booleans are not. ``smallest``: the least magnitude
    other than zero (``MIN_MAGNITUDE`` for a positive quantity unless told, else none)."""
    if smallest is None:            # a positive quantity is divided by: keep it from 0
        smallest = MIN_MAGNITUDE if positive else 0.0
    t = type(value)
    if (t is float or t is int) and -limit <= value <= limit:   # the common case, at once
        x = float(value)            # (compared first: a huge int never reaches float())
        if ((not positive or x > 0.0)
                and (not nonnegative or x >= 0.0) and (not nonzero or x != 0.0)
                and (not smallest or x == 0.0 or not -smallest < x < smallest)):
            return x
    if isinstance(value, bool | np.bool_) or not isinstance(
            value, int | float | np.integer | np.floating):
        raise error(f"{where} must be a number, not {_typename(value)}")
    try:
        x = float(value)
    except OverflowError:           # an int beyond every float
        raise error(f"{where} = {'-' if value < 0 else ''}{len(str(abs(value)))}-digit "
                    f"number is out of range (at most {limit:g} in magnitude)") from None
    if not math.isfinite(x):
        raise error(f"{where} must be a finite number, not {value!r}")
    if abs(x) > limit:
        raise error(f"{where} = {x:g} is out of range (at most {limit:g} in magnitude)")
    if positive and x <= 0.0:
        raise error(f"{where} must be positive, got {x:g}")
    if nonnegative and x < 0.0:
        raise error(f"{where} must not be negative, got {x:g}")
    if nonzero and x == 0.0:
        raise error(f"{where} must not be zero")
    if x != 0.0 and abs(x) < smallest:
        zero = "" if positive or nonzero else "0 or "
        raise error(f"{where} = {x:g} is too small to compute with (below {smallest:g} "
                    f"in magnitude, its square underflows); give {zero}a larger value")
    return x


def as_int(value: Any, where: str, *, lo: int | None = None, hi: int | None = None) -> int:
    """An integer within [lo, hi] (a float with an integral value is accepted)."""
    if isinstance(value, bool) or not isinstance(value, int | float):
        raise SceneError(f"{where} must be an integer, not {_typename(value)}")
    if isinstance(value, float):
        if not math.isfinite(value) or value != int(value):
            raise SceneError(f"{where} must be an integer, got {value!r}")
    n = int(value)
    if lo is not None and n < lo:
        raise SceneError(f"{where} must be at least {lo}, got {n}")
    if hi is not None and n > hi:
        raise SceneError(f"{where} must be at most {hi:_}, got {n:_}")
    return n


def as_str(value: Any, where: str) -> str:
    """A non-empty string."""
    if not isinstance(value, str) or not value.strip():
        raise SceneError(f"{where} must be a non-empty string, not {_typename(value)}")
    return value


def as_vec2(value: Any, where: str) -> tuple[float, float]:
    """A pair of finite numbers ``[x, y]``."""
    plain = plain_vec2(value)
    if plain is not None:
        return plain
    if not isinstance(value, list | tuple) or len(value) != 2:
        raise SceneError(f"{where} must be a pair [x, y] of numbers, not {value!r}")
    return (as_float(value[0], f"{where}[0]"), as_float(value[1], f"{where}[1]"))


def plain_vec2(value: Any) -> tuple[float, float] | None:
    """``(x, y)`` of a list of two floats within range (the common case, told without
    building a message), else None: :func:`as_vec2` then checks it (``plain_vec2(v) or
    as_vec2(v, where)`` names ``where`` only when needed)."""
    if type(value) is list and len(value) == 2:
        x, y = value
        if (type(x) is float and type(y) is float and -MAX_MAGNITUDE <= x <= MAX_MAGNITUDE
                and -MAX_MAGNITUDE <= y <= MAX_MAGNITUDE):
            return (x, y)
    return None


def as_list(value: Any, where: str) -> list:
    """A list (TOML array)."""
    if not isinstance(value, list | tuple):
        raise SceneError(f"{where} must be a list, not {_typename(value)}")
    return list(value)
