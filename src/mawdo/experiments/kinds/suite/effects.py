"""Component effects of a component study (:mod:`.components`): each switch against its base,
per function group of the suite (BBOB's five, CEC 2017's four), with bootstrap confidence
intervals over instances and runs.

A variant and its base share every seed (a run's seed depends on its problem and index only), so
the two are compared *paired*, unit by unit, a unit being an (instance, run) pair. Two measures:

- **ECDF area**: the area under a run's runtime ECDF over COCO's 51 targets ``1e2 .. 1e-8``,
  budgets on a log scale from ``D`` to the plan's budget, normalised to ``[0, 1]`` (1: every target
  at once; 0: none within the budget). For one run it is ``mean_t clip(1 - log(rt_t / D) /
  log(budget), 0, 1)``; averaged over runs it is the mean height of :func:`.metrics.runtime_ecdf`
  over ``log(evaluations / D)``. The effect is the variant's area minus its base's, in percentage
  points, averaged over the group's functions.
- **aRT ratio**: ``aRT(variant) / aRT(base)`` at the aRT tables' targets, geometric mean over the
  (function, target) cells of the group that both solve at least once; the cells only one of the
  two solves are counted beside it (``+gained/-lost``).

Confidence intervals: percentile bootstrap (95 %, 1000 samples, a fixed seed) resampling the units
with replacement, one resample shared by every function of a group (and by base and variant).
"""

from __future__ import annotations

import functools
import math
import warnings

import numpy as np

from mawdo.experiments.kinds.suite.components import parse_label
from mawdo.experiments.kinds.suite.data import StudyRuns, runtime_table
from mawdo.experiments.kinds.suite.measures import ART_TARGETS, groups
from mawdo.experiments.kinds.suite.metrics import aggregate_runtime, standard_targets
from mawdo.experiments.tables import Table
from mawdo.suites import SUITES

BOOTSTRAP = 1000
"""Bootstrap samples of the confidence intervals."""

BOOT_SEED = 29
"""Seed of the bootstrap resamples (a report is the same each time it is written)."""


def component_pairs(study: StudyRuns) -> list[tuple[str, str]]:
    """``(variant, base)`` for every component variant of the study whose base it also holds."""
    out = []
    for algo in study.algorithms:
        try:
            base, names = parse_label(algo)
        except ValueError:
            continue
        if names and base in study.algorithms:
            out.append((algo, base))
    return out


def run_area(rt: np.ndarray, dim: int, budget: float) -> np.ndarray:
    """Normalised area under each run's runtime ECDF (see the module docstring).

    Parameters
    ----------
    rt : numpy.ndarray
        Runtimes ``(..., T)`` in evaluations (``inf``: not reached).
    dim : int
        Dimension D.
    budget : float
        Evaluations per dimension of the plan (> 1).

    Returns
    -------
    numpy.ndarray
        Shape ``rt.shape[:-1]``, in ``[0, 1]``.
    """
    with np.errstate(divide="ignore"):
        frac = 1.0 - np.log(np.asarray(rt, float) / dim) / math.log(budget)
    return np.clip(frac, 0.0, 1.0).mean(axis=-1)


def unit_runtimes(study: StudyRuns, algo: str, fid: int, dim: int, targets, units):
    """``(rt (U, T), spent (U,))`` of ``algo`` on ``fid`` at ``dim``, rows in ``units`` order.

    Raises ``ValueError`` when a unit (instance, run) has no stored run (an unfinished study).
    """
    return runtime_table(unit_runs(study, algo, fid, dim, units), targets)


def unit_runs(study: StudyRuns, algo: str, fid: int, dim: int, units) -> list:
    """The stored runs of ``algo`` on ``fid`` at ``dim``, one per unit, in ``units`` order.

    Raises ``ValueError`` when a unit (instance, run) has no stored run (an unfinished study).
    """
    runs = {(r.instance, r.run): r for r in study.select(algo, fid, dim)}
    missing = [u for u in units if u not in runs]
    if missing:
        raise ValueError(
            f"{algo} has no stored run for instance {missing[0][0]}, run {missing[0][1]} of "
            f"f{fid} at D = {dim}: finish the study (mawdo study run resumes it) first"
        )
    return [runs[u] for u in units]


def _units(study: StudyRuns, base: str, dim: int) -> list[tuple[int, int]]:
    return sorted({(r.instance, r.run) for r in study.select(base, study.functions[0], dim)})


def _ci(samples: np.ndarray) -> tuple[float, float]:
    lo, hi = np.nanpercentile(samples, [2.5, 97.5])
    return float(lo), float(hi)


