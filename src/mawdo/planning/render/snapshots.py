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
    axis_label,
    checked_output_path,
    display_name,
    keep_layout,
    new_figure,
    optimum_path,
    route_of,
    save_figure,
)
from mawdo.planning.render.world import draw_world, legend_handles, move_world, moving_layers
from mawdo.planning.run.result import PlanResult

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
        if metrics.get("length_px") is not None:
            u, px = result.scenario.units, metrics["length_px"]
            length = f"{px:.1f}" if u.is_pixels else f"{u.length(px):.2f}"
            parts.append(f"length {length} {u.length_label}")
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
    _check_shape(rows, cols)
    blocks = grid_blocks(items, times, rows * cols, metrics)
    frame = GridFrame.for_blocks(blocks, rows, cols, optimum, dpi)
    return frame.fill(blocks)


def grid_blocks(items, times, n_panels: int, metrics: Mapping[str, Mapping] | None) -> list:
    """Per run ``(result, headline, panel times)`` of a grid of ``n_panels`` panels a run."""
    times = _checked_times(times, n_panels)
    metrics = dict(metrics or {})
    out = []
    for key, res in items:
        label = display_name(key)
        headline = run_headline(label, res, metrics.get(key, metrics.get(label)))
        out.append((res, headline, default_times(res, n_panels) if times is None else times))
    return out


class GridFrame:
    """A snapshot grid in two steps: what needs only the scenarios, then the runs.

    ``GridFrame(scenarios, ...)`` lays out the figure, its panels with their axes, ticks and
    labels, the static obstacles, the optimum, start and goal, the legend and the note;
    :meth:`fill` adds what moves (obstacles at each panel's time, tracks, plan, trail, robot)
    and the titles. The first step is most of the grid's work (the layout above all) and can
    run before the runs exist (:mod:`.early`: while the planner runs), with placeholder titles.
    The figure is the one a single pass draws: the same artists in the same order, and the
    layout made with titles of the heights drawn (if a real title's height differs from its
    placeholder's, :meth:`fill` lays out a new frame with the real titles).

    Parameters
    ----------
    scenarios : list of Scenario
        One per block of panels (one block per run), top to bottom.
    rows, cols : int
        Panels per block.
    optimum : bool
        Draw the exact shortest path around the static obstacles.
    dpi : int
        Resolution (dots per inch).
    titles : list of str, optional
        Each block's title (default a placeholder headline).
    shown : list of int, optional
        Panels shown in each block, the first ones (default all).
    """

    def __init__(
        self, scenarios, rows=2, cols=4, optimum=True, dpi=GRID_DPI, titles=None, shown=None
    ) -> None:
        _check_shape(rows, cols)
        self.rows, self.cols, self.scenarios = rows, cols, list(scenarios)
        self.args = (rows, cols, optimum, dpi)
        n = len(self.scenarios)
        self.titles = list(titles or [_PLACEHOLDER] * n)
        self.shown = list(shown or [rows * cols] * n)
        block_h = rows * PANEL_IN + 0.75  # title row and x labels
        legend_h = 1.0  # the legend and the time note under it
        self.fig = fig = new_figure((cols * PANEL_IN + 0.5, n * block_h + legend_h), dpi)
        fig.get_layout_engine().set(w_pad=0.03, h_pad=0.05, hspace=0.02, wspace=0.02)
        self.subfigs = fig.subfigures(
            n + 1, 1, height_ratios=[block_h] * n + [legend_h], squeeze=False
        )[:, 0]
        cache: dict = {}
        self.axes, self.optima, self.layers = [], [], {}
        titled = zip(self.scenarios, self.subfigs, self.titles, self.shown, strict=False)
        for sc, sub, title, k in titled:  # (the last sub-figure is the legend's)
            sub.suptitle(title, fontsize=11, fontweight="bold")
            opt = optimum_path(sc, cache) if optimum else None
            axes = sub.subplots(rows, cols, squeeze=False)
            for i, ax in enumerate(axes.flat):
                if i >= k:
                    ax.set_visible(False)
                    continue
                # a new axes: clearing it again would only rebuild its ticks (0.1-0.2 s a grid)
                draw_world(ax, sc, 0.0, optimum=opt, clear=False, moving=False)
                self._label(ax, sc, i, k)
                # what moves, hidden until fill() places it: making 160 artists there cost
                # 0.2-0.3 s of the grid's work after the run
                self.layers[ax] = moving_layers(ax, sc)
            self.axes.append(axes)
            self.optima.append(opt)
        _legend(self.subfigs[-1], self.scenarios[0])
        # Lay out once, and save with the layout fixed: savefig would otherwise draw the whole
        # figure twice (a layout pass with drawing off, then the real one), about 0.4 s of 2 s.
        keep_layout(fig)
        _wrapped_now(self.subfigs[-1].texts[-1], fig.canvas.get_renderer())
        self.laid_out = self._extents()

    @classmethod
    def for_blocks(cls, blocks, rows=2, cols=4, optimum=True, dpi=GRID_DPI):
        """The frame of :func:`grid_blocks`' blocks, laid out with their titles."""
        scenarios = [res.scenario for res, _, _ in blocks]
        titles = [headline for _, headline, _ in blocks]
        return cls(scenarios, rows, cols, optimum, dpi, titles, [len(ts) for *_, ts in blocks])

    def _label(self, ax, sc, i: int, n: int) -> None:
        """Axis labels of panel ``i`` of ``n``: y on the first column, x where none is below."""
        r, c = divmod(i, self.cols)
        if c == 0:
            ax.set_ylabel(axis_label(sc, "y"), fontsize=8)
        else:
            ax.tick_params(labelleft=False)
        if r == self.rows - 1 or i + self.cols >= n:
            ax.set_xlabel(axis_label(sc, "x"), fontsize=8)
        else:
            ax.tick_params(labelbottom=False)

    def _extents(self) -> list[tuple[float, float]]:
        """Each title's vertical extent on the canvas (what the layout made room for)."""
        renderer = self.fig.canvas.get_renderer()
        texts = [s._suptitle for s in self.subfigs[:-1]]
        texts += [ax.title for axes in self.axes for ax in axes.flat if ax.get_visible()]
        boxes = [t.get_window_extent(renderer) for t in texts]
        return [(round(b.y0, 6), round(b.y1, 6)) for b in boxes]

    def fill(self, blocks, again: bool = True):
        """Draw the runs of :func:`grid_blocks`, one per scenario given; returns the figure
        (a new frame's, laid out for the blocks, if they do not fit this one's titles and
        panel counts and ``again``)."""
        if again and [len(ts) for *_, ts in blocks] != self.shown:
            return GridFrame.for_blocks(blocks, *self.args).fill(blocks, again=False)
        for (res, headline, ts), sub, axes, opt in zip(
            blocks, self.subfigs, self.axes, self.optima, strict=False
        ):
            sub._suptitle.set_text(headline)  # where the layout put it, in its font
            for ax, t in zip(axes.flat, ts, strict=False):
                move_world(ax, self.layers[ax], res.scenario, float(t), res, opt)
        if again and self._extents() != self.laid_out:  # a title the layout did not expect
            return GridFrame.for_blocks(blocks, *self.args).fill(blocks, again=False)
        return self.fig


