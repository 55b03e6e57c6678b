"""Plain-text lines of the field-balancing results (the CLI's readable report and the
HTML report's tables), and the walk that collects every result's warnings."""

from __future__ import annotations

from collections.abc import Iterator
from typing import Any

__all__ = ["field_text", "fmt", "interval_text", "noise_lines", "result_warnings"]


def fmt(x: Any, unit: str = "", digits: int = 4) -> str:
    """A number to ``digits`` significant digits with its unit; '-' for None."""
    if x is None:
        return "-"
    return f"{x:.{digits}g}{(' ' + unit) if unit else ''}"


def interval_text(iv: dict | None, unit: str, confidence: float) -> str:
    """``mass lo .. hi unit, angle lo .. hi deg (95 %)`` of a correction interval."""
    if not iv:
        return ""
    m, a = iv["mass"], iv["angle"]
    hi = "unbounded" if m[1] is None else fmt(m[1], unit)
    ang = "" if a is None else (", angle: any" if a == [0.0, 360.0]
                               else f", angle {fmt(a[0])} .. {fmt(a[1], 'deg')}")
    return f"{fmt(m[0])} .. {hi}{ang} ({100.0 * confidence:g} %)"


def unit_text(unit: str) -> str:
    """A unit as printed: micrometres with the micro sign (``um`` -> ``µm``)."""
    return {"um": "µm", "um/s": "µm/s", "mum": "µm"}.get(unit, unit)


def rounded(x: Any, ref: float, unit: str = "", digits: int = 4) -> str:
    """``fmt(x, unit)``, or ``0 (to rounding)`` when |x| is at rounding level of ``ref``
    (under 1e-9 of it: a residual the corrections cancel exactly)."""
    if x is not None and ref > 0 and abs(float(x)) <= 1e-9 * ref:
        return "0 (to rounding)"
    return fmt(x, unit, digits)


def _units(out: dict[str, Any]) -> dict[str, str]:
    u = out.get("scene_units") or {}
    return {"mass": u.get("mass", "kg"), "vibration": unit_text(u.get("vibration", "")),
            "length": u.get("length", "m"), "unbalance": u.get("unbalance", "kg m")}


def field_text(out: dict[str, Any]) -> list[str]:
    """Readable lines for the ``influence``, ``iso``, ``split`` and ``combine`` results."""
    u = _units(out)
    mu, vu = u["mass"], u["vibration"]
    lines: list[str] = []
    for k, r in enumerate(out.get("influence", [])):
        conf = r["noise"]["confidence"]
        lines.append(f"influence coefficients: {r.get('name', f'influence {k + 1}')}"
                     + (f", after {r['trim_runs']} trim run(s)" if r["trim_runs"] else ""))
        for c in r["corrections"]:
            lines.append(f"  plane {c['plane']}: add {fmt(c['mass'], mu)} at "
                         f"{fmt(c['angle'], 'deg')}; interval "
                         f"{interval_text(c.get('interval'), mu, conf)}")
            if "split" in c:
                parts = ", ".join(f"{fmt(p['mass'], mu)} in position {p['position']} "
                                  f"({fmt(p['angle'], 'deg')})" for p in c["split"]["placements"])
                lines.append(f"    on {c['split']['positions']} positions: {parts}")
        ref = max((abs(x) for row in r.get("coefficients") or [] for x in _moduli(row)),
                  default=0.0) * max((abs(c["mass"] or 0.0) for c in r["corrections"]),
                                     default=0.0)
        res = ", ".join(f"{r2.get('point', f'point {i + 1}')} "
                        f"{rounded(r2['amplitude'], ref, vu)}"
                        for i, r2 in enumerate(r["residual_vibration"]))
        lines.append(f"  predicted residual vibration: {res}")
        n = r["noise"]
        lines.append(f"  intervals at {100.0 * n['confidence']:g} % for readings with "
                     f"{_noise_text(n['relative'], n['absolute'], vu, n['phase_noise'])}")
        lines.append(f"  condition number {fmt(r['condition_number'])}: that reading noise "
                     f"moves the correction by up to {fmt(100.0 * r['noise_amplification'])} % "
                     "(a first-order bound; the intervals above are the likelihood's)")
    if "iso" in out:
        s = out["iso"]
        un = s["unbalance_unit"]
        lines.append(f"ISO 21940-11: G {s['grade']:g}, {fmt(s['rotor_mass'], mu)} at "
                     f"{s['speed_rpm']:g} rpm: U_per = {fmt(s['U_per'], un)} (e_per "
                     f"{fmt(s['e_per'], u['length'])})")
        for b in s.get("bearing_planes", []):
            lines.append(f"  bearing plane {b['name']} (z = {b['z']:g} {u['length']}): "
                         f"permissible {fmt(b['permissible'], un)}")
        for c in s.get("correction_planes", []):
            if c["permissible"] is not None:
                lines.append(f"  correction plane {c['plane']} (z = {c['z']:g} {u['length']}):"
                             f" permissible {fmt(c['permissible'], un)}")
        if s.get("kind") == "narrow":
            lines.append(f"  narrow rotor: static {fmt(s['static'], un)}, couple "
                         f"{fmt(s['couple'], un)} per plane")
        if "check" in s:
            c = s["check"]
            lines.append(f"  residual {', '.join(fmt(x, un) for x in c['residual'])}: "
                         f"{'within' if c['ok'] else 'NOT within'} tolerance (ratio "
                         f"{', '.join(fmt(x) for x in c['ratio'])})")
    for sp in out.get("split", []):
        parts = ", ".join(f"{fmt(p['mass'], mu)} in position {p['position']} "
                          f"({fmt(p['angle'], 'deg')})" for p in sp["placements"])
        lines.append(f"split {fmt(sp['mass'], mu)} at {fmt(sp['angle'], 'deg')} onto "
                     f"{sp['positions']} positions: {parts}")
    for cb in out.get("combine", []):
        at = f" at radius {fmt(cb['radius'], u['length'])}" if cb["radius"] is not None else ""
        what = ("they cancel: no weight needed" if cb["angle"] is None
                else f"{fmt(cb['mass'], mu)} at {fmt(cb['angle'], 'deg')}{at}")
        lines.append(f"combine {cb['count']} weights into one: {what}")
    return lines


