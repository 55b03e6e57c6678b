"""CSV text of table columns, vectorised with numpy: floats as ``'%.17g'``.

The contract's CSV files keep full precision: every float is written with 17
significant digits, exactly as Python's ``'%.17g' % x`` (and so as pandas'
``to_csv(float_format="%.17g")``) writes it, which reads back to the same double.
Formatting value by value in Python runs at about 15 MB/s; here whole columns are
formatted at once:

1. the 17 significant digits: D = round(|x| 10^(16-E)) with E the decimal exponent,
   the product taken in double-double arithmetic (Dekker's exact product; 10^k held
   as the sum of two doubles), so that D is exact unless |x| 10^(16-E) lies within
   1e-9 of a half-integer; those few values, and values beyond 1e+-270, infinities
   and the like, go to Python's own ``'%.17g'``;
2. the text: the digits, sign, point and exponent are gathered into a fixed-width
   character matrix by a layout table (one layout per sign, form and number of
   significant digits, following the ``%g`` rules: scientific when E < -4 or E >= 17,
   trailing zeros dropped), with the length of each field;
3. the rows: the columns' fields, each ending in its separator, are laid side by side
   and the characters within each field's length taken out in row order (one boolean
   mask).

Missing values (NaN) are written as empty fields, booleans as ``True``/``False``, text
quoted only when it holds a comma, a quote or a line break (pandas' defaults).
"""

from __future__ import annotations

import numpy as np

WIDTH = 25              # the longest '%.17g' text, -1.2345678901234567e-308, and a separator
_RANGE = 270            # fast path for 1e-270 <= |x| <= 1e270 (no overflow in the split)
_TIE = 1e-9             # closer than this to a half-integer: formatted by Python
_SPLIT = 134217729.0    # 2^27 + 1, Veltkamp's splitter for a double

# 10^k = _HI[k] + _LO[k] (double-double), k = -_K .. _K
_K = _RANGE + 20


def _powers_of_ten() -> tuple[np.ndarray, np.ndarray]:
    """10^k rounded to the nearest double, and the rest rounded: exact rational arithmetic
    in Python integers (int / int is correctly rounded; int -> float too)."""
    hi, lo = [], []
    for k in range(-_K, _K + 1):
        if k >= 0:
            h = float(10 ** k)
            hi.append(h)
            lo.append(float(10 ** k - int(h)))
        else:
            m = 10 ** -k
            h = 1 / m
            num, den = h.as_integer_ratio()          # h = num / den, den a power of 2
            hi.append(h)
            lo.append((den - num * m) / (m * den))   # 1/m - h
    return np.array(hi), np.array(lo)


_HI, _LO = _powers_of_ten()
_D_MIN = 10 ** 16       # 17 digits: 10^16 <= D < 10^17

# A value's characters are gathered from eight 4-byte words: six groups of three digits
# (the first group's leading digit is always 0) each followed by a filler byte that
# carries one of the constant characters (the last one the separator after the field),
# the exponent's three digits and sign, and a zero word: the room of a field after its
# text is zero bytes (never a character of a CSV field), see :func:`rows_text`.
_ZERO = 0
_DIGIT = (1, 2, 4, 5, 6, 8, 9, 10, 12, 13, 14, 16, 17, 18, 20, 21, 22)   # digits 0..16
_DOT, _MINUS, _E, _SEP = 7, 11, 15, 23
_E100, _E10, _E1, _ESIGN = 24, 25, 26, 27
_PAD = 28               # a zero byte (the eighth word is zero): a field's room after its text
_SRC = 32
_FORMS = 23             # E = -4 .. 16 in fixed notation, scientific with 2 or 3 exponent digits


