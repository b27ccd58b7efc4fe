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


def competition_score(errors: np.ndarray, weights: np.ndarray) -> dict[str, np.ndarray]:
    """A CEC 2017-style score of ``A`` algorithms from their mean errors on ``K`` blocks.

    ``SE = sum_k w_k e_k`` and ``SR = sum_k w_k r_k``, with ``e_k`` an algorithm's mean final
    error on block ``k`` (a function at one dimension; errors <= 1e-8 as 0) and ``r_k`` its
    rank there (1 = least mean error, ties share the mean of their ranks); then
    ``Score1 = 50 (1 - (SE - min SE) / SE)``, ``Score2 = 50 (1 - (SR - min SR) / SR)`` and
    ``Score = Score1 + Score2``, in [0, 100], 100 for an algorithm least on both sums.

    Parameters
    ----------
    errors : numpy.ndarray
        Mean errors, shape ``(K, A)``, >= 0.
    weights : numpy.ndarray
        Each block's weight (its dimension's), shape ``(K,)``, > 0.

    Returns
    -------
    dict of str to numpy.ndarray
        ``"SE"``, ``"SR"``, ``"Score1"``, ``"Score2"``, ``"Score"``, each of shape ``(A,)``.
    """
    from scipy.stats import rankdata

    e = np.asarray(errors, dtype=float)
    w = np.asarray(weights, dtype=float)[:, None]
    se, sr = (w * e).sum(axis=0), (w * rankdata(e, axis=1)).sum(axis=0)
    out = {"SE": se, "SR": sr}
    for part, total in (("Score1", se), ("Score2", sr)):
        with np.errstate(divide="ignore", invalid="ignore"):
            share = (total - total.min()) / total
        # a sum of 0 is the least one: its share is 0, not 0/0
        out[part] = 50.0 * (1.0 - np.where(total == total.min(), 0.0, share))
    out["Score"] = out["Score1"] + out["Score2"]
    return out


def score_table(study: StudyRuns) -> Table | None:
    """The suite competition's score (:attr:`mawdo.suites.SuiteSpec.score`) of the study's
    algorithms, on the finished (function, dimension) blocks of the dimensions it weighs: each
    algorithm with the same number of runs there. None when the suite defines no score, the
    store is in opfunu's numbering, or no block is finished."""
    rule = SUITES[study.suite].score if study.suite in SUITES else None
    if rule is None or study.numbering:
        return None
    errors, weights, blocks = [], [], {}
    for dim in (d for d in study.dims if d in rule.weights):
        for fid in (f for f in study.functions if f not in rule.excluded):
            cells = [study.select(a, fid, dim) for a in study.algorithms]
            if not cells[0] or any(len(c) != len(cells[0]) for c in cells):
                continue
            end = (evaluation_budget(study.budget, dim),)  # the competition table's "mean"
            errors.append([competition_errors(precision_at(c, end)).mean() for c in cells])
            weights.append(rule.weights[dim])
            blocks.setdefault(dim, []).append(fid)
    if not errors:
        return None
    s = competition_score(np.array(errors), np.array(weights))
    order = np.argsort(-s["Score"], kind="stable")
    rows = [[i + 1, study.algorithms[k], s["SE"][k], s["Score1"][k], s["SR"][k],
             s["Score2"][k], s["Score"][k]] for i, k in enumerate(order)]  # fmt: skip
    used = "; ".join(f"D={d} (weight {rule.weights[d]:g}): {len(f)} functions"
                     for d, f in blocks.items())  # fmt: skip
    left_out = ", ".join(f"F{f}" for f in rule.excluded)
    return Table(
        name="score",
        title=f"{SUITES[study.suite].label}: the {rule.name} (100 = least on both sums)",
        columns=["place", "algorithm", "SE", "Score1", "SR", "Score2", "Score"],
        rows=rows,
        notes=[
            f"Blocks: {used}; {left_out} left out. SE: weighted sum of mean final errors "
            "(<= 1e-8 as 0); SR: weighted sum of ranks of those means (ties share); "
            "Score1 = 50 (1 - (SE - min SE) / SE), Score2 likewise from SR; Score = Score1 + "
            f"Score2. Rule: {rule.source}.",
        ],
        formats={"SE": ".4e", "SR": ".2f", "Score1": ".2f", "Score2": ".2f", "Score": ".2f"},
    )
