"""Plots across runs: the first plan's cost convergence (paper Fig. 3) and metric box plots."""

from __future__ import annotations

from collections.abc import Mapping
from pathlib import Path

import numpy as np

from mawdo.planning.render.style import (
    IMAGE_SUFFIXES,
    checked_output_path,
    display_name,
    new_figure,
    save_figure,
)


def as_runs(curves, label: str) -> np.ndarray:
    """A ``(runs, iterations)`` array; 1-D rows of unequal length are padded with their last value
    (a best-so-far curve stays flat after it stops)."""
    if isinstance(curves, np.ndarray) and curves.ndim == 2:
        arr = curves.astype(float)
    else:
        rows = [np.asarray(c, dtype=float).ravel() for c in curves]
        if not rows or any(r.size == 0 for r in rows):
            raise ValueError(f"curves[{label!r}] has no runs or an empty run")
        n = max(r.size for r in rows)
        arr = np.vstack([np.pad(r, (0, n - r.size), mode="edge") for r in rows])
    if arr.ndim != 2 or arr.size == 0:
        raise ValueError(f"curves[{label!r}] must be a non-empty (runs, iterations) array")
    return arr


def plain_log_labels(ax, values: np.ndarray) -> None:
    """Plain numbers (``225``, not ``2.25 x 10^2``) on a log axis spanning less than a decade."""
    from matplotlib.ticker import FuncFormatter

    v = values[np.isfinite(values) & (values > 0)]
    if v.size and v.max() / v.min() < 10.0:
        fmt = FuncFormatter(lambda y, _: f"{y:g}")
        ax.yaxis.set_major_formatter(fmt)
        ax.yaxis.set_minor_formatter(fmt)


def plot_cost_convergence(
    curves: Mapping[str, object], path, log: bool = True, title: str | None = None
) -> Path:
    """First-plan convergence per algorithm: median best cost with its IQR band (paper Fig. 3).

    Parameters
    ----------
    curves : dict label -> array_like, shape (runs, iterations)
        Best cost per iteration of each run's first plan (``result.replans[0].history``); rows of
        unequal length are padded with their last value.
    path : str or Path
        Output image (``.png``, ``.svg`` or ``.pdf``).
    log : bool
        Logarithmic cost axis (switched off if some cost is <= 0).

    Returns
    -------
    Path
        The written file.
    """
    from mawdo.viz import band

    if not isinstance(curves, Mapping) or not curves:
        raise ValueError("no curves to plot: pass a dict label -> (runs, iterations) array")
    data = {str(k): as_runs(v, str(k)) for k, v in curves.items()}
    out = checked_output_path(path, IMAGE_SUFFIXES)
    if log and any(np.nanmin(a) <= 0 for a in data.values()):
        log = False
    fig = new_figure((6.4, 4.2), 120)
    ax = fig.add_subplot()
    for key, arr in data.items():
        band(ax, arr, f"{display_name(key)} (n = {arr.shape[0]})", log=log)
    ax.set_xlabel("iteration")
    ax.set_ylabel("best cost C" + (" (log scale)" if log else ""))
    ax.set_title(title or "First plan: median best cost and IQR over runs", fontsize=10)
    ax.grid(True, which="both", alpha=0.3)
    if log:
        plain_log_labels(ax, np.concatenate([a.ravel() for a in data.values()]))
    ax.legend(fontsize=8)
    return save_figure(fig, out)


def plot_metric_boxes(
    values: Mapping[str, object], path, metric_label: str, title: str | None = None
) -> Path:
    """Box plots of one metric across algorithms, with the individual runs as dots.

    Parameters
    ----------
    values : dict label -> 1-D array_like
        The metric per run; NaN (e.g. the gap of a failed run) is left out and the count shown.
    path : str or Path
        Output image (``.png``, ``.svg`` or ``.pdf``).
    metric_label : str
        Axis label, with units (``"path length (px)"``).

    Returns
    -------
    Path
        The written file.
    """
    if not isinstance(values, Mapping) or not values:
        raise ValueError("no values to plot: pass a dict label -> 1-D array of the metric")
    data, ticks = [], []
    for key, v in values.items():
        arr = np.asarray(v, dtype=float)
        if arr.ndim > 1:
            raise ValueError(f"values[{key!r}] must be 1-D, got shape {arr.shape}")
        arr = arr.ravel()
        kept = arr[np.isfinite(arr)]
        data.append(kept)
        ticks.append(f"{display_name(key)}\n(n = {kept.size}/{arr.size})")
    if not any(d.size for d in data):
        raise ValueError(f"no finite values of {metric_label!r} to plot")
    out = checked_output_path(path, IMAGE_SUFFIXES)
    fig = new_figure((max(4.0, 1.1 * len(data) + 1.5), 4.2), 120)
    ax = fig.add_subplot()
    pos = np.arange(1, len(data) + 1)
    shown = [d if d.size else np.array([np.nan]) for d in data]
    ax.boxplot(
        shown,
        positions=pos,
        widths=0.55,
        showfliers=False,
        medianprops={"color": "tab:red", "lw": 1.5},
    )
    rng = np.random.default_rng(0)  # fixed jitter: the same data give the same image
    for p, d in zip(pos, data, strict=True):
        ax.plot(p + rng.uniform(-0.12, 0.12, d.size), d, "o", ms=3, alpha=0.5, color="tab:blue")
    ax.set_xticks(pos, ticks, fontsize=8, rotation=30 if len(data) > 5 else 0)
    ax.set_ylabel(metric_label)
    if title:
        ax.set_title(title, fontsize=10)
    ax.grid(True, axis="y", alpha=0.3)
    return save_figure(fig, out)
