"""Figures for optimizer results (the only core module that imports matplotlib)."""

from __future__ import annotations

from collections.abc import Mapping
from pathlib import Path

import numpy as np


def _pyplot():
    import matplotlib

    if matplotlib.get_backend().lower() not in ("agg", "pdf", "svg", "cairo"):
        matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


def band(
    ax,
    curves: np.ndarray,
    label: str,
    x: np.ndarray | None = None,
    log: bool = True,
    color=None,
    floor: float | None = None,
    lw: float = 1.6,
):
    """Draw the median of ``curves`` (``(R, T)``) with its interquartile band on ``ax``.

    On a log axis, values below ``floor`` (default: the smallest positive float) are drawn at
    the floor, so runs that reached the optimum exactly stay visible.
    """
    c = np.asarray(curves, float)
    x = np.arange(1, c.shape[1] + 1) if x is None else x
    q1, med, q3 = np.percentile(c, [25, 50, 75], axis=0)
    if log:
        lo = np.finfo(float).tiny if floor is None else floor
        q1, med, q3 = (np.maximum(q, lo) for q in (q1, med, q3))
    (line,) = ax.plot(x, med, label=label, color=color, lw=lw)
    ax.fill_between(x, q1, q3, color=line.get_color(), alpha=0.2, lw=0)
    if log:
        ax.set_yscale("log")
    return line


def plot_convergence(
    results: Mapping[str, object], path: str | Path, title: str = "", error: bool = True
) -> Path:
    """Convergence of several algorithms on one problem: median best-so-far and IQR band.

    Parameters
    ----------
    results : mapping of label -> OptimizeResult
        One batch of runs per algorithm.
    path : str or Path
        Output image (PNG or SVG, from the suffix).
    error : bool
        Plot ``f - f*`` when the optimum is known (log scale), else raw values.
    """
    plt = _pyplot()
    fig, ax = plt.subplots(figsize=(6.4, 4.2), dpi=120)
    log = True
    for label, res in results.items():
        h = res.history
        if error and res.f_star is not None:
            h = h - res.f_star
        elif np.nanmin(h) <= 0:
            log = False
        band(ax, h, label, log=log)
    any_res = next(iter(results.values()))
    ylabel = "best-so-far error f - f*" if error and any_res.f_star is not None else "best f"
    ax.set_xlabel("iteration")
    ax.set_ylabel(ylabel)
    ax.set_title(title or f"{any_res.problem}: median and IQR over {any_res.runs} runs")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(path)
    plt.close(fig)
    return path
