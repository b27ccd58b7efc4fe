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
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from pathlib import Path

import numpy as np

from mawdo.planning.geometry import inflated_obstacles
from mawdo.planning.planner import PlanResult, Replan
from mawdo.planning.scenario import Scenario

__all__ = [
    "animate",
    "animation_times",
    "plot_cost_convergence",
    "plot_metric_boxes",
    "snapshot_figure",
    "snapshot_grid",
]

#: Resolution of the snapshot grid (dots per inch); 4 panels of PANEL_IN are ~1600 px wide.
GRID_DPI = 120
#: Side of one map panel in the snapshot grid (inches).
PANEL_IN = 3.2
#: Output formats of the static figures.
_IMAGE_SUFFIXES = (".png", ".svg", ".pdf")
#: Steps of obstacle motion shown as a faint track behind each moving obstacle.
TRACK_STEPS = 25.0

# One place for every colour and line style, shared by the panels and the legend.
_STYLE = {
    "static": {"facecolor": "goldenrod", "edgecolor": "darkgoldenrod", "lw": 0.8},
    "moving": {"facecolor": "0.12", "edgecolor": "black", "lw": 0.8},
    "inflated": {"color": "0.35", "lw": 0.6, "ls": (0, (3, 2)), "alpha": 0.7},
    "track": {"color": "0.5", "lw": 1.6, "alpha": 0.45, "solid_capstyle": "round"},
    "trail": {"color": "tab:blue", "lw": 2.0, "solid_capstyle": "round"},
    "plan": {"color": "tab:red", "lw": 1.0, "marker": "o", "ms": 2.2, "alpha": 0.9},
    "optimum": {"color": "tab:green", "lw": 1.0, "ls": (0, (5, 3)), "alpha": 0.9},
    "start": {"marker": "s", "ms": 7, "mfc": "white", "mec": "black", "mew": 1.2, "ls": "none"},
    "goal": {
        "marker": "*",
        "ms": 12,
        "mfc": "tab:purple",
        "mec": "black",
        "mew": 0.8,
        "ls": "none",
    },
    "robot": {"facecolor": "deepskyblue", "edgecolor": "navy", "lw": 1.0},
}

_LEGEND_LABELS = {
    "static": "static obstacle",
    "moving": "moving obstacle",
    "inflated": "inflated by robot radius",
    "track": f"obstacle track ({TRACK_STEPS:g} steps)",
    "trail": "executed path",
    "plan": "current plan",
    "optimum": "optimum (static)",
    "start": "start",
    "goal": "goal",
    "robot": "robot (to scale)",
}


# --------------------------------------------------------------------------------------------
# helpers