def _check_shape(rows, cols) -> None:
    for name, v in (("rows", rows), ("cols", cols)):
        if not isinstance(v, int | np.integer) or v < 1:
            raise ValueError(f"{name}={v!r} must be a positive integer")


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
        :func:`mawdo.planning.judge.metrics.run_metrics`.
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
    return save_grid(fig, out, metadata)


def save_grid(fig, out: Path, metadata: Mapping[str, str] | None = None) -> Path:
    """Write a laid-out grid figure to ``out`` (PNG text ``metadata`` if given)."""
    return save_figure(fig, out, metadata=dict(metadata)) if metadata else save_figure(fig, out)


#: Title of a block before its run is known: the layout only needs a line of bold text.
_PLACEHOLDER = "MAWDO  (seed 0)  |  length 0.0 px  |  gap L/L* 0.000  |  smoothness 0.00 rad"


def _checked_times(times, n_panels: int):
    """``times`` as a float array (None stays None), checked against ``n_panels``."""
    if times is None:
        return None
    times = np.atleast_1d(np.asarray(times, dtype=float))
    if times.ndim != 1 or times.size == 0:
        raise ValueError("times must be a non-empty 1-D sequence of time steps")
    if not np.all(np.isfinite(times)) or np.any(times < 0):
        raise ValueError(f"times must be finite and >= 0, got {times.tolist()}")
    if times.size > n_panels:
        raise ValueError(f"{times.size} times do not fit in rows x cols = {n_panels} panels")
    return times


def _legend(sub, scenario) -> None:
    """The legend and the time note, in the bottom sub-figure."""
    handles = legend_handles(scenario.robot_radius, scenario.units)
    sub.legend(
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
    sub.text(0.5, 0.04, TIME_NOTE, **note)


def _wrapped_now(text, renderer) -> None:
    """Give a wrapped text (the time note) its lines now, as the layout wraps it: drawing it
    then measures no word (a wrapped text measures its line word by word at every draw, 41
    measurements, 0.1-0.15 s of CPU of a grid's save). The lines are the ones the draw would
    find (same text, font, position and figure); where matplotlib's wrapping is not there to
    ask (it is private), the text keeps wrapping itself."""
    try:
        text.get_window_extent(renderer)  # (the renderer the wrapping measures with)
        lines = text._get_wrapped_text()
    except AttributeError:
        return
    text.set_text(lines)
    text.set_wrap(False)


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
