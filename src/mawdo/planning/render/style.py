"""Colours, sizes and helpers shared by every figure of planning runs (output paths, figures
outside pyplot, routes and replans at a time)."""

from __future__ import annotations

import weakref
from collections.abc import Mapping, Sequence
from pathlib import Path

import numpy as np

from mawdo.planning.run.result import PlanResult, Replan
from mawdo.planning.world.scenario import Scenario

#: Resolution of the snapshot grid (dots per inch); 4 panels of PANEL_IN are ~1600 px wide.
GRID_DPI = 120
#: Side of one map panel in the snapshot grid (inches).
PANEL_IN = 3.2
#: Output formats of the static figures.
IMAGE_SUFFIXES = (".png", ".svg", ".pdf")
#: Steps of obstacle motion shown as a faint track behind each moving obstacle.
TRACK_STEPS = 25.0

# One place for every colour and line style, shared by the panels and the legend.
STYLE = {
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

LEGEND_LABELS = {
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


def new_figure(figsize, dpi, layout="constrained"):
    """A :class:`~matplotlib.figure.Figure` on an Agg canvas, outside ``pyplot``."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    fig = Figure(figsize=figsize, dpi=dpi, layout=layout)
    FigureCanvasAgg(fig)
    return fig


def keep_layout(fig) -> None:
    """Lay ``fig`` out now with its layout engine, then drop the engine: saving draws the
    figure once. (``set_layout_engine("none")`` leaves a placeholder engine, and with any
    engine ``savefig`` first draws the whole figure with drawing off, a layout pass: 0.3-0.4 s
    of CPU of the snapshot grid's 0.8-1 s after a run.)"""
    from matplotlib import rc_context

    fig.get_layout_engine().execute(fig)
    # None means the rcParams' default engine: none unless a user's rcParams ask for one
    with rc_context({"figure.autolayout": False, "figure.constrained_layout.use": False}):
        fig.set_layout_engine(None)


def display_name(name) -> str:
    """Display label of a registered algorithm (``"mewdo"`` -> ``"MEWDO (reconstructed)"``)."""
    from mawdo.optimizers import OPTIMIZERS

    name = str(name)
    return OPTIMIZERS[name].display if name.lower() in OPTIMIZERS else name


def checked_output_path(path, suffixes: tuple[str, ...] | None = None) -> Path:
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


def save_figure(fig, out: Path, **kwargs) -> Path:
    try:
        fig.savefig(out, **kwargs)
    except OSError as exc:
        raise OSError(f"cannot write {str(out)!r}: {exc.strerror or exc}") from exc
    return out


def as_results(results) -> list[tuple[str, PlanResult]]:
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


def route_of(result: PlanResult) -> tuple[np.ndarray, np.ndarray]:
    """The executed polyline and its time stamps (falls back to the integer-step trajectory)."""
    if result.route is not None and result.route_times is not None and len(result.route):
        return np.asarray(result.route, float), np.asarray(result.route_times, float)
    traj = np.asarray(result.trajectory, float)
    return traj, np.arange(len(traj), dtype=float)


def position_at(route: np.ndarray, times: np.ndarray, t: float) -> np.ndarray:
    """Robot position at time ``t`` on the executed route (held at the ends)."""
    return np.array([np.interp(t, times, route[:, 0]), np.interp(t, times, route[:, 1])])


def trail_until(route: np.ndarray, times: np.ndarray, t: float) -> np.ndarray:
    """The executed route from the start up to time ``t`` (pixels)."""
    done = route[times <= t]
    return np.vstack([done, position_at(route, times, t)[None]])


def active_replan(result: PlanResult, t: float) -> Replan | None:
    """The plan the robot follows at time ``t``: the last replan made at or before ``t``."""
    active = None
    for rp in result.replans:
        if rp.step <= t + 1e-9:
            active = rp
        else:
            break
    return active


def rings_of(geom):
    """Exterior rings (``(k, 2)`` arrays) of a shapely polygon or multipolygon."""
    parts = getattr(geom, "geoms", [geom])
    return [np.asarray(p.exterior.coords) for p in parts if hasattr(p, "exterior")]


def reference_point(obstacle) -> np.ndarray:
    """A point that moves with the obstacle (circle centre, polygon vertex mean), at offset 0."""
    if obstacle.is_circle:
        return np.asarray(obstacle.shape.center, float)
    return np.asarray(obstacle.shape.vertices, float).mean(axis=0)


def optimum_path(scenario: Scenario, cache: dict) -> np.ndarray | None:
    """Static optimum path of a scenario (cached per scenario object; one given by
    :func:`know_optimum` is used as it is)."""
    key = id(scenario)
    if key not in cache:
        known = _KNOWN.get(scenario)
        if known is None:
            from mawdo.planning.guide.oracle import scenario_optimum

            known = scenario_optimum(scenario, static_only=True).path
        cache[key] = known
    return cache[key]


#: Static optima computed elsewhere (another process), by scenario object.
_KNOWN: weakref.WeakKeyDictionary = weakref.WeakKeyDictionary()


def know_optimum(scenario: Scenario, path: np.ndarray) -> None:
    """Give :func:`optimum_path` the static optimum path of ``scenario`` (what
    ``scenario_optimum(scenario, static_only=True).path`` returns), computed elsewhere: a
    figures' process then needs neither the oracle nor its compiled kernels."""
    _KNOWN[scenario] = path


def format_time(t: float) -> str:
    return f"{t:.0f}" if abs(t - round(t)) < 1e-9 else f"{t:.1f}"


def time_title(scenario: Scenario, t: float) -> str:
    """A panel's title at time ``t`` (time steps): ``t = 12`` (steps), or in seconds for a
    metre scenario (``t = 3 s``)."""
    u = scenario.units
    return f"t = {format_time(t)}" if u.is_pixels else f"t = {u.time(t):.4g} s"


def axis_label(scenario: Scenario, axis: str) -> str:
    """``"x (px)"``, or ``"x (m)"`` for a metre scenario."""
    return f"{axis} ({scenario.units.length_label})"


def metre_ticks(ax, scenario: Scenario) -> None:
    """Ticks at round metres on a metre scenario's map panel (drawn in pixels); nothing for a
    pixel scenario."""
    u = scenario.units
    if u.is_pixels:
        return
    from matplotlib.ticker import FixedLocator, FuncFormatter, MaxNLocator

    for axis, size in ((ax.xaxis, scenario.width), (ax.yaxis, scenario.height)):
        top = float(u.length(size))
        ticks = MaxNLocator(nbins=6, steps=[1, 2, 2.5, 5, 10]).tick_values(0.0, top)
        ticks = ticks[(ticks >= 0.0) & (ticks <= top * (1 + 1e-9))]
        axis.set_major_locator(FixedLocator(u.length_to_px(ticks)))
        axis.set_major_formatter(FuncFormatter(lambda v, _pos: f"{u.length(v):.6g}"))


# --------------------------------------------------------------------------------------------
# one map panel
