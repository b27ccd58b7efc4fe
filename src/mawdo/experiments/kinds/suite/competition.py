"""The CEC competitions' own result tables, for suites that define checkpoints (CEC 2017, CEC
2022): per function the best, worst, median, mean and standard deviation over runs of the
final error, and the mean error at each checkpoint of the budget.

The errors come from each run's stored best-so-far record, so any checkpoint is read exactly.
As the competitions ask, an error of at most 1e-8 counts as 0 (a run stops there: both reports
stop a trial at an error below 1e-8, CEC 2022 recording that trial's evaluations as FEterm,
the mean of which is the FEs column).
"""

from __future__ import annotations

import numpy as np

from mawdo.experiments.kinds.suite.data import StudyRuns, precision_at
from mawdo.experiments.tables import Table
from mawdo.suites import SUITES, evaluation_budget

ZERO_BELOW = 1e-8
"""Errors at or below this are reported as 0 (CEC 2017/2022 technical reports)."""


def competition_errors(errors: np.ndarray) -> np.ndarray:
    """Errors as the competitions report them: at most 1e-8 becomes 0."""
    e = np.asarray(errors, dtype=float)
    return np.where(e <= ZERO_BELOW, 0.0, e)


def competition_tables(study: StudyRuns, dim: int) -> list[Table]:
    """The final-error statistics and the checkpoint means at ``dim``; none for a suite
    without checkpoints."""
    spec = SUITES.get(study.suite)
    if spec is None or spec.checkpoints is None:
        return []
    max_evals = evaluation_budget(study.budget, dim)
    marks = spec.checkpoints(dim, max_evals)
    stats, means = [], []
    for fid in study.functions:
        for algo in study.algorithms:
            runs = study.select(algo, fid, dim)
            if not runs:
                continue
            at = competition_errors(precision_at(runs, marks))
            final = at[:, -1]
            fes = float(np.mean([r.nfev for r in runs]))
            stats.append([f"F{fid}", algo, final.min(), final.max(), float(np.median(final)),
                          final.mean(), final.std(), fes, len(runs)])  # fmt: skip
            means.append([f"F{fid}", algo, *at.mean(axis=0).tolist()])
    label = spec.label
    return [
        Table(
            name=f"competition_d{dim}",
            title=f"{label} D={dim}: error f - f* after {max_evals} evaluations over runs",
            columns=[
                "function",
                "algorithm",
                "best",
                "worst",
                "median",
                "mean",
                "std",
                "FEs",
                "runs",
            ],  # fmt: skip
            rows=stats,
            block=len(study.algorithms),
            notes=[
                "The competition's table: errors <= 1e-8 count as 0; std over runs (ddof 0); "
                "FEs: mean evaluations per run (a run stops at an error <= 1e-8)."
            ],
            formats={
                **{c: ".4e" for c in ("best", "worst", "median", "mean", "std")},
                "FEs": ".0f",
            },
        ),
        Table(
            name=f"checkpoints_d{dim}",
            title=f"{label} D={dim}: mean error f - f* after the competition's checkpoints "
            "(evaluations)",
            columns=["function", "algorithm", *(str(m) for m in marks)],
            rows=means,
            block=len(study.algorithms),
            notes=["Errors <= 1e-8 count as 0."],
            formats={str(m): ".3e" for m in marks},
        ),
    ]
