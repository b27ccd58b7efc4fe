"""The snapshot grid (paper Fig. 2): per algorithm a row of map panels over time."""

from __future__ import annotations

from collections.abc import Mapping
from pathlib import Path

import numpy as np

from mawdo.planning.render.style import (
    GRID_DPI,
    IMAGE_SUFFIXES,
    PANEL_IN,
    as_results,
    checked_output_path,
    display_name,
    new_figure,
    optimum_path,
    route_of,
    save_figure,
)
from mawdo.planning.render.world import draw_world, legend_handles
from mawdo.planning.result import PlanResult

#: Printed under the legend of every snapshot grid. A panel freezes the obstacles at its time
#: while the lines span other times, so a plan drawn across an obstacle is not a collision.
TIME_NOTE = (
    "Each panel draws the obstacles where they are at its time t, while the lines cover all "
    "times: the executed path the times up to t, the current plan the times from t on, and the "
    "optimum avoids the static obstacles only."
)


def run_headline(label: str, result: PlanResult, metrics: dict | None) -> str:
    parts = [f"{label}  (seed {result.seed})"]
    if metrics:
        if "length_px" in metrics:
            parts.append(f"length {metrics['length_px']:.1f} px")
        if "gap" in metrics:
            gap = metrics["gap"]
            parts.append(f"gap L/L* {gap:.3f}" if np.isfinite(gap) else "gap n/a")
        if "smoothness_rad" in metrics:
            parts.append(f"smoothness {metrics['smoothness_rad']:.2f} rad")
    if not result.success:
        parts.append(f"goal not reached: {result.reason}")
    return "  |  ".join(parts)


def default_times(result: PlanResult, n: int) -> np.ndarray:
    """``n`` integer times spread evenly from 0 to the end of the run."""
    end = float(route_of(result)[1][-1])
    return np.round(np.linspace(0.0, end, n))


# --------------------------------------------------------------------------------------------
# snapshot grid (paper Fig. 2)


def snapshot_figure(
    results,
    times=None,
    rows: int = 2,
    cols: int = 4,
    optimum: bool = True,
    metrics: Mapping[str, Mapping] | None = None,
    dpi: int = GRID_DPI,
):
    """Build the snapshot grid (see :func:`snapshot_grid`) and return the Figure, unsaved.

    Returns
    -------
    matplotlib.figure.Figure
        One sub-figure per result (its title is the algorithm and the headline metrics) with
        ``rows x cols`` map panels titled ``"t = <t>"``, and one legend sub-figure at the bottom.
    """
    items = as_results(results)
    for name, v in (("rows", rows), ("cols", cols)):
        if not isinstance(v, int | np.integer) or v < 1:
            raise ValueError(f"{name}={v!r} must be a positive integer")
    n_panels = rows * cols
    if times is not None:
        times = np.atleast_1d(np.asarray(times, dtype=float))
        if times.ndim != 1 or times.size == 0:
            raise ValueError("times must be a non-empty 1-D sequence of time steps")
        if not np.all(np.isfinite(times)) or np.any(times < 0):
            raise ValueError(f"times must be finite and >= 0, got {times.tolist()}")
        if times.size > n_panels:
            raise ValueError(f"{times.size} times do not fit in rows x cols = {n_panels} panels")
    metrics = dict(metrics or {})

    block_h = rows * PANEL_IN + 0.75  # title row and x labels
    legend_h = 1.0  # the legend and the time note under it
    width = cols * PANEL_IN + 0.5
    fig = new_figure((width, len(items) * block_h + legend_h), dpi)
    fig.get_layout_engine().set(w_pad=0.03, h_pad=0.05, hspace=0.02, wspace=0.02)
    subfigs = fig.subfigures(
        len(items) + 1, 1, height_ratios=[block_h] * len(items) + [legend_h], squeeze=False
    )[:, 0]
    cache: dict = {}
    for (key, res), sub in zip(items, subfigs[:-1], strict=False):
        label = display_name(key)
        m = metrics.get(key, metrics.get(label))
        sub.suptitle(run_headline(label, res, m), fontsize=11, fontweight="bold")
        ts = default_times(res, n_panels) if times is None else times
        opt = optimum_path(res.scenario, cache) if optimum else None
        axes = sub.subplots(rows, cols, squeeze=False)
        for i, ax in enumerate(axes.flat):
            r, c = divmod(i, cols)
            if i >= len(ts):
                ax.set_visible(False)
                continue
            # a new axes: clearing it again would only rebuild its ticks (0.1-0.2 s a grid)
            draw_world(ax, res.scenario, float(ts[i]), result=res, optimum=opt, clear=False)
            if c == 0:
                ax.set_ylabel("y (px)", fontsize=8)
            else:
                ax.tick_params(labelleft=False)
            if r == rows - 1 or i + cols >= len(ts):
                ax.set_xlabel("x (px)", fontsize=8)
            else:
                ax.tick_params(labelbottom=False)
    r0 = items[0][1].scenario.robot_radius
    handles = legend_handles(r0)
    subfigs[-1].legend(
        handles=handles,
        loc="upper center",
        ncols=min(len(handles), 5),
        fontsize=9,
        frameon=False,
        handlelength=2.4,
        columnspacing=1.6,
    )
    # wrap: a grid of one or two columns is narrower than the note
    note = dict(ha="center", va="bottom", fontsize=8.5, style="italic", wrap=True)
    subfigs[-1].text(0.5, 0.04, TIME_NOTE, **note)
    return fig


