"""Plain-text lines of the field-balancing results (the CLI's readable report and the
HTML report's tables), and the walk that collects every result's warnings."""

from __future__ import annotations

from collections.abc import Iterator
from typing import Any

__all__ = ["field_text", "fmt", "interval_text", "result_warnings"]


def fmt(x: Any, unit: str = "") -> str:
    """A number to 4 significant digits with its unit; '-' for None."""
    if x is None:
        return "-"
    return f"{x:.4g}{(' ' + unit) if unit else ''}"


def interval_text(iv: dict | None, unit: str, confidence: float) -> str:
    """``mass lo .. hi unit, angle lo .. hi deg (95 %)`` of a correction interval."""
    if not iv:
        return ""
    m, a = iv["mass"], iv["angle"]
    hi = "unbounded" if m[1] is None else fmt(m[1], unit)
    ang = "" if a is None else (", angle: any" if a == [0.0, 360.0]
                               else f", angle {fmt(a[0])} .. {fmt(a[1], 'deg')}")
    return f"{fmt(m[0])} .. {hi}{ang} ({100.0 * confidence:g} %)"


def _units(out: dict[str, Any]) -> dict[str, str]:
    u = out.get("units") or {}
    return {"mass": u.get("mass", "kg"), "vibration": u.get("vibration", ""),
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
        res = ", ".join(f"{r2.get('point', f'point {i + 1}')} {fmt(r2['amplitude'], vu)}"
                        for i, r2 in enumerate(r["residual_vibration"]))
        lines.append(f"  predicted residual vibration: {res}")
        lines.append(f"  condition number {fmt(r['condition_number'])}, noise amplified to "
                     f"{fmt(100.0 * r['noise_amplification'])} % of the correction")
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


def result_warnings(out: dict[str, Any]) -> Iterator[tuple[str, str]]:
    """Every entry of every ``warnings`` list in a result dict, with where it came from
    (``influence[0]``, ``rotor``, ``resonance_test[1].estimate``, ...)."""
    def walk(node: Any, where: str) -> Iterator[tuple[str, str]]:
        if isinstance(node, dict):
            for key, value in node.items():
                if key == "warnings" and isinstance(value, list):
                    yield from ((where, str(w)) for w in value)
                else:
                    yield from walk(value, f"{where}.{key}" if where else key)
        elif isinstance(node, list):
            for i, value in enumerate(node):
                yield from walk(value, f"{where}[{i}]")

    yield from walk(out, "")