class EffectData:
    """Per-unit measures of the algorithms of one dimension, computed once for all tables; the
    units are the (instance, run) pairs of ``unit_source`` (default: the first algorithm)."""

    def __init__(self, study: StudyRuns, dim: int, algorithms, unit_source: str | None = None):
        self.study, self.dim = study, dim
        self.units = _units(study, unit_source or algorithms[0], dim)
        rng = np.random.default_rng(BOOT_SEED)
        self.idx = rng.integers(0, len(self.units), (BOOTSTRAP, len(self.units)))
        ecdf_t = standard_targets()
        self.area: dict[tuple[str, int], np.ndarray] = {}
        self.rt: dict[tuple[str, int], tuple[np.ndarray, np.ndarray]] = {}
        for algo in algorithms:
            for fid in study.functions:
                rt, _ = unit_runtimes(study, algo, fid, dim, ecdf_t, self.units)
                self.area[algo, fid] = run_area(rt, dim, study.budget)
                self.rt[algo, fid] = unit_runtimes(study, algo, fid, dim, ART_TARGETS, self.units)

    def area_effect(self, variant: str, base: str, fids) -> tuple[float, float, float]:
        """Mean area difference (percentage points) and its CI over the functions ``fids``."""
        d = np.mean([self.area[variant, f] - self.area[base, f] for f in fids], axis=0) * 100
        return self.interval(d)

    def interval(self, d: np.ndarray) -> tuple[float, float, float]:
        """Mean of the per-unit values ``d`` ``(U,)`` and its bootstrap 95 % interval."""
        return float(d.mean()), *_ci(d[self.idx].mean(axis=1))

    def art_ratio(self, variant: str, base: str, fids) -> tuple[float, float, float, int, int, int]:
        """Geometric-mean aRT ratio, its CI, and the cells counted, gained and lost."""
        logs, boots, gained, lost = [], [], 0, 0
        for f in fids:
            (rv, sv), (rb, sb) = self.rt[variant, f], self.rt[base, f]
            av, ab = aggregate_runtime(rv, sv), aggregate_runtime(rb, sb)
            both = np.isfinite(av) & np.isfinite(ab)
            gained += int(np.sum(np.isfinite(av) & ~np.isfinite(ab)))
            lost += int(np.sum(~np.isfinite(av) & np.isfinite(ab)))
            logs.append(np.log10(av[both] / ab[both]))
            bv = aggregate_runtime(rv[self.idx], sv[self.idx])[:, both]  # (B, cells)
            bb = aggregate_runtime(rb[self.idx], sb[self.idx])[:, both]
            with np.errstate(invalid="ignore", divide="ignore"):
                boots.append(np.log10(bv / bb))  # inf/inf or x/inf in a sample: dropped below
        cells = np.concatenate(logs)
        if cells.size == 0:
            return math.nan, math.nan, math.nan, 0, gained, lost
        b = np.concatenate(boots, axis=1)
        b = np.where(np.isfinite(b), b, np.nan)
        with warnings.catch_warnings():  # a sample whose cells all went unsolved: NaN, skipped
            warnings.simplefilter("ignore", RuntimeWarning)
            samples = np.nanmean(b, axis=1)
        lo, hi = _ci(samples)
        return 10 ** cells.mean(), 10**lo, 10**hi, int(cells.size), gained, lost


def _fmt_area(v: tuple[float, float, float]) -> str:
    return f"{v[0]:+.1f} [{v[1]:+.1f}, {v[2]:+.1f}]"


def _fmt_art(v) -> str:
    if v[3] == 0:
        return f"- (0; +{v[4]}/-{v[5]})"
    return f"x{v[0]:.2f} [{v[1]:.2f}, {v[2]:.2f}] ({v[3]}; +{v[4]}/-{v[5]})"


