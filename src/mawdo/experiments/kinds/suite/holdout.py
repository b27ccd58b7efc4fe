"""The hold-out study as suite presets: CEC 2017 and CEC 2022.

WDO+ (``wdo_plus``) was designed on BBOB only; these presets judge it on suites it never saw,
at each suite's own budget, against the hold-out's ten algorithms. The paper's F1-F16, unshifted
and shifted, are the benchmark kind's presets ``holdout-paper`` and ``holdout-paper-shifted``.

Budgets (evaluations per dimension, COCO's convention): CEC 2017 gives ``10000 D`` per run;
CEC 2022 gives 200 000 evaluations at D = 10 and 1 000 000 at D = 20, i.e. ``20000 D`` and
``50000 D``, so its two dimensions are two presets (a suite plan has one budget per D).
CEC's protocol asks 51 runs; the presets make 10 (docs/deviations.md#d-holdout-runs).

The suites are the official code's (batched), in the official numbering. CEC 2017 runs the 29
functions its competition ranks: F1 and F3-F30 (its organisers dropped F2, the sum of different
powers, as unstable). The committed stores (docs/results/holdout) were made before, through
opfunu, when ``cec2017`` meant opfunu's F1-F29 (official F1, F3-F30 by formula); their reports
say so (:meth:`SuitePlan.numbering_note`).
"""

from __future__ import annotations

from typing import Any

from mawdo.optimizers import HOLDOUT_ALGORITHMS

HOLDOUT_SEED = 20261126
"""Master seed of the hold-out presets."""


CEC2017_RANKED = [1, *range(3, 31)]
"""The CEC 2017 functions its competition ranks (F2 was dropped by the organisers)."""


def _cec(
    name: str, suite: str, dims: list[int], budget: float, functions: list[int], runs: int = 10
) -> dict:
    return {
        "name": name,
        "suite": suite,
        "algorithms": list(HOLDOUT_ALGORITHMS),
        "functions": list(functions),
        "instances": [1],
        "dims": dims,
        "budget": budget,
        "runs": runs,
        "seed": HOLDOUT_SEED,
    }


HOLDOUT_PRESETS: dict[str, dict[str, Any]] = {
    "holdout-cec2017": _cec("holdout-cec2017", "cec2017", [10, 30], 1e4, CEC2017_RANKED),
    "holdout-cec2022-d10": _cec("holdout-cec2022-d10", "cec2022", [10], 2e4, list(range(1, 13))),
    "holdout-cec2022-d20": _cec("holdout-cec2022-d20", "cec2022", [20], 5e4, list(range(1, 13))),
    # The committed study (docs/results/holdout): what a shared 2-core machine finishes in one
    # session. opfunu evaluates one point per call (random search: 327 us of wall time per
    # evaluation on CEC 2017, D = 10, at load ~6), so CEC's own budgets at D = 30 / 20 are days
    # of CPU here (docs/deviations.md#d-holdout-quick).
    "holdout-quick-cec2017": _cec(
        "holdout-quick-cec2017", "cec2017", [10], 1e3, CEC2017_RANKED, runs=2
    ),
    "holdout-quick-cec2022": _cec(
        "holdout-quick-cec2022", "cec2022", [10], 1e3, list(range(1, 13)), runs=2
    ),
}
"""Suite presets of the hold-out study."""

HOLDOUT_HELP = {
    "holdout-cec2017": "WDO+ hold-out: CEC 2017 F1, F3-F30, D 10 and 30, 1e4 x D evaluations, "
    "10 runs: CMA-ES, scipy DE, random, GWO, WOA, WDO, AWDO, MAWDO, MEWDO, WDO+",
    "holdout-cec2022-d10": "WDO+ hold-out: CEC 2022 F1-F12, D 10, 2e4 x D (200 000) "
    "evaluations, 10 runs, the same ten algorithms",
    "holdout-cec2022-d20": "WDO+ hold-out: CEC 2022 F1-F12, D 20, 5e4 x D (1 000 000) "
    "evaluations, 10 runs, the same ten algorithms",
    "holdout-quick-cec2017": "WDO+ hold-out, reduced (the committed study, made through "
    "opfunu): CEC 2017 F1, F3-F30, D 10, 1e3 x D evaluations, 2 runs, the same ten algorithms",
    "holdout-quick-cec2022": "WDO+ hold-out, reduced (the committed study, made through "
    "opfunu): CEC 2022 "
    "F1-F12, D 10, 1e3 x D evaluations, 2 runs, the same ten algorithms",
}