def _template(neg: int, form: int, nsig: int) -> list[int]:
    """Source bytes of one field's characters (``%g`` rules, trailing zeros dropped) and
    the separator."""
    dig = _DIGIT
    out = [_MINUS] if neg else []
    if form < 21:
        e = form - 4
        if e >= 0:
            out += [dig[i] for i in range(e + 1)]
            if nsig > e + 1:
                out += [_DOT] + [dig[i] for i in range(e + 1, nsig)]
        else:
            out += [_ZERO, _DOT] + [_ZERO] * (-e - 1) + [dig[i] for i in range(nsig)]
    else:
        out += [dig[0]] + ([_DOT] + [dig[i] for i in range(1, nsig)] if nsig > 1 else [])
        out += [_E, _ESIGN] + ([_E100] if form == 22 else []) + [_E10, _E1]
    return out + [_SEP]


def _layouts() -> tuple[np.ndarray, np.ndarray]:
    keys = 2 * _FORMS * 17
    layout = np.full((keys, WIDTH), _PAD, dtype=np.intp)
    length = np.zeros(keys, dtype=np.uint8)
    for neg in range(2):
        for form in range(_FORMS):
            for nsig in range(1, 18):
                t = _template(neg, form, nsig)
                row = (neg * _FORMS + form) * 17 + nsig - 1
                layout[row, :len(t)] = t
                length[row] = len(t)
    return layout, length


_LAYOUT, _LENGTH = _layouts()
_OFFSETS = np.arange(1 << 16) * _SRC       # where each value's source bytes start


