"""Headline sentences of a suite study, generated from the store so that prose cannot drift.

The README quotes these sentences verbatim (``docs/results/bbob/summary.md``; a test checks the
quote), so every claim about where an algorithm stands on BBOB is a number of the stored runs:

* the runtime-ECDF value at the full budget: the fraction of (function, run, target) triples
  solved, over COCO's 51 targets ``1e2 .. 1e-8``, each function weighing the same;
* the Friedman mean rank of the median final error over (function, instance) blocks;
* per function, whether the reference algorithm's median final error ``f - f_opt`` (over
  instances and runs; lower is better) is below (better), equal to or above (worse) uniform
  random search's, naming the functions of each side, and the runs solved to ``1e-8``.
"""

from __future__ import annotations

import numpy as np

from mawdo.experiments.kinds.suite.data import StudyRuns
from mawdo.experiments.kinds.suite.measures import RANK_FLOOR, ecdf_curves, friedman_final


def final_ecdf(study: StudyRuns, dim: int) -> dict[str, float]:
    """Runtime-ECDF value at the whole budget per algorithm, in [0, 1] (all functions)."""
    x = np.array([study.budget])  # evaluations per dimension
    return {a: float(v[-1]) for a, v in ecdf_curves(study, dim, study.functions, x).items()}


def median_final(study: StudyRuns, algorithm: str, fid: int, dim: int) -> float:
    """Median over instances and runs of the final error ``f - f_opt``, floored at
    ``RANK_FLOOR``."""
    fin = [max(float(r.precision[-1]), RANK_FLOOR) for r in study.select(algorithm, fid, dim)]
    return float(np.median(fin)) if fin else float("nan")


def versus(
    study: StudyRuns, ref: str, other: str, dim: int
) -> tuple[tuple[int, ...], tuple[int, ...], tuple[int, ...]]:
    """Function ids where ``ref``'s median final error ``f - f_opt`` is below (better), equal
    to, or above (worse than) ``other``'s; functions either has no run on are left out."""
    better, equal, worse = [], [], []
    for fid in study.functions:
        a, b = median_final(study, ref, fid, dim), median_final(study, other, fid, dim)
        if np.isnan(a) or np.isnan(b):
            continue
        (better if a < b else worse if a > b else equal).append(fid)
    return tuple(better), tuple(equal), tuple(worse)


def function_list(fids) -> str:
    """``(1, 2, 3, 5, 7, 8)`` -> ``"f1-f3, f5, f7, f8"`` (runs of 3 or more as ranges); ``"none"``
    when empty."""
    parts, fids = [], sorted(fids)
    i = 0
    while i < len(fids):
        j = i
        while j + 1 < len(fids) and fids[j + 1] == fids[j] + 1:
            j += 1
        run = fids[i : j + 1]
        parts += [f"f{run[0]}-f{run[-1]}"] if len(run) >= 3 else [f"f{f}" for f in run]
        i = j + 1
    return ", ".join(parts) or "none"


def _solved(study: StudyRuns, algorithm: str, dim: int) -> tuple[int, int]:
    runs = study.select(algorithm=algorithm, dim=dim)
    hit = sum(1 for r in runs if r.evals.size and r.precision[-1] <= RANK_FLOOR)
    return hit, len(runs)


def headline(study: StudyRuns, reference: str = "mawdo", baseline: str = "random") -> list[str]:
    """One paragraph of plain sentences per dimension (Markdown), from the stored runs only.

    Parameters
    ----------
    study : StudyRuns
        The study, from :func:`mawdo.experiments.kinds.suite.data.load_runs`.
    reference : str
        The algorithm the sentences are about (MAWDO by default).
    baseline : str
        The algorithm it is compared with function by function (uniform random search).

    Returns
    -------
    list of str
        One sentence per line; empty if ``reference`` is not in the study.
    """
    if reference not in study.algorithms:
        return []
    lines = []
    for dim in study.dims:
        ecdf = final_ecdf(study, dim)
        order = sorted(ecdf, key=lambda a: -ecdf[a])
        listing = ", ".join(f"{a} {100 * ecdf[a]:.0f} %" for a in order)
        lines.append(
            f"- D = {dim}, {study.budget:g} x D evaluations: share of (function, run, target) "
            f"triples solved, COCO's 51 targets 1e2..1e-8: {listing}."
        )
        fr = friedman_final(study, (dim,))
        ranks = dict(zip(study.algorithms, fr.mean_ranks, strict=True))
        place = 1 + sum(1 for a in ranks if ranks[a] < ranks[reference])
        lines.append(
            f"- D = {dim}: {reference} has Friedman mean rank {ranks[reference]:.2f} (1 = best) "
            f"of the median final error over {fr.n_functions} (function, instance) blocks, "
            f"place {place} of {len(ranks)} (best: {min(ranks, key=ranks.get)} "
            f"{min(ranks.values()):.2f})."
        )
        if baseline in study.algorithms and baseline != reference:
            lines.append(_against(study, reference, baseline, dim))
    return lines


def _against(study: StudyRuns, reference: str, baseline: str, dim: int) -> str:
    """The sentence on ``reference`` against ``baseline``, its wins and its losses by name."""
    better, equal, worse = versus(study, reference, baseline, dim)
    hit, n = _solved(study, reference, dim)
    total = len(better) + len(equal) + len(worse)
    return (
        f"- D = {dim}: median final error f - f_opt over instances and runs (lower is better), "
        f"{reference} against {baseline}: better on {len(better)} of {total} functions "
        f"({function_list(better)}), worse on {len(worse)} ({function_list(worse)}), equal on "
        f"{len(equal)}; {hit} of {reference}'s {n} runs reach f - f_opt <= 1e-8."
    )
