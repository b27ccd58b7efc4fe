"""Figures and animations of planning runs (the only planning module that imports matplotlib).

* :func:`snapshot_grid` - per algorithm a ``rows x cols`` grid of snapshots of a run over time
  (paper Fig. 2); :func:`snapshot_figure` builds the same figure without saving it.
* :func:`animate` - an animated GIF of one run (Pillow, no ffmpeg).
* :func:`plot_cost_convergence` - median and IQR of the first plan's best cost per iteration
  (paper Fig. 3).
* :func:`plot_metric_boxes` - box plots of one metric across algorithms.

Every map panel is drawn by one function, :func:`draw_world`, so the grid and the animation show
exactly the same things. Figures are built with the object-oriented API
(:class:`matplotlib.figure.Figure` on an Agg canvas), never through ``pyplot``: nothing here
changes the global backend or leaves figures registered in ``pyplot``.

Units: pixels (x right, y up, origin at the lower-left map corner) and time steps, as in
:mod:`mawdo.planning.world.scenario`. A scenario in metres and seconds is drawn in pixels as
well, but its axes, ticks, panel times and legend read in metres and seconds
(``Scenario.units``).

A package, one module per job (every name is importable from here as before):
:mod:`.style` (colours, sizes, shared helpers), :mod:`.world` (one map panel), :mod:`.snapshots`
(the grid), :mod:`.animation` (the GIF), :mod:`.plots` (convergence and box plots),
:mod:`.forked` (a figure drawn in a second process beside another: the GIF beside the grid).
"""

# ruff: noqa: F401 - private names are re-exported: callers import them from here as before
from mawdo.planning.render.animation import animate, animation_times
from mawdo.planning.render.forked import Forked, can_fork, forked_note
from mawdo.planning.render.plots import (
    as_runs,
    plain_log_labels,
    plot_cost_convergence,
    plot_metric_boxes,
)
from mawdo.planning.render.snapshots import (
    TIME_NOTE,
    all_subfigures,
    default_times,
    panel_count,
    run_headline,
    snapshot_figure,
    snapshot_grid,
)
from mawdo.planning.render.style import (
    GRID_DPI,
    IMAGE_SUFFIXES,
    LEGEND_LABELS,
    PANEL_IN,
    STYLE,
    TRACK_STEPS,
    active_replan,
    as_results,
    checked_output_path,
    display_name,
    format_time,
    new_figure,
    optimum_path,
    position_at,
    reference_point,
    rings_of,
    route_of,
    save_figure,
    trail_until,
)
from mawdo.planning.render.world import draw_world, legend_handles

__all__ = [
    "Forked",
    "animate",
    "animation_times",
    "plot_cost_convergence",
    "plot_metric_boxes",
    "snapshot_figure",
    "snapshot_grid",
]