def effect_tables(study: StudyRuns, dim: int) -> list[Table]:
    """The effect tables of one dimension: ECDF-area effects, aRT ratios, the bases' own areas
    and, for pairs of switches, the interaction (pair effect minus the two single effects).
    Empty when the study holds no component variant beside its base."""
    pairs = component_pairs(study)
    if not pairs:
        return []
    variants = {v for v, _ in pairs}
    # the bases and every other algorithm of the study (references such as cmaes, random)
    levels = [a for a in study.algorithms if a not in variants]
    data = EffectData(study, dim, [*levels, *(v for v, _ in pairs)], unit_source=pairs[0][1])
    grp = groups(study)
    cols = list(grp)
    note = (
        f"Bootstrap 95 % CI over {len(data.units)} (instance, run) units, {BOOTSTRAP} "
        "resamples; the variant shares every seed with its base."
    )
    head = f"{study.suite} D={dim}: "
    area_rows = [[v, b, *(_fmt_area(data.area_effect(v, b, f)) for f in grp.values())]
                 for v, b in pairs]  # fmt: skip
    art_rows = [[v, b, *(_fmt_art(data.art_ratio(v, b, f)) for f in grp.values())]
                for v, b in pairs]  # fmt: skip
    targets = ", ".join(f"{t:g}" for t in ART_TARGETS)
    tables = [
        Table(
            name=f"effects_area_d{dim}",
            title=head + "effect of each component switch on the ECDF area (percentage "
            "points, variant - base; > 0: the switch helps)",
            columns=["variant", "base", *cols],
            rows=area_rows,
            notes=[note, "ECDF area: 51 targets 1e2..1e-8, log budget from D to the budget."],
        ),
        Table(
            name=f"effects_art_d{dim}",
            title=head + "aRT(variant) / aRT(base), geometric mean over the (function, target) "
            "cells both solve (< 1: the switch helps)",
            columns=["variant", "base", *cols],
            rows=art_rows,
            notes=[
                note,
                f"Targets {targets}; (cells; +solved only by the variant/-only by the base).",
            ],  # fmt: skip
        ),
        _bases_table(data, levels, grp, head, f"effects_bases_d{dim}"),
        _centre_table(study, dim, [*levels, *(v for v, _ in pairs)], grp, head),
    ]
    inter = _interaction_rows(data, pairs, grp)
    if inter:
        tables.append(
            Table(
                name=f"effects_pairs_d{dim}",
                title=head + "interaction of two switches on the ECDF area (pair effect - sum "
                "of the single effects, percentage points)",
                columns=["pair", *cols],
                rows=inter,
                notes=[note],
            )
        )
    return tables


def _bases_table(data: EffectData, levels, grp, head: str, name: str) -> Table:
    rows = [
        [a, *(100 * np.mean([data.area[a, f].mean() for f in fids]) for fids in grp.values())]
        for a in levels
    ]
    return Table(
        name=name,
        title=head + "ECDF area of the bases and the other algorithms (percent)",
        columns=["algorithm", *grp],
        rows=rows,
        formats=dict.fromkeys(grp, ".1f"),
    )


def centre_pull(study: StudyRuns, algo: str, fids, dim: int) -> float:
    """Median over the runs of ``algo`` on ``fids`` of ``best_x . x* / |x*|^2``: where the final
    best point lies along the line from the box centre (0) to the optimum ``x*`` (1)."""
    vals = []
    for fid in fids:
        for r in study.select(algo, fid, dim):
            x_star = _optimum(study.suite, fid, r.instance, dim)
            vals.append(float(r.best_x @ x_star / (x_star @ x_star)))
    return float(np.median(vals)) if vals else math.nan


@functools.cache
def _optimum(suite: str, fid: int, iid: int, dim: int) -> np.ndarray:
    return np.asarray(SUITES[suite].build(fid, iid, dim).x_star, dtype=float)


def _centre_table(study: StudyRuns, dim: int, algorithms, grp, head: str) -> Table:
    rows = [[a, *(centre_pull(study, a, fids, dim) for fids in grp.values())] for a in algorithms]
    return Table(
        name=f"effects_centre_d{dim}",
        title=head + "where the final best point lies: median of best_x . x* / |x*|^2 (1: at "
        "the optimum x*, 0: at the centre of the box)",
        columns=["algorithm", *grp],
        rows=rows,
        notes=["A diagnostic of the pull toward the box centre (gravity); no interval."],
        formats=dict.fromkeys(grp, ".2f"),
    )


def _interaction_rows(data: EffectData, pairs, grp) -> list[list]:
    have = {v for v, _ in pairs}
    rows = []
    for v, b in pairs:
        _, names = parse_label(v)
        singles = [f"{b}-{n}" for n in names]
        if len(names) != 2 or not all(s in have for s in singles):
            continue
        cells = []
        for fids in grp.values():
            d = np.mean(
                [
                    data.area[v, f] - data.area[singles[0], f] - data.area[singles[1], f]
                    + data.area[b, f]
                    for f in fids
                ],
                axis=0,
            ) * 100  # fmt: skip
            cells.append(_fmt_area((float(d.mean()), *_ci(d[data.idx].mean(axis=1)))))
        rows.append([v, *cells])
    return rows
