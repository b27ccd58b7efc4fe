"""Static scene families that punish greedy planners: u_trap and narrow passages."""

from __future__ import annotations

import numpy as np

from mawdo.planning.scenes.base import Family, Param, Redraw, draft
from mawdo.planning.scenes.shapes import box, convex_polygon, diagonal_endpoints, place, polygon

__all__ = ["NARROW", "U_TRAP"]


def _u_polygon(depth: float, width: float, t: float) -> np.ndarray:
    """A U in local coordinates ``(a, b)``: closed end at ``a in [0, t]``, arms toward ``-a``."""
    w = width / 2
    return np.array(
        [
            [-depth, w + t],
            [t, w + t],
            [t, -w - t],
            [-depth, -w - t],
            [-depth, -w],
            [0.0, -w],
            [0.0, w],
            [-depth, w],
        ]
    )


def _draw_u_trap(rng: np.random.Generator, p: dict) -> dict:
    m = max(0.04 * p["size"], p["robot_radius"] + p["clearance"] + 1.0)
    start, goal = diagonal_endpoints(rng, p, m)
    d = goal - start
    dist = float(np.hypot(*d))
    d /= dist
    n = np.array([-d[1], d[0]])
    depth, t = p["depth"], p["thickness"]
    # the closed end sits on the start-goal line; the mouth faces the start and stays ahead of it
    a0 = rng.uniform(0.45, 0.65) * dist
    mouth = a0 - depth
    if mouth < p["robot_radius"] + p["clearance"] + 1.0:
        raise Redraw("the U's mouth would swallow the start (depth too large for the map)")
    shift = rng.uniform(-0.15, 0.15) * p["width"]  # the line does not always hit the U's centre
    local = _u_polygon(depth, p["width"], t)
    world = start + (a0 + local[:, :1]) * d + (shift + local[:, 1:]) * n
    obs = [polygon(world)]
    s = p["size"]
    keep = [(pt, p["robot_radius"] + p["clearance"] + 1.0) for pt in (start, goal)]

    def one(rng):
        c, rad = rng.uniform(0.05 * s, 0.95 * s, 2), float(rng.uniform(8.0, 20.0))
        v = convex_polygon(rng, c, rad)
        return polygon(v), lambda pt: np.hypot(*(np.asarray(pt) - c)) - rad

    obs += [place(rng, one, keep) for _ in range(p["clutter"])]
    return draft(p, start, goal, obs)


U_TRAP = Family(
    "u_trap",
    "a U-shaped wall across the start-goal line, open toward the start, plus optional clutter",
    (
        Param("depth", 110.0, 10.0, 600.0, doc="arm length of the U, pixels"),
        Param("width", 120.0, 10.0, 600.0, doc="inner width of the U, pixels"),
        Param("thickness", 10.0, 2.0, 40.0, doc="wall thickness, pixels"),
        Param("clutter", 0, 0, 20, integer=True, doc="extra small convex obstacles"),
    ),
    _draw_u_trap,
)


def _draw_narrow(rng: np.random.Generator, p: dict) -> dict:
    s, k, t = p["size"], p["walls"], p["thickness"]
    gap = 2.0 * p["robot_radius"] + p["slack"]
    m = max(0.04 * s, p["robot_radius"] + p["clearance"] + 1.0)
    pitch = s / (k + 1)
    xs = pitch * np.arange(1, k + 1) + rng.uniform(-0.15, 0.15, k) * pitch
    obs = []
    for x in xs:
        # gaps anywhere but the outer tenth, not overlapping: sorted draws, re-drawn if too close
        y0 = np.sort(rng.uniform(0.1 * s, 0.9 * s - gap, p["gaps"]))
        if np.any(np.diff(y0) < gap + t):
            raise Redraw("two gaps of a wall overlap")
        edges = [0.0, *np.ravel(np.column_stack([y0, y0 + gap])), s]
        for a, b in zip(edges[0::2], edges[1::2], strict=True):
            if b > a:
                obs.append(box(x - t / 2, a, x + t / 2, b))
    need = t / 2 + p["robot_radius"] + p["clearance"] + 1.0
    if xs[0] - need < m or xs[-1] + need > s - m:
        raise Redraw("no room for start or goal beside the outer walls")
    start = rng.uniform([m, m], [xs[0] - need, s - m])
    goal = rng.uniform([xs[-1] + need, m], [s - m, s - m])
    return draft(p, start, goal, obs)


def _check_narrow(p: dict) -> None:
    pitch = p["size"] / (p["walls"] + 1)
    need = p["thickness"] + 2 * (p["robot_radius"] + p["clearance"]) + 2
    if 0.7 * pitch <= need:
        raise ValueError(
            f"narrow walls = {p['walls']} are ~{0.7 * pitch:.0f} px apart, too close for the "
            f"robot and walls ({need:.0f} px): fewer walls or a larger size"
        )
    gap = 2 * p["robot_radius"] + p["slack"]
    if p["gaps"] * (gap + p["thickness"]) > 0.6 * p["size"]:
        raise ValueError(f"narrow gaps = {p['gaps']} of {gap:g} px do not fit in one wall")


NARROW = Family(
    "narrow",
    "full-height walls pierced by passages barely wider than the robot",
    (
        Param("walls", 1, 1, 5, integer=True, doc="number of walls between start and goal"),
        Param("gaps", 1, 1, 4, integer=True, doc="passages per wall"),
        Param("slack", 3.0, 0.5, 60.0, doc="passage width beyond the robot diameter, pixels"),
        Param("thickness", 24.0, 2.0, 80.0, doc="wall thickness (passage length), pixels"),
    ),
    _draw_narrow,
    check=_check_narrow,
)
