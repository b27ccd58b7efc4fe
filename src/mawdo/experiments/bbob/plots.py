"""Figures of a suite study, drawn from the store only: runtime ECDFs (per dimension, per
function group) and convergence against evaluations.

Drawn on ``matplotlib.figure.Figure`` with the Agg canvas, so no display is needed and the
caller's pyplot backend is untouched.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure
from matplotlib.ticker import NullFormatter

from mawdo.experiments.bbob.data import StudyRuns, precision_at
from mawdo.experiments.bbob.measures import ecdf_curves, groups

DPI = 110
PRECISION_FLOOR = 1e-9
"""Convergence panels draw precisions below this at it (runs stop at 1e-8)."""


def _figure(n: int, ncols: int, w: float = 4.0, h: float = 3.0, layout="constrained"):
    ncols = min(ncols, n)
    nrows = math.ceil(n / ncols)
    fig = Figure(figsize=(w * ncols, h * nrows), dpi=DPI, layout=layout)
    FigureCanvasAgg(fig)
    axes = fig.subplots(nrows, ncols, squeeze=False).ravel().tolist()
    for ax in axes[n:]:
        ax.set_visible(False)
    return fig, axes[:n]


def _colors(algorithms) -> dict[str, tuple]:
    from matplotlib import colormaps

    cmap = colormaps["tab10"]
    return {a: cmap(i % 10) for i, a in enumerate(algorithms)}


def _save(fig: Figure, path: Path, svg: bool) -> list[Path]:
    out = [path.with_suffix(".png")]
    fig.savefig(out[0])
    if svg:
        out.append(path.with_suffix(".svg"))
        fig.savefig(out[1])
    return out


def _ids(fids) -> str:
    """``(1, 2, 3, 4, 5)`` -> ``"f1-f5"``; otherwise ``"f1, f8, f15"``."""
    fids = tuple(fids)
    if len(fids) > 2 and fids == tuple(range(fids[0], fids[-1] + 1)):
        return f"f{fids[0]}-f{fids[-1]}"
    return ", ".join(f"f{f}" for f in fids)


def plot_ecdfs(study: StudyRuns, dim: int, out_dir: Path, svg: bool = False) -> list[Path]:
    """One panel per function group (the first: all functions): fraction of (function, run,
    target) triples solved against evaluations / D, log x, 51 targets ``1e2 .. 1e-8``."""
    grp = groups(study)
    x = np.logspace(0, math.log10(study.budget), 200)
    fig, axes = _figure(len(grp), 3)
    colors = _colors(study.algorithms)
    for ax, (name, fids) in zip(axes, grp.items(), strict=True):
        for algo, y in ecdf_curves(study, dim, fids, x).items():
            ax.step(x, y, where="post", color=colors[algo], label=algo, lw=1.6)
        ax.set_xscale("log")
        ax.set_ylim(-0.02, 1.02)
        ax.set_xlim(1, study.budget)
        ax.grid(True, alpha=0.3)
        ax.set_title(f"{name} ({_ids(fids)})", fontsize=9)
        ax.set_xlabel("evaluations / D")
        ax.set_ylabel("fraction of (function, run, target)")
    axes[0].legend(fontsize=8, loc="upper left")
    fig.suptitle(f"{study.suite} D={dim}: runtime ECDFs, targets 1e2 .. 1e-8 (51)")
    return _save(fig, out_dir / f"ecdf_d{dim}", svg)


def plot_convergence(study: StudyRuns, dim: int, out_dir: Path, svg: bool = False) -> list[Path]:
    """One panel per function: median precision ``f - f_opt`` over instances and runs (IQR
    band) against evaluations / D, log-log; below 1e-9 drawn at 1e-9."""
    top = math.ceil(study.budget * dim - 1e-9)
    budgets = np.unique(np.round(np.logspace(0, math.log10(top), 120)))
    # a fixed layout (constrained layout measures every tick label of 24 log panels: slow),
    # with margins in inches so that one row of panels gets the same room as four
    fig, axes = _figure(len(study.functions), 6, 3.0, 2.4, layout=None)
    w, h = fig.get_size_inches()
    fig.set_size_inches(w + 0.6, h + 0.9)
    fig.subplots_adjust(
        left=0.9 / (w + 0.6),
        right=1 - 0.1 / (w + 0.6),
        bottom=0.55 / (h + 0.9),
        top=1 - 0.6 / (h + 0.9),
        wspace=0.3,
        hspace=0.45,
    )
    colors = _colors(study.algorithms)
    for ax, fid in zip(axes, study.functions, strict=True):
        name = ""
        for algo in study.algorithms:
            runs = study.select(algo, fid, dim)
            if not runs:
                continue
            name = runs[0].function_name
            p = np.maximum(precision_at(runs, budgets), PRECISION_FLOOR)
            lo, med, hi = np.percentile(p, [25, 50, 75], axis=0)
            ax.plot(budgets / dim, med, color=colors[algo], label=algo, lw=1.3)
            ax.fill_between(budgets / dim, lo, hi, color=colors[algo], alpha=0.15, lw=0)
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.yaxis.set_minor_formatter(NullFormatter())  # decade labels only: panels are small
        ax.set_title(f"f{fid} {name}", fontsize=8)
        ax.tick_params(labelsize=7)
        ax.grid(True, alpha=0.3)
    axes[0].legend(fontsize=6)
    fig.supxlabel("evaluations / D")
    fig.supylabel("median f - f_opt (IQR band)", x=0.15 / fig.get_size_inches()[0])
    fig.suptitle(f"{study.suite} D={dim}: best-so-far against evaluations")
    return _save(fig, out_dir / f"convergence_d{dim}", svg)
