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


def log_floor(values) -> tuple[float, bool]:
    """Where a log axis draws values <= 0, and whether any value needs it.

    The floor is one decade under the smallest positive finite value of ``values`` (1.0 when
    there is none): an error that is exactly 0 stays visible beside the others without
    stretching the axis down to 1e-300.

    Parameters
    ----------
    values : sequence of numpy.ndarray
        The data drawn on one axis.

    Returns
    -------
    floor : float
    clipped : bool
        True when some value is <= 0 and is drawn at the floor (say so on the figure).
    """
    pos = [v[(v > 0) & np.isfinite(v)] for v in values if v.size]
    pos = [p for p in pos if p.size]
    smallest = min(float(p.min()) for p in pos) if pos else 1.0
    clipped = any(bool(np.any(v <= 0)) for v in values if v.size)
    return smallest / 10.0, clipped


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
    curves = {}
    for label, res in results.items():
        h = np.asarray(res.history, float)
        curves[label] = h - res.f_star if error and res.f_star is not None else h
    any_res = next(iter(results.values()))
    errors = error and any_res.f_star is not None
    # errors are >= 0 and drawn on a log axis, exact zeros at a floor the label names; raw
    # values that reach 0 or below are drawn on a linear axis
    log = errors or all(np.nanmin(h) > 0 for h in curves.values())
    floor, clipped = log_floor(list(curves.values())) if log else (None, False)
    for label, h in curves.items():
        band(ax, h, label, log=log, floor=floor)
    ylabel = "best-so-far error f - f*" if errors else "best f"
    if clipped:
        ylabel += f" (0 drawn at {floor:.0e})"
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
