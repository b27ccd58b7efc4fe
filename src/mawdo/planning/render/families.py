"""Gallery of the scene families where time decides: one panel per scene.

Each panel shows the world at ``t = 0`` (:func:`~mawdo.planning.render.world.draw_world`:
obstacles, their inflation, start, goal, the static optimum), each moving obstacle's future
track up to the earliest arrival ``T*`` with an arrow for where it heads first, the waiting
spots of the scene, and the earliest-arrival route (:mod:`mawdo.planning.guide.sipp.optimum`) with
its waits marked. Made outside ``pyplot`` like every planning figure.

>>> timed_gallery("docs/img/families_time.png")  # doctest: +SKIP
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from mawdo.planning.render.style import (
    GRID_DPI,
    IMAGE_SUFFIXES,
    PANEL_IN,
    checked_output_path,
    new_figure,
    reference_point,
    save_figure,
)
from mawdo.planning.render.world import draw_world

__all__ = ["timed_gallery", "timed_panel"]

_ROUTE = {"color": "tab:red", "lw": 1.4, "marker": "o", "ms": 2.0, "zorder": 6}
_FUTURE = {"color": "0.4", "lw": 0.7, "ls": (0, (2, 2)), "alpha": 0.6, "zorder": 1.6}
#: Shortest wait (time steps) labelled on a panel: the search's touching-contact nudges are not.
_WAIT_LABEL = 0.5
_ARROW = {"arrowstyle": "-|>", "color": "tab:orange", "lw": 1.6, "mutation_scale": 10}


def _first_move(ob, t_end: float) -> tuple[np.ndarray, np.ndarray] | None:
    """Where the obstacle's reference point is at ``t = 0`` and once it has moved by twice its
    size (or where it gets farthest by ``t_end``); ``None`` if it never moves before then."""
    ts = np.linspace(0.0, t_end, 400)
    pts = reference_point(ob) + ob.offset(ts)
    step = np.hypot(*(pts - pts[0]).T)
    size = max(float(np.ptp(np.reshape(ob.shape.bounds(), (2, 2)), axis=0).max()), 1.0)
    far = np.nonzero(step >= 2.0 * size)[0]
    if step.max() <= 1e-9:
        return None
    return pts[0], pts[far[0] if len(far) else int(np.argmax(step))]


def timed_panel(ax, scene, small: float = 7.0) -> None:
    """Draw one timed scene on ``ax`` (see the module docstring).

    Parameters
    ----------
    ax : matplotlib.axes.Axes
    scene : mawdo.planning.scenes.Scene
        A scene of a timed family (``scene.t_star`` and ``scene.time_route`` set).
    small : float
        Font size of ticks and title (points).
    """
    sc, route = scene.scenario, scene.time_route
    v = sc.robot_speed
    title = (
        f"{scene.family}: T* {scene.t_star:.1f}, L*/v {scene.l_star / v:.1f}, "
        f"waits {route.waiting:.1f} (steps)"
    )
    draw_world(ax, sc, 0.0, optimum=scene.optimum, track=0.0, title=title, small=small)
    horizon = max(scene.t_star, 1.0)
    for i in sc.moving_indices:
        ob = sc.obstacles[i]
        ts = np.linspace(0.0, horizon, 300)
        future = reference_point(ob) + ob.offset(ts)
        ax.plot(*future.T, **_FUTURE)
        move = _first_move(ob, horizon)
        if move is not None:
            ax.annotate("", xy=move[1], xytext=move[0], arrowprops=_ARROW, zorder=6)
    if len(scene.spots):
        ax.plot(*scene.spots.T, ls="none", marker=".", ms=2.5, color="tab:olive", zorder=5)
    ax.plot(*route.points.T, gid="time-route", **_ROUTE)
    same = np.all(route.points[1:] == route.points[:-1], axis=1)
    same &= np.diff(route.times) >= _WAIT_LABEL
    for p, dt in zip(route.points[1:][same], np.diff(route.times)[same], strict=True):
        ax.plot(*p, marker="o", ms=7, mfc="none", mec="tab:red", mew=1.2, zorder=7)
        ax.annotate(
            f"wait {dt:.0f}", p, xytext=(4, 4), textcoords="offset points", fontsize=small - 1
        )


def _legend(fig) -> None:
    from matplotlib.lines import Line2D

    handles = [
        Line2D([], [], **{k: v for k, v in _ROUTE.items() if k != "zorder"}),
        Line2D([], [], marker="o", ms=7, mfc="none", mec="tab:red", ls="none"),
        Line2D([], [], **{k: v for k, v in _FUTURE.items() if k != "zorder"}),
        Line2D([], [], marker=".", ms=5, color="tab:olive", ls="none"),
        Line2D([], [], color="tab:green", lw=1.0, ls=(0, (5, 3))),
    ]
    labels = [
        "earliest-arrival route (T*)",
        "robot waits",
        "obstacle track until T* (arrow: heading)",
        "waiting spots",
        "static optimum (L*)",
    ]
    fig.legend(handles, labels, loc="outside lower center", ncol=3, fontsize=7, frameon=False)


def timed_gallery(
    path=None, scenes=None, seed: int = 0, index: int = 0, cols: int = 3, dpi: int = GRID_DPI
):
    """One panel per timed scene; default: scene ``index`` of every timed family for ``seed``.

    Parameters
    ----------
    path : str or pathlib.Path, optional
        Output file (``.png``, ``.svg`` or ``.pdf``); without it the figure is returned.
    scenes : sequence of Scene, optional
        Scenes of timed families (default: one per family of
        :data:`~mawdo.planning.scenes.TIMED_FAMILIES`).
    seed, index : int
        Which scene of each family when ``scenes`` is not given (>= 0).
    cols : int
        Panels per row (>= 1).
    dpi : int
        Resolution (dots per inch).

    Returns
    -------
    pathlib.Path or matplotlib.figure.Figure
        The file written, or the figure when ``path`` is ``None``.
    """
    from mawdo.planning.scenes import TIMED_FAMILIES, generate_scene

    out = None if path is None else checked_output_path(path, IMAGE_SUFFIXES)
    if scenes is None:
        scenes = [generate_scene(f, index, seed=seed) for f in TIMED_FAMILIES]
    scenes = list(scenes)
    if not scenes or any(s.t_star is None for s in scenes):
        raise ValueError("timed_gallery needs scenes of timed families (with a T*)")
    if isinstance(cols, bool) or not isinstance(cols, int) or cols < 1:
        raise ValueError(f"cols must be an integer >= 1, got {cols!r}")
    rows = -(-len(scenes) // cols)
    fig = new_figure((cols * PANEL_IN, rows * PANEL_IN + 0.6), dpi)
    axes = np.atleast_1d(fig.subplots(rows, cols, squeeze=False)).ravel()
    for ax, scene in zip(axes, scenes, strict=False):
        timed_panel(ax, scene)
    for ax in axes[len(scenes) :]:
        ax.set_axis_off()
    _legend(fig)
    if out is None:
        return fig
    return save_figure(fig, Path(out), dpi=dpi)
