"""Statistics of a sweep: summaries, Wilcoxon rank-sum vs the reference, Holm, Friedman.

Pure functions on arrays; they know nothing about stores or files
(docs/deviations.md#d-protocol).

* Summary: Best (min), Ave (mean), Std (sample, ``ddof=1``), median, worst.
* Wilcoxon rank-sum (Mann-Whitney U), two-sided, normal approximation with continuity and tie
  correction (``scipy.stats.mannwhitneyu(..., method="asymptotic")``), reference algorithm
  (MAWDO) against each rival on the final values. ``+``: the reference is significantly better
  (lower values rank lower: ``U_ref < n1 n2 / 2``), ``-``: significantly worse, ``=`` otherwise.
  When all pooled values are equal the test is undefined (zero variance); we return ``p = 1``
  and ``=`` explicitly instead of scipy's NaN.
* Holm's step-down correction over the whole family (rivals x functions).
* Friedman: per function, rank the algorithms by mean error (1 = lowest, ties averaged), average
  the ranks over functions; the chi-square test is ``scipy.stats.friedmanchisquare`` on the same
  table (needs >= 3 algorithms and >= 2 functions).
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass

import numpy as np

ALPHA = 0.05


@dataclass(frozen=True)
class Summary:
    """Best / Ave / Std / median / worst of one sample (NaN where undefined)."""

    n: int
    best: float
    mean: float
    std: float
    median: float
    worst: float


def summarize(values) -> Summary:
    """Summary of ``values``; ``std`` is the sample standard deviation (``ddof=1``, NaN for n<2).

    Infinite values (runs that never saw a finite objective value) propagate into mean and std.
    """
    x = np.asarray(values, dtype=float).ravel()
    n = int(x.size)
    if n == 0:
        nan = float("nan")
        return Summary(0, nan, nan, nan, nan, nan)
    with np.errstate(invalid="ignore"):  # inf - inf inside std of a sample holding inf
        std = float(np.std(x, ddof=1)) if n > 1 else float("nan")
    return Summary(n, float(x.min()), float(x.mean()), std, float(np.median(x)), float(x.max()))


@dataclass(frozen=True)
class RankSum:
    """Wilcoxon rank-sum of ``a`` (the reference) against ``b``.

    Attributes
    ----------
    statistic : float
        Mann-Whitney ``U`` of ``a`` (pairs ``(a_i, b_j)`` with ``a_i > b_j``, ties count 1/2).
    pvalue : float
        Two-sided asymptotic p-value (1 when undefined).
    sign : str
        ``"+"`` a significantly lower (better), ``"-"`` significantly higher, ``"="`` otherwise.
    n1, n2 : int
        Sample sizes.
    """

    statistic: float
    pvalue: float
    sign: str
    n1: int
    n2: int


def sign_of(statistic: float, n1: int, n2: int, pvalue: float, alpha: float = ALPHA) -> str:
    """``+``/``-``/``=`` from the direction of ``U`` of the reference and the p-value.

    ``U < n1 n2 / 2`` means the reference's values tend to be lower, i.e. its mean rank is lower;
    that is "better" for minimisation.
    """
    if not pvalue < alpha:
        return "="
    mid = n1 * n2 / 2.0
    if statistic < mid:
        return "+"
    if statistic > mid:
        return "-"
    return "="


def ranksum(a, b, alpha: float = ALPHA) -> RankSum:
    """Two-sided Wilcoxon rank-sum test of the reference sample ``a`` against ``b``.

    Parameters
    ----------
    a, b : array_like
        Final values (lower is better); NaNs must be removed by the caller.
    alpha : float
        Significance level of the sign.

    Returns
    -------
    RankSum
        ``p = 1`` and ``=`` when all pooled values are equal, or when a sample is empty.
    """
    x = np.asarray(a, dtype=float).ravel()
    y = np.asarray(b, dtype=float).ravel()
    n1, n2 = int(x.size), int(y.size)
    if n1 == 0 or n2 == 0:
        return RankSum(float("nan"), 1.0, "=", n1, n2)
    pooled = np.concatenate([x, y])
    if np.all(pooled == pooled[0]):
        # Zero rank variance: scipy returns NaN here; "no evidence of a difference" is p = 1.
        return RankSum(n1 * n2 / 2.0, 1.0, "=", n1, n2)
    from scipy import stats as sps  # lazy: importing scipy.stats costs ~1.5 s per command

    res = sps.mannwhitneyu(x, y, alternative="two-sided", method="asymptotic")
    p = float(res.pvalue)
    if not np.isfinite(p):
        p = 1.0
    p = min(p, 1.0)
    u = float(res.statistic)
    return RankSum(u, p, sign_of(u, n1, n2, p, alpha), n1, n2)


def holm(pvalues) -> np.ndarray:
    """Holm's step-down adjusted p-values, in the input order.

    With ``p_(1) <= ... <= p_(m)`` sorted, ``adj_(k) = max_{j <= k} min(1, (m - j + 1) p_(j))``.
    Rejecting ``adj < alpha`` controls the family-wise error rate at ``alpha``.
    """
    p = np.asarray(pvalues, dtype=float).ravel()
    m = p.size
    adj = np.empty(m)
    running = 0.0
    for j, i in enumerate(np.argsort(p, kind="stable")):
        running = max(running, min(1.0, (m - j) * p[i]))
        adj[i] = running
    return adj


@dataclass(frozen=True)
class Comparison:
    """One cell of the Wilcoxon table: reference vs ``rival`` on ``function``."""

    function: str
    rival: str
    statistic: float
    pvalue: float
    sign: str
    p_holm: float
    sign_holm: str


def compare(
    samples: Mapping[tuple[str, str], np.ndarray],
    reference: str,
    rivals: Sequence[str],
    functions: Sequence[str],
    alpha: float = ALPHA,
) -> list[Comparison]:
    """Wilcoxon of ``reference`` against each rival on each function, with Holm over the family.

    Parameters
    ----------
    samples : mapping
        ``(algorithm, function) -> final values``.
    reference : str
        The algorithm tested against the others (MAWDO).
    rivals, functions : sequences of str
        The family is every (rival, function) pair present in ``samples``.
    """
    cells = []
    for fn in functions:
        for rival in rivals:
            if (reference, fn) in samples and (rival, fn) in samples:
                r = ranksum(samples[reference, fn], samples[rival, fn], alpha)
                cells.append((fn, rival, r))
    adj = holm([c[2].pvalue for c in cells]) if cells else np.empty(0)
    return [
        Comparison(
            fn,
            rival,
            r.statistic,
            r.pvalue,
            r.sign,
            float(pa),
            sign_of(r.statistic, r.n1, r.n2, float(pa), alpha),
        )
        for (fn, rival, r), pa in zip(cells, adj, strict=True)
    ]


@dataclass(frozen=True)
class Friedman:
    """Friedman average ranks and test.

    Attributes
    ----------
    algorithms : tuple of str
        Column order.
    mean_ranks : numpy.ndarray
        Average rank of each algorithm over the functions used (1 = best).
    n_functions : int
        Functions (blocks) used: those where every algorithm has a finite-or-infinite mean.
    statistic, pvalue : float
        Friedman chi-square and its p-value; NaN when fewer than 3 algorithms or 2 functions.
    """

    algorithms: tuple[str, ...]
    mean_ranks: np.ndarray
    n_functions: int
    statistic: float
    pvalue: float


def friedman(table, algorithms: Sequence[str]) -> Friedman:
    """Friedman ranks of a ``(functions, algorithms)`` table of mean errors (lower is better).

    Rows holding NaN (an algorithm without a successful run there) are left out. When every
    remaining row is a complete tie, the test is undefined and ``p = 1``.
    """
    m = np.asarray(table, dtype=float)
    if m.ndim != 2 or m.shape[1] != len(algorithms):
        raise ValueError(f"table must have shape (functions, {len(algorithms)}), got {m.shape}")
    m = m[~np.isnan(m).any(axis=1)]
    n, k = m.shape
    if n == 0:
        nan = float("nan")
        return Friedman(tuple(algorithms), np.full(k, nan), 0, nan, nan)
    from scipy import stats as sps

    ranks = np.vstack([sps.rankdata(row, method="average") for row in m])
    mean_ranks = ranks.mean(axis=0)
    stat = pval = float("nan")
    if k >= 3 and n >= 2:
        if all(np.all(row == row[0]) for row in m):
            stat, pval = 0.0, 1.0
        else:
            with np.errstate(invalid="ignore", divide="ignore"):
                res = sps.friedmanchisquare(*m.T)
            stat, pval = float(res.statistic), float(res.pvalue)
    return Friedman(tuple(algorithms), mean_ranks, n, stat, pval)