def _new_figure(figsize, dpi, layout="constrained"):
    """A :class:`~matplotlib.figure.Figure` on an Agg canvas, outside ``pyplot``."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    fig = Figure(figsize=figsize, dpi=dpi, layout=layout)
    FigureCanvasAgg(fig)
    return fig


def _display(name) -> str:
    """Display label of a registered algorithm (``"mewdo"`` -> ``"MEWDO (reconstructed)"``)."""
    from mawdo.optimizers import OPTIMIZERS

    name = str(name)
    return OPTIMIZERS[name].display if name.lower() in OPTIMIZERS else name


def _output_path(path, suffixes: tuple[str, ...] | None = None) -> Path:
    """Check an output path before any drawing: a known suffix and a directory we can make."""
    out = Path(path)
    if suffixes is not None and out.suffix.lower() not in suffixes:
        raise ValueError(f"output path {str(out)!r} must end in one of {', '.join(suffixes)}")
    if out.is_dir():
        raise IsADirectoryError(f"output path {str(out)!r} is a directory, not a file")
    try:
        out.parent.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise OSError(
            f"cannot write {str(out)!r}: cannot create its directory {str(out.parent)!r} "
            f"({exc.strerror or exc})"
        ) from exc
    return out


def _save(fig, out: Path, **kwargs) -> Path:
    try:
        fig.savefig(out, **kwargs)
    except OSError as exc:
        raise OSError(f"cannot write {str(out)!r}: {exc.strerror or exc}") from exc
    return out


def _as_results(results) -> list[tuple[str, PlanResult]]:
    """``[(key, result), ...]`` from a list of results or a mapping label -> result."""
    if isinstance(results, PlanResult):
        results = [results]
    if isinstance(results, Mapping):
        items = [(str(k), v) for k, v in results.items()]
    elif isinstance(results, Sequence):
        items = [(getattr(r, "algorithm", "?"), r) for r in results]
    else:
        raise TypeError(
            f"results must be a list of PlanResult or a dict label -> PlanResult, "
            f"got {type(results).__name__}"
        )
    if not items:
        raise ValueError("no results to draw: pass at least one PlanResult")
    for key, r in items:
        if not isinstance(r, PlanResult):
            raise TypeError(f"results[{key!r}] is a {type(r).__name__}, not a PlanResult")
        if len(r.trajectory) == 0:
            raise ValueError(f"results[{key!r}] has an empty trajectory")
    return items


def _route(result: PlanResult) -> tuple[np.ndarray, np.ndarray]:
    """The executed polyline and its time stamps (falls back to the integer-step trajectory)."""
    if result.route is not None and result.route_times is not None and len(result.route):
        return np.asarray(result.route, float), np.asarray(result.route_times, float)
    traj = np.asarray(result.trajectory, float)
    return traj, np.arange(len(traj), dtype=float)


def _position_at(route: np.ndarray, times: np.ndarray, t: float) -> np.ndarray:
    """Robot position at time ``t`` on the executed route (held at the ends)."""
    return np.array([np.interp(t, times, route[:, 0]), np.interp(t, times, route[:, 1])])


def _trail_until(route: np.ndarray, times: np.ndarray, t: float) -> np.ndarray:
    """The executed route from the start up to time ``t`` (pixels)."""
    done = route[times <= t]
    return np.vstack([done, _position_at(route, times, t)[None]])


def _active_replan(result: PlanResult, t: float) -> Replan | None:
    """The plan the robot follows at time ``t``: the last replan made at or before ``t``."""
    active = None
    for rp in result.replans:
        if rp.step <= t + 1e-9:
            active = rp
        else:
            break
    return active


def _rings(geom):
    """Exterior rings (``(k, 2)`` arrays) of a shapely polygon or multipolygon."""
    parts = getattr(geom, "geoms", [geom])
    return [np.asarray(p.exterior.coords) for p in parts if hasattr(p, "exterior")]


def _reference_point(obstacle) -> np.ndarray:
    """A point that moves with the obstacle (circle centre, polygon vertex mean), at offset 0."""
    if obstacle.is_circle:
        return np.asarray(obstacle.shape.center, float)
    return np.asarray(obstacle.shape.vertices, float).mean(axis=0)


def _optimum_path(scenario: Scenario, cache: dict) -> np.ndarray | None:
    """Static optimum path of a scenario (cached per scenario object)."""
    key = id(scenario)
    if key not in cache:
        from mawdo.planning.oracle import scenario_optimum

        cache[key] = scenario_optimum(scenario, static_only=True).path
    return cache[key]


def _fmt_time(t: float) -> str:
    return f"{t:.0f}" if abs(t - round(t)) < 1e-9 else f"{t:.1f}"


# --------------------------------------------------------------------------------------------
# one map panel


def _draw_world(
    ax,
    scenario: Scenario,
    t: float,
    result: PlanResult | None = None,
    optimum: np.ndarray | None = None,
    track: float = TRACK_STEPS,
    title: str | None = None,
    small: float = 7.0,
    clear: bool = True,
) -> None:
    """Draw the world at time ``t`` on ``ax``, and a run's state at ``t`` if ``result`` is given.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        Target axes, cleared first; with ``clear=False`` only its lines and patches are removed
        (labels kept), which is what an animation frame needs.
    scenario : Scenario
    t : float
        Time (time steps).
    result : PlanResult, optional
        Adds the executed trail up to ``t``, the plan active at ``t`` (position -> waypoints ->
        goal) and the robot disc (radius to scale).
    optimum : numpy.ndarray, optional
        The static optimum path ``(k, 2)`` (pixels), drawn thin and dashed.
    track : float
        Steps of past motion drawn as a faint track behind moving obstacles (0: none).
    title : str, optional
        Panel title (default ``"t = <t>"``).
    small : float
        Font size of ticks and title (points).
    clear : bool
        Clear the axes completely before drawing.

    Notes
    -----
    Every artist carries a ``gid`` (``"trail"``, ``"plan"``, ``"optimum"``, ``"robot"``,
    ``"start"``, ``"goal"``, ``"static:<id>"``, ``"moving:<id>"``, ``"inflated:<id>"``,
    ``"track:<id>"``): SVG output names its elements, and tests can find them.
    """
    from matplotlib.patches import Circle, Polygon

    s = _STYLE
    if clear:
        ax.clear()
    else:
        for artist in [*ax.lines, *ax.patches]:
            artist.remove()
    offsets = np.asarray(scenario.offsets(float(t)))
    inflated = inflated_obstacles(scenario, float(t))
    for ob, off, grown in zip(scenario.obstacles, offsets, inflated, strict=True):
        style = s["static"] if ob.is_static else s["moving"]
        z = 2 if ob.is_static else 3
        gid = f"{'static' if ob.is_static else 'moving'}:{ob.id}"
        if ob.is_circle:
            centre = np.asarray(ob.shape.center, float) + off
            ax.add_patch(Circle(centre, ob.shape.radius, zorder=z, gid=gid, **style))
        else:
            verts = np.asarray(ob.shape.vertices, float) + off
            ax.add_patch(Polygon(verts, closed=True, zorder=z, gid=gid, **style))
        if scenario.robot_radius > 0:
            for ring in _rings(grown):
                ax.plot(ring[:, 0], ring[:, 1], zorder=z, gid=f"inflated:{ob.id}", **s["inflated"])
        if not ob.is_static and track > 0 and t > 0:
            ts = np.linspace(max(0.0, t - track), t, max(2, int(2 * min(track, t)) + 1))
            pts = _reference_point(ob) + ob.offset(ts)
            ax.plot(pts[:, 0], pts[:, 1], zorder=1.5, gid=f"track:{ob.id}", **s["track"])
    if optimum is not None:
        ax.plot(optimum[:, 0], optimum[:, 1], zorder=4, gid="optimum", **s["optimum"])
    ax.plot(*scenario.start, zorder=7, gid="start", **s["start"])
    ax.plot(*scenario.goal, zorder=7, gid="goal", **s["goal"])
    if result is not None:
        route, times = _route(result)
        active = _active_replan(result, t)
        finished = result.success and t >= times[-1] - 1e-9
        if active is not None and not finished:
            plan = np.vstack([active.position, active.waypoints, scenario.goal])
            ax.plot(plan[:, 0], plan[:, 1], zorder=5, gid="plan", **s["plan"])
        trail = _trail_until(route, times, t)
        ax.plot(trail[:, 0], trail[:, 1], zorder=6, gid="trail", **s["trail"])
        pos = trail[-1]
        r = max(scenario.robot_radius, 0.0)
        if r > 0:
            ax.add_patch(Circle(pos, r, zorder=8, gid="robot", **s["robot"]))
        else:
            ax.plot(*pos, "o", ms=3, color=s["robot"]["edgecolor"], zorder=8, gid="robot")
    ax.set_xlim(0.0, scenario.width)
    ax.set_ylim(0.0, scenario.height)
    ax.set_aspect("equal", adjustable="box")
    ax.tick_params(labelsize=small - 1, length=2, pad=1.5)
    ax.set_title(f"t = {_fmt_time(t)}" if title is None else title, fontsize=small + 1, pad=3)


def _legend_handles(robot_radius: float) -> list:
    """Proxy artists for the figure legend, in the styles of :func:`_draw_world`.

    Ordered so that a 5-column legend (filled column by column) pairs related entries:
    obstacles, their outline and track, the robot's path and plan, optimum and robot, start and
    goal.
    """
    from matplotlib.lines import Line2D
    from matplotlib.patches import Patch

    s = _STYLE
    lab = _LEGEND_LABELS
    robot = s["robot"]
    robot_marker = {
        "ls": "none",
        "marker": "o",
        "ms": 7,
        "mfc": robot["facecolor"],
        "mec": robot["edgecolor"],
    }
    return [
        Patch(label=lab["static"], **s["static"]),
        Patch(label=lab["moving"], **s["moving"]),
        Line2D([], [], label=lab["inflated"], **s["inflated"]),
        Line2D([], [], label=lab["track"], **s["track"]),
        Line2D([], [], label=lab["trail"], **s["trail"]),
        Line2D([], [], label=lab["plan"], **s["plan"]),
        Line2D([], [], label=lab["optimum"], **s["optimum"]),
        Line2D([], [], label=f"{lab['robot']}, r = {robot_radius:g} px", **robot_marker),
        Line2D([], [], label=lab["start"], **s["start"]),
        Line2D([], [], label=lab["goal"], **s["goal"]),
    ]


def _headline(label: str, result: PlanResult, metrics: dict | None) -> str:
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


def _default_times(result: PlanResult, n: int) -> np.ndarray:
    """``n`` integer times spread evenly from 0 to the end of the run."""
    end = float(_route(result)[1][-1])
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
    items = _as_results(results)
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
    legend_h = 0.75
    width = cols * PANEL_IN + 0.5
    fig = _new_figure((width, len(items) * block_h + legend_h), dpi)
    fig.get_layout_engine().set(w_pad=0.03, h_pad=0.05, hspace=0.02, wspace=0.02)
    subfigs = fig.subfigures(
        len(items) + 1, 1, height_ratios=[block_h] * len(items) + [legend_h], squeeze=False
    )[:, 0]
    cache: dict = {}
    for (key, res), sub in zip(items, subfigs[:-1], strict=False):
        label = _display(key)
        m = metrics.get(key, metrics.get(label))
        sub.suptitle(_headline(label, res, m), fontsize=11, fontweight="bold")
        ts = _default_times(res, n_panels) if times is None else times
        opt = _optimum_path(res.scenario, cache) if optimum else None
        axes = sub.subplots(rows, cols, squeeze=False)
        for i, ax in enumerate(axes.flat):
            r, c = divmod(i, cols)
            if i >= len(ts):
                ax.set_visible(False)
                continue
            _draw_world(ax, res.scenario, float(ts[i]), result=res, optimum=opt)
            if c == 0:
                ax.set_ylabel("y (px)", fontsize=8)
            else:
                ax.tick_params(labelleft=False)
            if r == rows - 1 or i + cols >= len(ts):
                ax.set_xlabel("x (px)", fontsize=8)
            else:
                ax.tick_params(labelbottom=False)
    r0 = items[0][1].scenario.robot_radius
    handles = _legend_handles(r0)
    subfigs[-1].legend(
        handles=handles,
        loc="center",
        ncols=min(len(handles), 5),
        fontsize=9,
        frameon=False,
        handlelength=2.4,
        columnspacing=1.6,
    )
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
) -> Path:
    """Per algorithm a ``rows x cols`` grid of snapshots of its run over time (paper Fig. 2).

    Each panel shows the map at time ``t``: static obstacles (goldenrod), moving obstacles (dark)
    with their outline inflated by the robot radius and their recent track, the executed path up
    to ``t``, the plan active at ``t`` (position -> waypoints -> goal), the static optimum path,
    start, goal and the robot disc (to scale).

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
    out = _output_path(path, _IMAGE_SUFFIXES)
    fig = snapshot_figure(
        results, times=times, rows=rows, cols=cols, optimum=optimum, metrics=metrics, dpi=dpi
    )
    return _save(fig, out)


