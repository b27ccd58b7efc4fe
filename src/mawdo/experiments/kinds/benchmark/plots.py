"""Figures of a sweep, drawn from the results store only (docs/deviations.md#d-protocol).

* Convergence: per function one panel, per algorithm the median best-so-far error
  ``f - f*`` over runs with the interquartile band, log y. The x axis is the iteration, or the
  evaluations spent for ``budget="evals"`` plans.
* Box plots: per function one panel, the final errors of each algorithm, log y.

Errors that are exactly 0 (or a rounding hair below) cannot sit on a log axis; they are drawn at
a floor one decade under the panel's smallest positive value, and the panel says so.

This is the only module of ``mawdo.experiments`` that imports matplotlib. It draws on
``matplotlib.figure.Figure`` with the Agg canvas directly, so it neither needs a display nor
changes the pyplot backend of the caller's session.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from pathlib import Path

import numpy as np
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure

from mawdo.experiments.kinds.benchmark.data import curves as read_curves
from mawdo.experiments.kinds.benchmark.data import finals as read_finals
from mawdo.experiments.kinds.benchmark.labels import function_label, label
from mawdo.experiments.store import Store
from mawdo.viz import band
from mawdo.viz import log_floor as _floor

NCOLS = 4
DPI = 110


def _grid(n: int) -> tuple[Figure, list]:
    ncols = min(NCOLS, n)
    nrows = math.ceil(n / ncols)
    fig = Figure(figsize=(4.2 * ncols, 3.2 * nrows), dpi=DPI, layout="constrained")
    FigureCanvasAgg(fig)
    axes = fig.subplots(nrows, ncols, squeeze=False).ravel().tolist()
    for ax in axes[n:]:
        ax.set_visible(False)
    return fig, axes[:n]


def _save(fig: Figure, stem: Path, formats: Sequence[str]) -> list[Path]:
    out = []
    for ext in formats:
        p = stem.with_suffix(f".{ext}")
        fig.savefig(p, format=ext)
        out.append(p)
    return out


def _colours(algorithms: Sequence[str]) -> dict[str, str]:
    cycle = [f"C{i}" for i in range(10)]
    return {a: cycle[i % 10] for i, a in enumerate(algorithms)}


def convergence_figure(
    store: Store, stem: str | Path, formats: Sequence[str] = ("png",)
) -> list[Path]:
    """Median best-so-far error with interquartile band, one panel per function.

    Parameters
    ----------
    store : Store
        An open store (read-only is enough).
    stem : str or Path
        Output path without suffix.
    formats : sequence of str
        ``"png"``, ``"svg"``, ...

    Returns
    -------
    list of Path
        Files written.
    """
    plan = store.plan
    colours = _colours(plan.algorithms)
    fig, axes = _grid(len(plan.functions))
    by_evals = plan.budget == "evals"
    for ax, fn in zip(axes, plan.functions, strict=True):
        series = []
        for algo in plan.algorithms:
            curve, nfev, f_star = read_curves(store, algo, fn)
            if curve.size == 0:
                continue
            err = curve - (0.0 if math.isnan(f_star) else f_star)
            x = np.median(nfev, axis=0) if by_evals else np.arange(1, err.shape[1] + 1)
            series.append((algo, x, err))
        floor, clipped = _floor([s[2] for s in series])
        for algo, x, err in series:
            band(ax, err, label(algo), x=x, color=colours[algo], floor=floor, lw=1.2)
        ax.set_yscale("log")
        ax.set_title(
            f"{function_label(fn)} ({fn})" + (" [0 drawn at floor]" if clipped else ""), fontsize=9
        )
        ax.set_xlabel("evaluations" if by_evals else "iteration", fontsize=8)
        ax.set_ylabel("best-so-far f - f*", fontsize=8)
        ax.tick_params(labelsize=7)
    if axes:
        handles, names = axes[0].get_legend_handles_labels()
        fig.legend(
            handles, names, loc="outside lower center", ncols=min(6, max(1, len(names))), fontsize=8
        )
    fig.suptitle(f"{plan.name}: median and interquartile range over runs", fontsize=11)
    return _save(fig, Path(stem), formats)


def boxplot_figure(store: Store, stem: str | Path, formats: Sequence[str] = ("png",)) -> list[Path]:
    """Box plots of the final errors ``f - f*``, one panel per function."""
    plan = store.plan
    finals = read_finals(store)
    colours = _colours(plan.algorithms)
    fig, axes = _grid(len(plan.functions))
    for ax, fn in zip(axes, plan.functions, strict=True):
        algos = [a for a in plan.algorithms if (a, fn) in finals and finals[a, fn]["error"].size]
        data = [finals[a, fn]["error"][np.isfinite(finals[a, fn]["error"])] for a in algos]
        floor, clipped = _floor(data)
        shown = [np.maximum(d, floor) if d.size else np.array([floor]) for d in data]
        if shown:
            bp = ax.boxplot(shown, patch_artist=True, widths=0.6)
            for patch, a in zip(bp["boxes"], algos, strict=True):
                patch.set_facecolor(colours[a])
                patch.set_alpha(0.5)
            ax.set_xticks(
                range(1, len(algos) + 1),
                [label(a).replace(" (reconstructed)", "*") for a in algos],
                rotation=45,
                ha="right",
                fontsize=7,
            )
        ax.set_yscale("log")
        ax.set_title(
            f"{function_label(fn)} ({fn})" + (" [0 drawn at floor]" if clipped else ""), fontsize=9
        )
        ax.set_ylabel("final f - f*", fontsize=8)
        ax.tick_params(axis="y", labelsize=7)
    fig.suptitle(f"{plan.name}: final errors over runs (* reconstructed)", fontsize=11)
    return _save(fig, Path(stem), formats)