def _noise_text(relative: float, absolute: float, unit: str, phase: float | None) -> str:
    """``1 % of each amplitude (1 sigma), 1 deg of phase``: a noise model in words."""
    parts = [f"{100.0 * relative:g} % of each amplitude"]
    if absolute:
        parts[0] += f" + {absolute:g} {unit}".rstrip()
    parts[0] += " (1 sigma)"
    if phase is not None:
        parts.append(f"{phase:g} deg of phase")
    return ", ".join(parts)


def noise_lines(results: dict[str, Any], out: dict[str, Any]) -> list[str]:
    """What the report's intervals assume: the reading noise and the confidence of each
    resonance test's estimate (the result objects carry them; the result dict does
    not), and what "not determined" means. Influence results state theirs in
    :func:`field_text`."""
    from ..resonance.estimate import WIDE, WIDE_ANGLE
    vu = _units(out)["vibration"]
    lines = []
    for k, t in enumerate(results.get("resonance_test", [])):
        est = getattr(t, "estimate", None)
        if est is None:
            continue
        rel, ab = est.noise
        lines.append(f"resonance test {k + 1}: intervals at {100.0 * est.confidence:g} % for "
                     f"readings with {_noise_text(rel, ab, vu, None)}; an estimate is not "
                     f"determined when its interval leaves more than {100.0 * WIDE:g} % of "
                     f"the unbalance uncorrected (or spans more than {WIDE_ANGLE:.1f} deg)")
    return lines


def result_warnings(out: dict[str, Any]) -> Iterator[tuple[str, str]]:
    """Every entry of every ``warnings`` list in a result dict, with where it came from
    (``influence[0]``, ``rotor``, ``resonance_test[1].estimate``, ...)."""
    def walk(node: Any, where: str) -> Iterator[tuple[str, str]]:
        if isinstance(node, dict):
            for key, value in node.items():
                if key == "warnings" and isinstance(value, list):
                    # a note that names its section already ("rotor: ...") is not
                    # prefixed twice
                    yield from (("" if str(w).startswith(f"{where}: ") else where, str(w))
                                for w in value)
                else:
                    yield from walk(value, f"{where}.{key}" if where else key)
        elif isinstance(node, list):
            for i, value in enumerate(node):
                yield from walk(value, f"{where}[{i}]")

    yield from walk(out, "")


def _moduli(row: Any) -> list[float]:
    """The moduli of a row of influence coefficients (complex as [re, im] or dicts)."""
    out = []
    for c in row if isinstance(row, list) else [row]:
        if isinstance(c, dict):
            c = c.get("amplitude", c.get("modulus", 0.0))
        if isinstance(c, list | tuple) and len(c) == 2:
            c = complex(c[0], c[1])
        try:
            out.append(abs(complex(c)))
        except (TypeError, ValueError):
            continue
    return out


def _fmt6(x: Any, unit: str = "") -> str:
    return fmt(x, unit, 6)


