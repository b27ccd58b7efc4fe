"""Who is at fault in a collision: the robot, or the agent that ran into it.

With people who react, "the robot stood still" is too narrow a notion of innocence. A collision is
**robot-caused** when, at the first contact within the colliding step, the robot's velocity has a
positive component toward the obstacle (toward the obstacle's centre for a disc, toward the nearest
point of its shape for a polygon); a robot that moves into a space the obstacle already occupies
(contact at the very start of the step) is judged the same way. A moving robot that touches a
static obstacle always caused it. Every other collision (the robot at rest, or moving away or
sideways while the obstacle closes in) is the obstacle's. Success needs
neither kind. This follows the usual reading in the crowd-navigation literature, where a robot is
blamed for the contacts its own motion produces.

Contact times are exact for discs (a quadratic per constant-velocity piece); for polygons the first
contact is located on points :data:`SAMPLES` apart in each piece, enough to give the direction of
approach (the collision itself is the independent checker's exact verdict).
"""

from __future__ import annotations

import numpy as np
import shapely

from mawdo.planning.world.scenario import CircleObstacle, Scenario

__all__ = ["SAMPLES", "blame"]

#: Points per constant-velocity piece on which a polygon's first contact is located.
SAMPLES = 64
#: A velocity component toward the obstacle above this (pixels per step) is an approach.
APPROACH_TOL = 1e-9


def _first_disc_contact(rel0, rel1, centre, reach: float) -> float | None:
    """Earliest ``u`` in [0, 1] with ``|rel0 + u (rel1 - rel0) - centre| <= reach``."""
    d0 = np.asarray(rel0) - centre
    dv = np.asarray(rel1) - np.asarray(rel0)
    a, b, c = dv @ dv, 2.0 * (d0 @ dv), d0 @ d0 - reach * reach
    if c <= 0.0:
        return 0.0
    if a <= 0.0:
        return None
    disc = b * b - 4.0 * a * c
    if disc < 0.0:
        return None
    u = (-b - np.sqrt(disc)) / (2.0 * a)
    return float(u) if 0.0 <= u <= 1.0 else None


def _first_polygon_contact(rel0, rel1, poly, reach: float) -> float | None:
    u = np.linspace(0.0, 1.0, SAMPLES + 1)
    pts = np.asarray(rel0) + u[:, None] * (np.asarray(rel1) - np.asarray(rel0))
    d = shapely.distance(shapely.points(pts), poly)
    hit = np.nonzero(d <= reach)[0]
    return float(u[hit[0]]) if len(hit) else None


def _contact(route, times, s: int, obstacle, radius: float):
    """The robot centre relative to the obstacle's frame at the first contact in step ``s``,
    and the time of it; ``None`` when the pieces never come within reach (a polygon that
    only the depth measure flags)."""
    ta, tb = float(times[s]), float(times[s + 1])
    pa, pb = np.asarray(route[s], float), np.asarray(route[s + 1], float)
    tk, ok = obstacle.knots(ta, tb)
    if len(tk) == 1:
        tk, ok = np.array([ta, ta]), np.vstack([ok, ok])
    shape = obstacle.shape
    circle = isinstance(shape, CircleObstacle)
    poly = None if circle else shapely.Polygon(shape.vertices)
    reach = radius + (shape.radius if circle else 0.0)
    for k in range(len(tk) - 1):
        fa = (tk[k] - ta) / (tb - ta) if tb > ta else 0.0
        fb = (tk[k + 1] - ta) / (tb - ta) if tb > ta else 0.0
        rel0 = pa + fa * (pb - pa) - ok[k]
        rel1 = pa + fb * (pb - pa) - ok[k + 1]
        if circle:
            u = _first_disc_contact(rel0, rel1, np.asarray(shape.center, float), reach)
        else:
            u = _first_polygon_contact(rel0, rel1, poly, reach)
        if u is not None:
            return rel0 + u * (rel1 - rel0), poly
    return None


def blame(route, times, scenario: Scenario, collisions) -> tuple[tuple, tuple]:
    """Split the checker's collisions into robot-caused and other ones.

    Parameters
    ----------
    route : array_like, shape (k, 2)
        The executed route (pixels), as given to
        :func:`~mawdo.planning.judge.check.check_trajectory`.
    times : array_like, shape (k,)
        Its time stamps (time steps).
    scenario : Scenario
        The scenario the route was checked against (realised motions).
    collisions : sequence of (int, int)
        The checker's ``(segment, obstacle index)`` pairs.

    Returns
    -------
    robot_caused, other : tuple of (int, int)
        The pairs split by fault (see the module docstring).
    """
    route = np.asarray(route, dtype=float)
    times = np.asarray(times, dtype=float)
    mine, theirs = [], []
    for s, o in collisions:
        obstacle = scenario.obstacles[o]
        dt = times[s + 1] - times[s]
        v = (route[s + 1] - route[s]) / dt if dt > 0 else np.zeros(2)
        if not np.any(v):
            theirs.append((s, o))
            continue
        if obstacle.is_static:  # only the robot's own motion brings it into a wall
            mine.append((s, o))
            continue
        hit = _contact(route, times, s, obstacle, scenario.robot_radius)
        if hit is None:
            theirs.append((s, o))
            continue
        rel, poly = hit
        if poly is None:  # a disc: toward its centre
            toward = np.asarray(obstacle.shape.center, float) - rel
        elif shapely.contains_xy(poly, *rel):  # already inside: toward its middle
            toward = np.asarray(poly.centroid.coords[0]) - rel
        else:  # a polygon: toward its nearest point
            near = shapely.shortest_line(shapely.Point(rel), poly).coords[-1]
            toward = np.asarray(near) - rel
        (mine if float(v @ toward) > APPROACH_TOL else theirs).append((s, o))
    return tuple(mine), tuple(theirs)
