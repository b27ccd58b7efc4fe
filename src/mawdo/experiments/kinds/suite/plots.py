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

from mawdo.experiments.kinds.suite.data import StudyRuns, precision_at
from mawdo.experiments.kinds.suite.measures import ecdf_curves, groups
from mawdo.experiments.kinds.suite.summary import function_list

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


#: Dash patterns beside the colours: any two of up to 10 algorithms differ in colour, dash
#: pattern and marker, so curves that overlap (or print in grey) stay apart.
_DASHES = (
    "-",
    (0, (5, 2)),
    (0, (1, 1.5)),
    (0, (6, 2, 1, 2)),
    (0, (2, 2)),
    (0, (8, 2, 1, 2, 1, 2)),
    (0, (10, 3)),
    (0, (3, 1, 1, 1)),
    (0, (1, 3)),
    (0, (4, 1, 4, 1, 1, 1)),
)
_MARKERS = ("o", "s", "^", "v", "D", "x", "+", "*", "P", "<")
# the second ten: other markers, and the two darkest shades of tab20b's five hues
_MORE_MARKERS = ("h", "p", "d", ">", "X", "8", "1", "2", "3", "4")
_MORE_SHADES = (0, 4, 8, 12, 16, 1, 5, 9, 13, 17)


def styles(algorithms) -> dict[str, dict]:
    """Matplotlib line keywords per algorithm: a colour, a dash pattern and a marker.

    Parameters
    ----------
    algorithms : sequence of str
        In the study's order; the first 10 get tab10's colours with their own dash patterns
        and markers, the next 10 tab20b's darker shades with ten more markers and the dash
        patterns shifted by three, so any two of the first 20 differ in colour and marker
        (and the first 10 look as they did before there could be more).

    Returns
    -------
    dict
        ``{algorithm: {"color", "ls", "marker"}}``; markers are drawn sparsely by the callers.
    """
    from matplotlib import colormaps

    first, more = colormaps["tab10"], colormaps["tab20b"]
    out = {}
    for i, a in enumerate(algorithms):
        k = i % 20
        if k < 10:
            out[a] = {"color": first(k), "ls": _DASHES[k], "marker": _MARKERS[k]}
        else:
            j = k - 10
            out[a] = {"color": more(_MORE_SHADES[j]), "ls": _DASHES[(j + 3) % 10],
                      "marker": _MORE_MARKERS[j]}  # fmt: skip
    return out


def _marks(i: int, curves: int, points: int, count: int) -> tuple[int, int]:
    """``markevery`` of curve ``i`` of ``curves`` with ``points`` points: about ``count``
    markers, shifted from curve to curve so that overlapping curves show every marker."""
    step = max(points // count, 1)
    return (i * step // max(curves, 1), step)


def _save(fig: Figure, path: Path, svg: bool) -> list[Path]:
    out = [path.with_suffix(".png")]
    fig.savefig(out[0])
    if svg:
        out.append(path.with_suffix(".svg"))
        fig.savefig(out[1])
    return out


def plot_ecdfs(
    study: StudyRuns, dim: int, out_dir: Path, svg: bool = False, top: float = 1.0, stem=None
) -> list[Path]:
    """One panel per function group (the first: all functions): fraction of (function, run,
    target) triples solved against evaluations / D, log x, 51 targets ``1e2 .. 1e-8``; the y
    axis up to ``top`` (< 1 zooms in on weak algorithms), saved as ``stem`` (default
    ``ecdf_d{D}``)."""
    grp = groups(study)
    x = np.logspace(0, math.log10(study.budget), 200)
    fig, axes = _figure(len(grp), 3)
    look = styles(study.algorithms)
    for ax, (name, fids) in zip(axes, grp.items(), strict=True):
        for i, (algo, y) in enumerate(ecdf_curves(study, dim, fids, x).items()):
            ax.step(
                x,
                y,
                where="post",
                label=algo,
                lw=1.6,
                ms=4,
                markevery=_marks(i, len(look), x.size, 8),
                **look[algo],
            )
        ax.set_xscale("log")
        ax.set_ylim(-0.02 * top, 1.02 * top)
        ax.set_xlim(1, study.budget)
        ax.grid(True, alpha=0.3)
        ax.set_title(f"{name} ({function_list(fids)})", fontsize=9)
        ax.set_xlabel("evaluations / D")
        ax.set_ylabel("fraction of (function, run, target)")
    handles = axes[0].get_legend_handles_labels()
    spare = fig.axes[len(axes)] if len(fig.axes) > len(axes) else None
    if spare is not None:  # an empty slot of the grid: the legend there covers no curve
        spare.set_visible(True)
        spare.axis("off")
        spare.legend(*handles, fontsize=9, loc="center")
    else:
        axes[0].legend(fontsize=8, loc="upper left")
    cut = f"; y axis cut at {top:g}" if top < 1 else ""
    # one panel (a suite without function groups) is too narrow for the title on one line
    sep = "\n" if len(grp) == 1 else ", "
    fig.suptitle(f"{study.suite} D={dim}: runtime ECDFs{sep}targets 1e2 .. 1e-8 (51){cut}")
    return _save(fig, out_dir / (stem or f"ecdf_d{dim}"), svg)


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
    look = styles(study.algorithms)
    for ax, fid in zip(axes, study.functions, strict=True):
        name = ""
        for i, algo in enumerate(study.algorithms):
            runs = study.select(algo, fid, dim)
            if not runs:
                continue
            name = runs[0].function_name
            p = np.maximum(precision_at(runs, budgets), PRECISION_FLOOR)
            lo, med, hi = np.percentile(p, [25, 50, 75], axis=0)
            marks = _marks(i, len(look), budgets.size, 6)
            ax.plot(budgets / dim, med, label=algo, lw=1.3, ms=3, markevery=marks, **look[algo])
            ax.fill_between(budgets / dim, lo, hi, color=look[algo]["color"], alpha=0.15, lw=0)
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