# --------------------------------------------------------------------------------------------
# animation


def animation_times(result: PlanResult, every: int = 1, max_frames: int = 200) -> np.ndarray:
    """Frame times of :func:`animate`: every ``every`` steps, thinned to ``max_frames``.

    The end of the run is always the last frame.
    """
    if not isinstance(every, int | np.integer) or every < 1:
        raise ValueError(f"every={every!r} must be a positive integer")
    if not isinstance(max_frames, int | np.integer) or max_frames < 2:
        raise ValueError(f"max_frames={max_frames!r} must be an integer >= 2")
    end = float(_route(result)[1][-1])
    ts = np.arange(0.0, end + 1e-9, every)
    if ts[-1] < end - 1e-9:
        ts = np.append(ts, end)
    if ts.size > max_frames:
        ts = ts[np.unique(np.linspace(0, ts.size - 1, max_frames).round().astype(int))]
    return ts


def animate(
    result: PlanResult,
    path,
    fps: int = 12,
    every: int = 1,
    max_frames: int = 200,
    optimum: bool = True,
    dpi: int = 80,
    label: str | None = None,
) -> Path:
    """Animated GIF of one run: the snapshot panel of :func:`snapshot_grid`, one frame per time.

    Parameters
    ----------
    result : PlanResult
    path : str or Path
        Output ``.gif``; missing directories are created.
    fps : int
        Frames per second.
    every : int
        Time steps between frames.
    max_frames : int
        Upper bound on frames (the times are thinned evenly, the last one kept).
    optimum : bool
        Draw the static optimum path.
    dpi : int
        Resolution of the 5 x 5.6 in figure (80 dpi: 400 x 448 px, a few MB at most).
    label : str, optional
        Title (default the algorithm's display label).

    Returns
    -------
    Path
        The written GIF.
    """
    from matplotlib.animation import PillowWriter

    if not isinstance(result, PlanResult):
        raise TypeError(f"animate needs a PlanResult, got {type(result).__name__}")
    if not (isinstance(fps, int | np.integer | float) and fps > 0):
        raise ValueError(f"fps={fps!r} must be > 0")
    out = _output_path(path, (".gif",))
    ts = animation_times(result, every, max_frames)
    sc = result.scenario
    opt = _optimum_path(sc, {}) if optimum else None
    fig = _new_figure((5.0, 5.6), dpi)
    fig.get_layout_engine().set(w_pad=0.02, h_pad=0.02)
    fig.suptitle(f"{label or _display(result.algorithm)}  (seed {result.seed})", fontsize=10)
    ax = fig.add_subplot()
    handles = _legend_handles(sc.robot_radius)
    fig.legend(
        handles=handles,
        loc="outside lower center",
        ncols=3,
        fontsize=6.5,
        frameon=False,
        handlelength=2.0,
        columnspacing=1.0,
    )

    def frame(i):
        _draw_world(ax, sc, float(ts[i]), result=result, optimum=opt, clear=False)

    frame(0)
    ax.set_xlabel("x (px)", fontsize=7)
    ax.set_ylabel("y (px)", fontsize=7)
    fig.draw_without_rendering()  # fix the constrained layout once; frames keep it
    fig.set_layout_engine("none")
    # PillowWriter driven frame by frame: FuncAnimation.save would draw every frame twice
    # (once for the writer, once more in its post-draw hook) for the same GIF.
    writer = PillowWriter(fps=fps)
    try:
        with writer.saving(fig, out, dpi):
            for i in range(len(ts)):
                if i:
                    frame(i)
                writer.grab_frame()
    except OSError as exc:
        raise OSError(f"cannot write {str(out)!r}: {exc.strerror or exc}") from exc
    return out


