"""Headline sentences of a suite study, generated from the store so that prose cannot drift.

The README quotes these sentences verbatim (``docs/results/bbob/summary.md``; a test checks the
quote), so every claim about where an algorithm stands on BBOB is a number of the stored runs:

* the runtime-ECDF value at the full budget: the fraction of (function, run, target) triples
  solved, over COCO's 51 targets ``1e2 .. 1e-8``, each function weighing the same;
* the Friedman mean rank of the median final precision over (function, instance) blocks;
* per function, whether the reference algorithm's median final precision (over instances and
  runs) is below, equal to or above uniform random search's, and problems solved to ``1e-8``.
"""

from __future__ import annotations

import numpy as np

from mawdo.experiments.bbob.data import StudyRuns
from mawdo.experiments.bbob.measures import RANK_FLOOR, ecdf_curves, friedman_final


def final_ecdf(study: StudyRuns, dim: int) -> dict[str, float]:
    """Runtime-ECDF value at the whole budget per algorithm, in [0, 1] (all functions)."""
    x = np.array([study.budget])  # evaluations per dimension
    return {a: float(v[-1]) for a, v in ecdf_curves(study, dim, study.functions, x).items()}


def median_final(study: StudyRuns, algorithm: str, fid: int, dim: int) -> float:
    """Median over instances and runs of the final precision, floored at ``RANK_FLOOR``."""
    fin = [max(float(r.precision[-1]), RANK_FLOOR) for r in study.select(algorithm, fid, dim)]
    return float(np.median(fin)) if fin else float("nan")


def versus(study: StudyRuns, ref: str, other: str, dim: int) -> tuple[int, int, int]:
    """Functions where ``ref``'s median final precision is below / equal to / above ``other``'s."""
    wins = ties = losses = 0
    for fid in study.functions:
        a, b = median_final(study, ref, fid, dim), median_final(study, other, fid, dim)
        if np.isnan(a) or np.isnan(b):
            continue
        wins, ties, losses = wins + (a < b), ties + (a == b), losses + (a > b)
    return wins, ties, losses


def _solved(study: StudyRuns, algorithm: str, dim: int) -> tuple[int, int]:
    runs = study.select(algorithm=algorithm, dim=dim)
    hit = sum(1 for r in runs if r.evals.size and r.precision[-1] <= RANK_FLOOR)
    return hit, len(runs)


def headline(study: StudyRuns, reference: str = "mawdo", baseline: str = "random") -> list[str]:
    """One paragraph of plain sentences per dimension (Markdown), from the stored runs only.

    Parameters
    ----------
    study : StudyRuns
        The study, from :func:`mawdo.experiments.bbob.data.load_runs`.
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
            f"- D = {dim}: {reference} has Friedman mean rank {ranks[reference]:.2f} over "
            f"{fr.n_functions} (function, instance) blocks, place {place} of {len(ranks)}"
            f" (best: {min(ranks, key=ranks.get)} {min(ranks.values()):.2f})."
        )
        if baseline in study.algorithms and baseline != reference:
            w, t, lo = versus(study, reference, baseline, dim)
            hit, n = _solved(study, reference, dim)
            lines.append(
                f"- D = {dim}: {reference}'s median final precision is lower than {baseline}'s on "
                f"{w} of {w + t + lo} functions ({t} equal, {lo} higher); {hit} of its {n} runs "
                f"reach 1e-8."
            )
    return lines