def summary_text(out: dict[str, Any], speed: bool) -> str:
    lines: list[str] = []
    if "rotor" in out:
        r = out["rotor"]
        fu, mu = ("N", "N m") if speed else ("kg m", "kg m^2")
        kind = "static (one plane)" if len(r["corrections"]) == 1 else "dynamic (two planes)"
        lines.append(f"rotor: {kind} balancing")
        for c in r["corrections"]:
            lines.append(f"  plane {c['plane']} (z = {c['z']:g} m): mass {_fmt6(c['mass'], 'kg')}"
                         f" at {_fmt6(c['angle'], 'deg')}, radius {c['radius']:g} m, "
                         f"U = {_fmt6(c['U'], 'kg m')}")
        for what, unit, tail in (("force", fu, ""), ("moment", mu, " (about z = 0)")):
            before = r[f"initial_{what}"]
            lines.append(f"  {what:<6} before {_fmt6(before, unit)}, after "
                         f"{rounded(r[f'residual_{what}'], before or 0.0, unit, 6)}{tail}")
    if "static_test" in out:
        s = out["static_test"]
        lines.append("static balancing device:")
        lines.append(f"  eccentricity {_fmt6(s['eccentricity'], 'm')}, correction mass "
                     f"{_fmt6(s['correction_mass'], 'kg')}")
    for t in out.get("resonance_test", []):
        lines.append(f"resonance test, plane {t['plane']}:")
        lines.append(f"  A = {_fmt6(t['A'])}, phi = {_fmt6(t['phi'], 'deg')}, unbalance "
                     f"{_fmt6(t['unbalance'], 'kg m')}")
        where = f"at {_fmt6(t['angle'], 'deg')}"
        if t["mirror_angle"] is not None:
            where += f" (or at {_fmt6(t['mirror_angle'], 'deg')}: the mirror position)"
        lines.append(f"  correction mass {_fmt6(t['correction_mass'], 'kg')} {where}")
        if "uncertainty" in t:
            u = t["uncertainty"]
            ang = u["angle"]
            lines.append(f"  with +-{u['dA']:g} on each amplitude: mass {_fmt6(u['magnitude'][0])}"
                         f" .. {_fmt6(u['magnitude'][1], 'kg')}"
                         + (f", angle {_fmt6(ang[0])} .. {_fmt6(ang[1], 'deg')}" if ang else ""))
        if t.get("estimate"):
            lines.extend(_estimate_lines(t["estimate"]))
    lines.extend(field_text(out))
    if "balancing" in out:
        b = out["balancing"]
        lines.append(f"mechanism balancing: {b['mechanism']}, method {b['method']}")
        lines.append(f"  procedure: {b['procedure']}")
        for c in b["counterweights"]:
            lines.append(f"  counterweight on {c['body']} about {c['about']}: mass "
                         f"{_fmt6(c['mass'], 'kg')} at radius {c['radius']:g} m, angle "
                         f"{_fmt6(c['angle'], 'deg')} (body frame)")
        if b.get("counter_rotating"):
            p = b["counter_rotating"]
            lines.append(f"  counter-rotating pair: two masses of {_fmt6(p['mass'], 'kg')} at "
                         f"{_fmt6(p['radius'], 'm')}")
        lines.append(f"  shaking force max: before {_fmt6(b['shaking_force_before'], 'N')}, "
                     f"after {_fmt6(b['shaking_force_after'], 'N')}")
        if "shaking_moment_before" in b:
            lines.append(f"  shaking moment max (about the crank axis): before "
                         f"{_fmt6(b['shaking_moment_before'], 'N m')}, after "
                         f"{_fmt6(b['shaking_moment_after'], 'N m')}")
    return "\n".join(lines)


def _estimate_lines(est: dict[str, Any]) -> list[str]:
    """The maximum-likelihood estimate of a resonance test, with its intervals."""
    def arc(iv: dict[str, Any] | None) -> str:
        if not iv:
            return ""
        u, a = iv["unbalance"], iv["angle"]
        hi = "unbounded" if u[1] is None else fmt(u[1], "kg m")
        text = f"; unbalance {fmt(u[0])} .. {hi}"
        return text + (f", angle {fmt(a[0])} .. {fmt(a[1], 'deg')} (counterclockwise)"
                       if a else "")
    conf = est.get("confidence")
    head = f"  estimate (maximum likelihood{f', {100 * conf:g} %' if conf else ''}): "
    out = [head + f"unbalance {fmt(est['unbalance'], 'kg m')}, mass "
           f"{fmt(est['correction_mass'], 'kg')} at {fmt(est['angle'], 'deg')}"
           + arc(est.get("interval"))]
    if est.get("mirror_angle") is not None:
        out.append(f"    or at {fmt(est['mirror_angle'], 'deg')} (the readings cannot tell)"
                   + arc(est.get("mirror_interval")))
    return out