_THOUSAND = np.arange(1000)
_DIGITS3 = (48 + np.stack([_THOUSAND // 100, _THOUSAND // 10 % 10, _THOUSAND % 10],
                          axis=1)).astype(np.uint8)


def _words(last: np.ndarray) -> np.ndarray:
    """Words of the three digits of 0..999 followed by the byte(s) ``last``."""
    out = np.empty((last.shape[0], 4), dtype=np.uint8)
    out[:, :3] = np.tile(_DIGITS3, (last.shape[0] // 1000, 1))
    out[:, 3] = last
    return out.view(np.uint32).ravel()


_TRIPLE = {f: _words(np.full(1000, ord(f), dtype=np.uint8)) for f in "0.-e,\n"}
_EXPONENT = _words(np.repeat(np.frombuffer(b"+-", dtype=np.uint8), 1000))
# trailing zero digits of a three-digit group
_TRAILING = np.where(_THOUSAND == 0, 3, (_THOUSAND % 10 == 0).astype(np.int64)
                     + (_THOUSAND % 100 == 0))


def _two_product(a: np.ndarray, b: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """p = fl(a b) and its exact rounding error (Dekker), for |a|, |b| below 1e300."""
    p = a * b
    c = _SPLIT * a
    ah = c - (c - a)
    al = a - ah
    c = _SPLIT * b
    bh = c - (c - b)
    bl = b - bh
    return p, ((ah * bh - p) + ah * bl + al * bh) + al * bl


def _digits(a: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """For positive finite a within the fast range: the 17-digit integer D, the decimal
    exponent E (a = D 10^(E-16) rounded half to even) and a mask of the values whose
    rounding is too close to call (left to Python)."""
    e = np.floor(np.log10(a)).astype(np.int64)
    d, unsure = _scaled(a, e)
    for _ in range(2):              # the log10 estimate of E is off by one at most
        low, high = d < _D_MIN, d >= 10 * _D_MIN
        redo = np.flatnonzero(low | high)
        if not redo.size:
            break
        e[redo] += np.where(high[redo], 1, -1)
        d[redo], unsure[redo] = _scaled(a[redo], e[redo])
    else:
        unsure[(d < _D_MIN) | (d >= 10 * _D_MIN)] = True
    return d, e, unsure


def _scaled(a: np.ndarray, e: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """round(a 10^(16-e)) and whether a 10^(16-e) is within _TIE of a half-integer."""
    k = 16 - e + _K
    p, err = _two_product(a, _HI[k])
    t = err + a * _LO[k]                           # a 10^(16-e) = p + t, p an integer
    d = p.astype(np.int64) + np.rint(t).astype(np.int64)
    t -= np.floor(t)
    return d, np.abs(t - 0.5) < _TIE


def _sources(d: np.ndarray, e: np.ndarray, sep: str) -> tuple[np.ndarray, np.ndarray]:
    """Per value the bytes a field is gathered from (see ``_DIGIT``), and the number of
    significant digits of D (1 for D = 0)."""
    hi, lo = np.divmod(d, 10 ** 9)                 # 8 and 9 digits: int32 from here on
    hi = hi.astype(np.int32)
    lo = lo.astype(np.int32)
    groups = (hi // 1_000_000, hi // 1000 % 1000, hi % 1000,
              lo // 1_000_000, lo // 1000 % 1000, lo % 1000)
    words = np.empty((d.size, _SRC // 4), dtype=np.uint32)
    for i, (g, filler) in enumerate(zip(groups, "0.-e0" + sep, strict=True)):
        words[:, i] = _TRIPLE[filler].take(g)
    words[:, 6] = _EXPONENT.take(np.minimum(np.abs(e), 999) + 1000 * (e < 0))
    words[:, 7] = 0
    # trailing zero digits of D: of its last group, and past that (a last group of 000,
    # rare but for round numbers) of the groups before it
    trailing = _TRAILING.take(groups[5])
    more = np.flatnonzero(groups[5] == 0)
    if more.size:
        zero = np.ones(more.size, dtype=bool)
        for g in groups[4::-1]:
            gm = g[more]
            trailing[more] += np.where(zero, _TRAILING.take(gm), 0)
            zero &= gm == 0
    nsig = np.where(d == 0, 1, 17 - trailing)
    return words.view(np.uint8).reshape(d.size, _SRC), nsig


def format_floats(x: np.ndarray, sep: str = ",") -> tuple[np.ndarray, np.ndarray]:
    """``'%.17g' % v`` of every value, NaN as an empty field, each followed by ``sep``
    (``","`` or ``"\\n"``).

    Returns
    -------
    chars : ndarray of uint8, shape (n, w)
        Each value's text and separator, left-aligned, then zero bytes (``w`` at most
        ``WIDTH``: the longest field's length).
    length : ndarray of uint8, shape (n,)
        Characters of each field, the separator included.
    """
    x = np.asarray(x, dtype=float)
    n = x.size
    a = np.abs(x)
    fast = (a >= 10.0 ** -_RANGE) & (a <= 10.0 ** _RANGE)
    if fast.all():                                 # the usual case: no gather, no scatter
        d, e, unsure = _digits(a)
        slow = unsure
    else:
        d = np.zeros(n, dtype=np.int64)
        e = np.zeros(n, dtype=np.int64)
        idx = np.flatnonzero(fast)
        df, ef, unsure = _digits(a[idx])
        d[idx], e[idx] = df, ef
        slow = ~fast & (a != 0.0)                  # NaN, inf and the far ranges
        slow[idx[unsure]] = True
    src, nsig = _sources(d, e, sep)
    form = np.where((e < -4) | (e >= 17), np.where(np.abs(e) >= 100, 22, 21), e + 4)
    key = (np.signbit(x) * _FORMS + form) * 17 + nsig - 1
    length = _LENGTH[key]
    slow = np.flatnonzero(slow)
    # only as wide as the longest field (Python's text of a slow value: up to WIDTH)
    w = WIDTH if slow.size or not n else int(length.max())
    where = _LAYOUT[:, :w][key]
    where += (_OFFSETS[:n] if n <= _OFFSETS.size else np.arange(n) * _SRC)[:, None]
    chars = src.ravel().take(where).astype(np.uint8, copy=False)
    for i in slow:
        v = x[i]
        text = (b"" if v != v else (b"%.17g" % v)) + sep.encode()
        chars[i] = 0
        chars[i, :len(text)] = np.frombuffer(text, dtype=np.uint8)
        length[i] = len(text)
    return chars, length


def quote(text: str) -> str:
    """A field as pandas writes it: quoted only when it holds , " or a line break."""
    if any(c in text for c in ',"\n\r'):
        return '"' + text.replace('"', '""') + '"'
    return text


def _labels(texts: list[str], codes: np.ndarray, sep: str) -> tuple[np.ndarray, np.ndarray]:
    """Fields of a column with few distinct values: each text once, gathered by code."""
    raw = [(quote(t) + sep).encode() for t in texts] or [sep.encode()]
    width = max(1, max(len(r) for r in raw))
    table = np.zeros((len(raw), width), dtype=np.uint8)
    for i, r in enumerate(raw):
        table[i, :len(r)] = np.frombuffer(r, dtype=np.uint8)
    lengths = np.array([len(r) for r in raw], dtype=np.uint8)
    return table[codes], lengths[codes]


def format_column(col, sep: str = ",") -> tuple[np.ndarray, np.ndarray]:
    """A column's CSV fields: ``(chars, length)`` as in :func:`format_floats`.

    Floats go through :func:`format_floats`; booleans, categoricals and other columns
    are formatted once per distinct value (NaN/None as empty fields). pandas is needed
    only for a column of mixed or missing objects."""
    if hasattr(col, "categories") and hasattr(col, "codes"):        # a pandas Categorical
        texts = [str(c) for c in col.categories] + [""]
        codes = np.asarray(col.codes)
        return _labels(texts, np.where(codes < 0, len(texts) - 1, codes), sep)
    if hasattr(getattr(col, "dtype", None), "categories"):           # a categorical Series
        return format_column(col.array, sep)
    arr = np.asarray(col)
    if arr.dtype.kind == "f":
        return format_floats(arr, sep)
    if arr.dtype.kind == "b":
        return _labels(["False", "True"], arr.astype(np.intp), sep)
    if arr.dtype.kind in "iuU":
        uniques, codes = np.unique(arr, return_inverse=True)
        return _labels([str(u) for u in uniques], codes.ravel(), sep)
    seen: dict = {}                   # objects, in order of appearance (pandas.factorize)
    codes = np.fromiter((seen.setdefault(x, len(seen)) for x in arr.ravel()),
                        dtype=np.intp, count=arr.size)
    texts = ["" if x is None or (isinstance(x, float) and x != x) else str(x) for x in seen]
    return _labels(texts or [""], codes, sep)


def format_label(text: str, sep: str = ",") -> tuple[np.ndarray, np.ndarray]:
    """One row holding ``text`` (a block's name in a long table)."""
    return _labels([str(text)], np.zeros(1, dtype=np.intp), sep)


_COLUMNS = np.arange(256, dtype=np.uint8)


def rows_text(fields: list[tuple[np.ndarray, np.ndarray]]) -> bytes:
    """CSV lines from the columns' fields (each with its separator: ``,`` and, in the
    last column, ``\\n``): the fields side by side, then their characters in row order.

    The fields' room after their text is zero bytes (:func:`format_floats`,
    :func:`format_column`), so the characters are the bytes that are not zero; should a
    field hold a zero byte itself (a label with a NUL character), the count tells, and
    each field's length is used instead."""
    mats = []
    expected = 0
    for chars, length in fields:
        w = int(length.max()) if length.size else 0
        mats.append(chars[:, :w])
        expected += int(length.sum())
    flat = np.concatenate(mats, axis=1).ravel()
    text = flat[flat != 0]
    if text.size == expected:
        return text.tobytes()
    keeps = [_COLUMNS[None, :m.shape[1]] < length[:, None]
             for m, (_, length) in zip(mats, fields, strict=True)]
    return flat[np.concatenate(keeps, axis=1).ravel()].tobytes()


def header_text(names: list[str]) -> bytes:
    """The header line."""
    return (",".join(quote(str(n)) for n in names) + "\n").encode()