# --------------------------------------------------------------------------------------------
# statistics across runs


def _as_runs(curves, label: str) -> np.ndarray:
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


def _plain_log_labels(ax, values: np.ndarray) -> None:
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
    data = {str(k): _as_runs(v, str(k)) for k, v in curves.items()}
    out = _output_path(path, _IMAGE_SUFFIXES)
    if log and any(np.nanmin(a) <= 0 for a in data.values()):
        log = False
    fig = _new_figure((6.4, 4.2), 120)
    ax = fig.add_subplot()
    for key, arr in data.items():
        band(ax, arr, f"{_display(key)} (n = {arr.shape[0]})", log=log)
    ax.set_xlabel("iteration")
    ax.set_ylabel("best cost C" + (" (log scale)" if log else ""))
    ax.set_title(title or "First plan: median best cost and IQR over runs", fontsize=10)
    ax.grid(True, which="both", alpha=0.3)
    if log:
        _plain_log_labels(ax, np.concatenate([a.ravel() for a in data.values()]))
    ax.legend(fontsize=8)
    return _save(fig, out)


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
        ticks.append(f"{_display(key)}\n(n = {kept.size}/{arr.size})")
    if not any(d.size for d in data):
        raise ValueError(f"no finite values of {metric_label!r} to plot")
    out = _output_path(path, _IMAGE_SUFFIXES)
    fig = _new_figure((max(4.0, 1.1 * len(data) + 1.5), 4.2), 120)
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
    return _save(fig, out)


def _panel_count(fig) -> int:
    """Map panels of a snapshot figure (axes titled ``"t = ..."``), for tests and checks."""
    axes = [ax for sub in [fig, *_all_subfigures(fig)] for ax in sub.axes]
    return sum(1 for ax in set(axes) if ax.get_visible() and ax.get_title().startswith("t = "))


def _all_subfigures(fig) -> list:
    out = []
    for sub in getattr(fig, "subfigs", []):
        out += [sub, *_all_subfigures(sub)]
    return out
