"""The design search's speed: kinetostatic rows per second of ``design`` (bench row)."""

from __future__ import annotations


def bench_design(population: int = 1000, generations: int = 10, repeat: int = 2
                 ) -> list[dict]:
    """``design`` on the bundled four_bar_design (``population`` x ``generations`` x 361
    rows, seed 1, nothing written) against ``solve_many`` of as many scenes of that
    mechanism as dicts (its variants within +-10 %: the bare stacked solve, no screen,
    no optimiser): the seconds of each, their ratio, and ``design``'s rows per second.
    Needs pymoo (the ``[design]`` extra); without it, no row."""
    try:
        import pymoo  # noqa: F401
    except ImportError:
        return []
    from ..design.result import design
    from ..solver.many import solve_many
    from .speed import _row, four_bar_variants, side_by_side
    dicts = four_bar_variants(population)
    times = side_by_side({
        "design": lambda: design("four_bar_design", population=population,
                                 generations=generations, seed=1),
        "many": lambda: [solve_many(dicts) for _ in range(generations)]}, repeat)
    rows = population * generations * 361
    return [_row("design: rows per second (NSGA-II, one stacked solve a generation)",
                 f"{population} x {generations} x 361", times, "design", "many",
                 rows_per_second=rows / min(times["design"]))]
