"""The CEC competitions' own protocols as suite presets (``cec2017-official``,
``cec2022-official-d10``, ``cec2022-official-d20``).

CEC 2017: F1-F30 at D = 10 and 30, 51 runs, ``10000 D`` evaluations per run; CEC 2022: F1-F12,
30 runs, 200 000 evaluations at D = 10 and 1 000 000 at D = 20 (``20000 D`` and ``50000 D``:
two presets, a suite plan having one budget per dimension). A run stops at an error of 1e-8 or
at the budget, as both reports ask; every run's best-so-far record is stored, so the errors at
the competitions' checkpoints (:func:`mawdo.suites.cec_native.checkpoints`) and their tables
(:mod:`.competition`: best, worst, median, mean, std of the error per function, errors up to
1e-8 as 0) come from the store. The algorithms are the hold-out study's ten and the three
winners of recent competitions (L-SHADE, jSO, NL-SHADE-RSP, EA4eig): fourteen.
"""

from __future__ import annotations

from typing import Any

from mawdo.optimizers import OFFICIAL_ALGORITHMS

OFFICIAL_SEED = 20171122
"""Master seed of the official-protocol presets."""


def _official(name: str, suite: str, n: int, dims: list[int], budget: float, runs: int) -> dict:
    return {
        "name": name,
        "suite": suite,
        "algorithms": list(OFFICIAL_ALGORITHMS),
        "functions": list(range(1, n + 1)),
        "instances": [1],
        "dims": dims,
        "budget": budget,
        "runs": runs,
        "seed": OFFICIAL_SEED,
    }


OFFICIAL_PRESETS: dict[str, dict[str, Any]] = {
    "cec2017-official": _official("cec2017-official", "cec2017", 30, [10, 30], 1e4, 51),
    "cec2022-official-d10": _official("cec2022-official-d10", "cec2022", 12, [10], 2e4, 30),
    "cec2022-official-d20": _official("cec2022-official-d20", "cec2022", 12, [20], 5e4, 30),
}
"""The competitions' protocols (one plan per CEC 2022 dimension: its budgets differ)."""

OFFICIAL_HELP = {
    "cec2017-official": "CEC 2017's protocol: F1-F30, D 10 and 30, 1e4 x D evaluations, 51 "
    "runs, the hold-out's ten algorithms and four CEC winners; report with the "
    "competition's tables",
    "cec2022-official-d10": "CEC 2022's protocol at D 10: F1-F12, 200 000 evaluations, 30 runs",
    "cec2022-official-d20": "CEC 2022's protocol at D 20: F1-F12, 1 000 000 evaluations, 30 runs",
}