def snapshot_grid(
    results,
    path,
    times=None,
    rows: int = 2,
    cols: int = 4,
    optimum: bool = True,
    metrics: Mapping[str, Mapping] | None = None,
    dpi: int = GRID_DPI,
    metadata: Mapping[str, str] | None = None,
) -> Path:
    """Per algorithm a ``rows x cols`` grid of snapshots of its run over time (paper Fig. 2).

    Each panel shows the map at time ``t``: static obstacles (goldenrod), moving obstacles (dark)
    with their outline inflated by the robot radius and their recent track, the executed path up
    to ``t``, the plan active at ``t`` (position -> waypoints -> goal), the static optimum path,
    start, goal and the robot disc (to scale). A note under the legend (:data:`TIME_NOTE`) says
    that the obstacles are drawn at ``t`` while the lines span other times.

    Parameters
    ----------
    results : list of PlanResult or dict label -> PlanResult
        One run per algorithm (a list is labelled by each result's ``algorithm``); registered
        algorithm names are shown by their display label.
    path : str or Path
        Output image (``.png``, ``.svg`` or ``.pdf``); missing directories are created.
    times : sequence of float, optional
        Snapshot times (time steps) for every run, at most ``rows x cols``; default
        ``rows x cols`` integer times spread evenly over each run.
    rows, cols : int
        Panels per algorithm.
    optimum : bool
        Draw the exact shortest path around the static obstacles.
    metrics : dict label -> dict, optional
        Headline metrics per label (``length_px``, ``gap``, ``smoothness_rad``), as returned by
        :func:`mawdo.planning.metrics.run_metrics`.
    dpi : int
        Resolution; the image is ``figure size x dpi`` pixels (about 1600 px wide for 4 columns).
    metadata : dict str -> str, optional
        Text stored in the file (PNG tEXt chunks, e.g. ``{"Title": ...}``, readable with
        Pillow's ``Image.open(path).text``); the keys each format accepts are matplotlib's
        ``savefig(metadata=...)``.

    Returns
    -------
    Path
        The written file.

    Raises
    ------
    ValueError
        No results, bad ``rows``/``cols``/``times``, or an unsupported suffix.
    OSError
        The path cannot be written (the message names it).
    """
    out = checked_output_path(path, IMAGE_SUFFIXES)
    fig = snapshot_figure(
        results, times=times, rows=rows, cols=cols, optimum=optimum, metrics=metrics, dpi=dpi
    )
    # Lay out once, then save with the layout fixed: savefig would otherwise draw the whole
    # figure twice (a layout pass with drawing switched off, then the real one), about 0.4 s
    # of the grid's 2 s. Same positions, same pixels.
    fig.get_layout_engine().execute(fig)
    fig.set_layout_engine("none")
    return save_figure(fig, out, metadata=dict(metadata)) if metadata else save_figure(fig, out)


# --------------------------------------------------------------------------------------------
# animation


def panel_count(fig) -> int:
    """Map panels of a snapshot figure (axes titled ``"t = ..."``), for tests and checks."""
    axes = [ax for sub in [fig, *all_subfigures(fig)] for ax in sub.axes]
    return sum(1 for ax in set(axes) if ax.get_visible() and ax.get_title().startswith("t = "))


def all_subfigures(fig) -> list:
    out = []
    for sub in getattr(fig, "subfigs", []):
        out += [sub, *all_subfigures(sub)]
    return out
