"""One map panel: obstacles (inflated, tracks), executed path, current plan, optimum, robot;
and the legend that names them. The snapshot grid and the animation both draw with it."""

from __future__ import annotations

import numpy as np

from mawdo.planning.geometry import inflated_obstacles
from mawdo.planning.planner import PlanResult
from mawdo.planning.render.style import (
    _LEGEND_LABELS,
    _STYLE,
    TRACK_STEPS,
    _active_replan,
    _fmt_time,
    _reference_point,
    _rings,
    _route,
    _trail_until,
)
from mawdo.planning.scenario import Scenario


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

    Long by design: one panel's layers in drawing order, each a short block.

    Long because each layer of the panel is a few plotting calls in drawing order.

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
