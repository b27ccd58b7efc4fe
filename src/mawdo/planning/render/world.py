"""One map panel: obstacles (inflated, tracks), executed path, current plan, optimum, robot;
and the legend that names them. The snapshot grid and the animation both draw with it."""

from __future__ import annotations

import weakref

import numpy as np

from mawdo.planning.render.style import (
    LEGEND_LABELS,
    STYLE,
    TRACK_STEPS,
    active_replan,
    metre_ticks,
    reference_point,
    rings_of,
    route_of,
    time_title,
    trail_until,
)
from mawdo.planning.run.result import PlanResult
from mawdo.planning.world.geometry import inflate
from mawdo.planning.world.scenario import Scenario
from mawdo.planning.world.units import PIXELS, Units

# drawing order of the line layers (obstacles: 2 static, 3 moving; robot 8)
_ZORDER = {"track": 1.5, "optimum": 4, "plan": 5, "trail": 6, "start": 7, "goal": 7}
#: Font size of a panel's ticks (minus 1) and title (plus 1), points: draw_world's ``small``.
_SMALL = 7.0


def draw_world(
    ax,
    scenario: Scenario,
    t: float,
    result: PlanResult | None = None,
    optimum: np.ndarray | None = None,
    track: float = TRACK_STEPS,
    title: str | None = None,
    small: float = _SMALL,
    clear: bool = True,
    moving: bool = True,
    static: bool = True,
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
    moving, static : bool
        Draw what moves (moving obstacles, tracks, the run) and what stands (static obstacles,
        optimum, start, goal, limits, ticks), each or both: a snapshot grid draws the standing
        part before the run exists (:class:`~mawdo.planning.render.snapshots.GridFrame`). In
        the order both are drawn, ties of ``zorder`` between the two parts never occur, so
        the panel is the same in one call or in two.

    Notes
    -----
    Every artist carries a ``gid`` (``"trail"``, ``"plan"``, ``"optimum"``, ``"robot"``,
    ``"start"``, ``"goal"``, ``"static:<id>"``, ``"moving:<id>"``, ``"inflated:<id>"``,
    ``"track:<id>"``): SVG output names its elements, and tests can find them.
    """
    fixed = standing_gids(scenario)
    if clear:
        ax.clear()
    else:
        for artist in [*ax.lines, *ax.patches]:
            if static if artist.get_gid() in fixed else moving:
                artist.remove()
    for gid, data in world_state(scenario, t, result, optimum, track).items():
        if data is not None and (static if gid in fixed else moving):
            add_layer(ax, scenario, gid, data)
    if static:
        ax.set_xlim(0.0, scenario.width)
        ax.set_ylim(0.0, scenario.height)
        ax.set_aspect("equal", adjustable="box")
        ax.tick_params(labelsize=small - 1, length=2, pad=1.5)
        metre_ticks(ax, scenario)
    title = time_title(scenario, t) if title is None else title
    ax.set_title(title, fontsize=small + 1, pad=3)


def world_state(
    scenario: Scenario,
    t: float,
    result: PlanResult | None = None,
    optimum: np.ndarray | None = None,
    track: float = TRACK_STEPS,
) -> dict:
    """What a panel shows at time ``t``, by ``gid`` in drawing order (pixels).

    ``"static:<id>"`` / ``"moving:<id>"``: the shape where it is (a circle's centre, a polygon's
    vertices); ``"inflated:<id>"``: its inflated outline (list of rings, empty without a robot
    radius); ``"track:<id>"``: the moving obstacle's past track; ``"optimum"``, ``"start"``,
    ``"goal"``; with a run, ``"plan"`` (position -> waypoints -> goal), ``"trail"`` and
    ``"robot"`` (its position). An entry is ``None`` where nothing is drawn at ``t`` (no track
    at t = 0, no plan once the goal is reached): the animation keeps its artist, empty.
    """
    state: dict = {}
    offsets = np.asarray(scenario.offsets(float(t)))
    rings = _inflated_rings(scenario)
    for ob, off, grown in zip(scenario.obstacles, offsets, rings, strict=True):
        kind = "static" if ob.is_static else "moving"
        if ob.is_circle:
            state[f"{kind}:{ob.id}"] = np.asarray(ob.shape.center, float) + off
        else:
            state[f"{kind}:{ob.id}"] = np.asarray(ob.shape.vertices, float) + off
        state[f"inflated:{ob.id}"] = [r + off for r in grown]
        if not ob.is_static and track > 0:
            state[f"track:{ob.id}"] = None
            if t > 0:
                ts = np.linspace(max(0.0, t - track), t, max(2, int(2 * min(track, t)) + 1))
                state[f"track:{ob.id}"] = reference_point(ob) + ob.offset(ts)
    if optimum is not None:
        state["optimum"] = optimum
    state["start"] = np.asarray(scenario.start, float)
    state["goal"] = np.asarray(scenario.goal, float)
    if result is not None:
        route, times = route_of(result)
        active = active_replan(result, t)
        finished = result.success and t >= times[-1] - 1e-9
        state["plan"] = None
        if active is not None and not finished:
            state["plan"] = np.vstack([active.position, active.waypoints, scenario.goal])
        trail = trail_until(route, times, t)
        state["trail"] = trail
        state["robot"] = trail[-1]
    return state


def moving_layers(ax, scenario: Scenario) -> dict[str, list]:
    """What moves on a panel, drawn now as hidden artists (``gid`` -> artists) for
    :func:`move_world` to place: a snapshot grid makes them before its run exists. Made in the
    order :func:`draw_world` adds them, after what stands, so the panel draws the same."""
    fixed = standing_gids(scenario)
    state = world_state(scenario, 0.0)
    gids = [g for g in state if g not in fixed] + ["plan", "trail", "robot"]
    layers = {}
    for gid in gids:
        data = scenario.start if gid == "robot" else state.get(gid)
        layers[gid] = add_layer(ax, scenario, gid, data)
        for a in layers[gid]:
            a.set_visible(False)
    return layers


def move_world(ax, layers: dict, scenario: Scenario, t: float, result, optimum=None) -> None:
    """Draw what moves at time ``t`` on a panel by placing :func:`moving_layers`' artists:
    the panel ``draw_world(ax, ..., t, result, optimum, clear=False, static=False)`` draws,
    in a fraction of its time (no artist made, removed or added to the data limits)."""
    state = world_state(scenario, t, result, optimum)
    fixed = standing_gids(scenario)
    if not all(g in layers for g in state if g not in fixed):  # made for another scenario
        return _redrawn(ax, layers, scenario, t, result, optimum)
    for gid, arts in layers.items():
        data = state.get(gid)
        if data is not None and not set_layer(arts, gid, data):  # (a ring more or less)
            return _redrawn(ax, layers, scenario, t, result, optimum)
        for a in arts:
            a.set_visible(data is not None)
    ax.set_title(time_title(scenario, t), fontsize=_SMALL + 1, pad=3)


def _redrawn(ax, layers: dict, scenario: Scenario, t: float, result, optimum) -> None:
    """:func:`move_world`'s way out: the layers dropped (emptied: later calls come here too),
    what moves drawn by :func:`draw_world`."""
    for a in [a for arts in layers.values() for a in arts]:
        a.remove()
    layers.clear()
    draw_world(ax, scenario, t, result, optimum, clear=False, static=False)


def standing_gids(scenario: Scenario) -> set[str]:
    """The ``gid`` of what a panel draws the same at every time: the static obstacles and their
    inflated outlines, the optimum, start and goal."""
    fixed = {"optimum", "start", "goal"}
    for ob in scenario.obstacles:
        if ob.is_static:
            fixed |= {f"static:{ob.id}", f"inflated:{ob.id}"}
    return fixed


#: per scenario, its obstacles' inflated outlines at offset zero (a frame translates them)
_RINGS: weakref.WeakKeyDictionary = weakref.WeakKeyDictionary()


def _inflated_rings(scenario: Scenario) -> list[list[np.ndarray]]:
    """Per obstacle the exterior rings of its shape grown by the robot radius, at offset zero
    (none without a radius). Obstacles only translate, so a panel at time t adds the offset:
    inflating once instead of once per frame spares shapely a quarter of a GIF frame's work."""
    if scenario not in _RINGS:
        r = scenario.robot_radius
        _RINGS[scenario] = [
            rings_of(inflate(o.shape, r)) if r > 0 else [] for o in scenario.obstacles
        ]
    return _RINGS[scenario]


def add_layer(ax, scenario: Scenario, gid: str, data) -> list:
    """Draw one entry of :func:`world_state` on ``ax`` in its style; returns its artists."""
    from matplotlib.patches import Circle, Polygon

    s = STYLE
    kind, _, oid = gid.partition(":")
    if kind in ("static", "moving"):
        ob = next(o for o in scenario.obstacles if str(o.id) == oid)
        z = 2 if ob.is_static else 3
        if ob.is_circle:
            return [ax.add_patch(Circle(data, ob.shape.radius, zorder=z, gid=gid, **s[kind]))]
        return [ax.add_patch(Polygon(data, closed=True, zorder=z, gid=gid, **s[kind]))]
    if kind == "inflated":
        z = 2 if next(o for o in scenario.obstacles if str(o.id) == oid).is_static else 3
        return [ax.plot(r[:, 0], r[:, 1], zorder=z, gid=gid, **s["inflated"])[0] for r in data]
    if kind == "robot" and scenario.robot_radius > 0:
        return [ax.add_patch(Circle(data, scenario.robot_radius, zorder=8, gid=gid, **s["robot"]))]
    if kind == "robot":
        return ax.plot(*data, "o", ms=3, color=s["robot"]["edgecolor"], zorder=8, gid=gid)
    xy = np.empty((0, 2)) if data is None else np.atleast_2d(data)
    return ax.plot(xy[:, 0], xy[:, 1], zorder=_ZORDER[kind], gid=gid, **s[kind])


def set_layer(artists: list, gid: str, data) -> bool:
    """Move the artists :func:`add_layer` made to ``data``; False if they cannot follow it (a
    ring more or less), so the caller draws them anew."""
    kind = gid.partition(":")[0]
    if kind == "inflated":
        if len(data) != len(artists):
            return False
        for a, ring in zip(artists, data, strict=True):
            a.set_data(ring[:, 0], ring[:, 1])
        return True
    (a,) = artists
    if hasattr(a, "set_center"):
        a.set_center(data)
    elif hasattr(a, "set_xy"):
        a.set_xy(data)
    else:
        xy = np.empty((0, 2)) if data is None else np.atleast_2d(data)
        a.set_data(xy[:, 0], xy[:, 1])
    return True


def legend_handles(robot_radius: float, units: Units = PIXELS) -> list:
    """Proxy artists for the figure legend, in the styles of :func:`draw_world`; the robot's
    radius (pixels) and the track's length are written in ``units`` (the scenario's).

    Ordered so that a 5-column legend (filled column by column) pairs related entries:
    obstacles, their outline and track, the robot's path and plan, optimum and robot, start and
    goal.
    """
    from matplotlib.lines import Line2D
    from matplotlib.patches import Patch

    s = STYLE
    lab = LEGEND_LABELS
    robot = s["robot"]
    radius = f"r = {units.length(robot_radius):g} {units.length_label}"
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
        Line2D([], [], label=_track_label(units), **s["track"]),
        Line2D([], [], label=lab["trail"], **s["trail"]),
        Line2D([], [], label=lab["plan"], **s["plan"]),
        Line2D([], [], label=lab["optimum"], **s["optimum"]),
        Line2D([], [], label=f"{lab['robot']}, {radius}", **robot_marker),
        Line2D([], [], label=lab["start"], **s["start"]),
        Line2D([], [], label=lab["goal"], **s["goal"]),
    ]


def _track_label(units: Units) -> str:
    if units.is_pixels:
        return LEGEND_LABELS["track"]
    return f"obstacle track ({units.time(TRACK_STEPS):g} s)"
