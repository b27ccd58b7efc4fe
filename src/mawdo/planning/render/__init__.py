"""Figures and animations of planning runs (the only planning module that imports matplotlib).

* :func:`snapshot_grid` - per algorithm a ``rows x cols`` grid of snapshots of a run over time
  (paper Fig. 2); :func:`snapshot_figure` builds the same figure without saving it.
* :func:`animate` - an animated GIF of one run (Pillow, no ffmpeg).
* :func:`plot_cost_convergence` - median and IQR of the first plan's best cost per iteration
  (paper Fig. 3).
* :func:`plot_metric_boxes` - box plots of one metric across algorithms.

Every map panel is drawn by one function, :func:`_draw_world`, so the grid and the animation show
exactly the same things. Figures are built with the object-oriented API
(:class:`matplotlib.figure.Figure` on an Agg canvas), never through ``pyplot``: nothing here
changes the global backend or leaves figures registered in ``pyplot``.

Units: pixels (x right, y up, origin at the lower-left map corner) and time steps, as in
:mod:`mawdo.planning.scenario`.

A package, one module per job (every name is importable from here as before):
:mod:`.style` (colours, sizes, shared helpers), :mod:`.world` (one map panel), :mod:`.snapshots`
(the grid), :mod:`.animation` (the GIF), :mod:`.plots` (convergence and box plots).
"""

# ruff: noqa: F401 - private names are re-exported: callers import them from here as before
from mawdo.planning.render.animation import animate, animation_times
from mawdo.planning.render.plots import (
    _as_runs,
    _plain_log_labels,
    plot_cost_convergence,
    plot_metric_boxes,
)
from mawdo.planning.render.snapshots import (
    TIME_NOTE,
    _all_subfigures,
    _default_times,
    _headline,
    _panel_count,
    snapshot_figure,
    snapshot_grid,
)
from mawdo.planning.render.style import (
    _IMAGE_SUFFIXES,
    _LEGEND_LABELS,
    _STYLE,
    GRID_DPI,
    PANEL_IN,
    TRACK_STEPS,
    _active_replan,
    _as_results,
    _display,
    _fmt_time,
    _new_figure,
    _optimum_path,
    _output_path,
    _position_at,
    _reference_point,
    _rings,
    _route,
    _save,
    _trail_until,
)
from mawdo.planning.render.world import _draw_world, _legend_handles

__all__ = [
    "animate",
    "animation_times",
    "plot_cost_convergence",
    "plot_metric_boxes",
    "snapshot_figure",
    "snapshot_grid",
]
