"""A mechanism solve's summary as the lines a person reads (``solve`` and ``demo``
print them): every number with its unit, a mean that is rounding said as zero, the
warnings last."""

from __future__ import annotations

__all__ = ["summary_text"]


def summary_text(summary: dict) -> str:
    """A mechanism solve's labelled summary (as
    :func:`~kinetostatics.results.output.summary_with_units` gives it) as readable
    lines, every number with its unit, the warnings last."""
    unit = summary["unit_of"]
    q = "Fe" if "Fe_mean" in summary else "Me"
    u, pu = unit[f"{q}_mean"], unit["reaction_max"]["position"]
    mean, low, high = (summary[q + k] for k in ("_mean", "_min", "_max"))
    # a mean that is rounding next to the peaks (a whole cycle of a conservative load:
    # 6e-16 N m beside 22 N m) is said as zero, not as a number nobody can use
    said = ("0 (to rounding)" if abs(mean) <= 1e-12 * max(abs(low), abs(high))
            else f"{mean:.6g} {u}")
    lines = [f"{summary['title'] or 'scene'}: {summary['positions']} positions", *(
        "  " + line for line in summary["structure"]),
        f"  {q} mean {said}, min {low:.6g} {u}, max {high:.6g} {u}"]
    lines += [f"  joint {j}: max |F| = {r['F']:.6g} N at {r['position']:g} {pu}"
              for j, r in summary["reaction_max"].items()]
    if summary.get("transmission_angle_min") is not None:
        lines.append(f"  transmission angle min(tau, 180 - tau) = "
                     f"{summary['transmission_angle_min']:.6g} deg at "
                     f"{summary['transmission_angle_min_position']:g} {pu} (dyad "
                     f"{summary['transmission_angle_min_dyad']})")
    lines.append(f"  singular rows {summary['singular_rows']}, undefined-load rows "
                 f"{summary['undefined_load_rows']}")
    scene = summary["scene_units"]
    if any(scene[k] != v for k, v in (("length", "m"), ("mass", "kg"), ("angle", "deg"),
                                      ("speed", "rad/s"), ("force", "N"))):
        lines.append("  (the scene was typed in " + ", ".join(f"{k} {v}" for k, v in
                                                              scene.items()) + "; the "
                     "numbers above are SI)")
    lines.append("warnings: " + ("; ".join(summary["warnings"]) or "none"))
    return "\n".join(lines)
