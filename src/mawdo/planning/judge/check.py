"""Independent collision checker (shapely only; shares no code with the cost kernel).

An executed trajectory is the robot's positions at integer time steps ``t0, t0 + 1, ...``; between
two positions the robot moves in a straight line at constant speed. Over each step, every
obstacle's motion is cut into constant-velocity pieces (the scenario's motion model); on a piece
the robot's position *relative to the obstacle* moves along a straight segment, so the relative
trajectory over the step is a polyline, and its distance to the obstacle's shape (at offset zero)
is the smallest distance between robot centre and obstacle during the step. Clearance is that
distance minus the robot radius (and minus the radius for circles): exact, no time sampling.

Clearance is negative when the robot disc overlaps an obstacle: for a circle it is the exact
signed value; for a polygon, once the robot's centre is inside, it is ``-r`` minus how deep the
centre gets (measured on points ``DEPTH_STEP / 2`` apart; positive exactly when the centre
enters the interior). A collision is a clearance ``< -tol`` (touching is allowed, as in the
oracle; ``tol`` defaults to 1e-9 px so that rounding is not reported).

The map's border is a wall: a step whose robot disc leaves the map ``[0, W] x [0, H]`` by more
than ``tol`` collides with it (``CheckReport.border``). The disc's centre moves along a segment
and the map is a convex box, so the step stays inside exactly when the discs at both ends do;
how far it leaves is ``r`` minus the smallest distance of those ends' centres to the border.

Active and passive collisions: a collision during a step in which the robot moves
is *active* (its own motion took part); one during a step in which it stands still (both ends
within ``REST_TOL`` px) is *passive*: an obstacle ran into a robot at rest (whether some other
action could have avoided it is not judged here). Both are collisions; a run succeeds only with
neither.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import shapely

from mawdo.planning.judge.check_index import near_steps, robot_boxes
from mawdo.planning.world.scenario import CircleObstacle, PolygonObstacle, Scenario

__all__ = ["CheckReport", "check_static_path", "check_trajectory"]

#: Clearance down to ``-DEFAULT_TOL`` (pixels) counts as touching, not as a collision, so that
#: rounding (e.g. a path sliding along an inflated edge) is not reported.
DEFAULT_TOL = 1e-9
#: Spacing (pixels) of the points on which a polygon's penetration depth is measured.
DEPTH_STEP = 0.25
#: A step whose two positions are this close (pixels) is the robot at rest.
REST_TOL = 1e-9
#: From this many moving obstacles on, :func:`check_trajectory` measures only the pairs that
#: come near (below it, measuring every pair costs less than sorting them out).
INDEX_MOVERS = 1000
#: How near (robot radii) a pair must come to be measured, by default, among many obstacles.
INDEX_REACH = 10.0
#: ... and from this many steps on (sorting out costs a few knot queries per obstacle).
INDEX_STEPS = 16


@dataclass(frozen=True)
class CheckReport:
    """Result of a collision check.

    Attributes
    ----------
    ok : bool
        No collision and (for trajectories) the robot's whole disc inside the map.
    collisions : tuple of (int, int)
        ``(step, obstacle index)`` for each step/segment that collides with an obstacle.
    min_clearance : float
        Smallest clearance over all steps and obstacles (pixels; negative = overlap; ``inf``
        without obstacles, or with none within a ``reach``).
    clearance : numpy.ndarray, shape (n_steps, n_obstacles)
        Clearance per step (segment) and obstacle (pixels); ``inf`` for the pairs a ``reach``
        of :func:`check_trajectory` left out (they are farther apart than it).
    out_of_map : tuple of int
        Indices of positions whose centre is outside the map box (trajectories only).
    border : tuple of int
        Steps (segments) whose robot disc leaves the map by more than ``tol``: collisions with
        the map's border (trajectories only).
    border_excess : float
        How far the disc leaves the map at worst (pixels; <= 0: it stays inside, ``-inf``
        without a map, as for :func:`check_static_path`).
    active, passive : tuple of (int, int)
        The ``collisions`` split by whether the robot moves during the step (active) or stands
        still (passive: hit at rest); together they are ``collisions``.
    active_time, passive_time : float
        Start time (time steps) of the first step with an active / passive collision; ``nan``
        when there is none (and for :func:`check_static_path`, which has no times).
    """

    ok: bool
    collisions: tuple[tuple[int, int], ...]
    min_clearance: float
    clearance: np.ndarray
    out_of_map: tuple[int, ...] = ()
    border: tuple[int, ...] = ()
    border_excess: float = -np.inf
    active: tuple[tuple[int, int], ...] = ()
    passive: tuple[tuple[int, int], ...] = ()
    active_time: float = np.nan
    passive_time: float = np.nan

    @property
    def hits(self) -> int:
        """Collisions with obstacles and with the map's border, ``(step, obstacle)`` pairs and
        steps counted one each."""
        return len(self.collisions) + len(self.border)

    def describe(self) -> str:
        """Why the check failed, in words (``"ok"`` when it passed), e.g. ``"2 collisions with
        obstacles; route leaves the map by 1.5 px"``."""
        parts = []
        if self.collisions:
            parts.append(
                f"{len(self.collisions)} collisions with obstacles ({len(self.active)} active, "
                f"{len(self.passive)} passive)"
            )
        if self.border:
            parts.append(f"route leaves the map by {self.border_excess:.3g} px")
        return "; ".join(parts) if parts else "ok"


def _polygon_depth(geoms: np.ndarray, poly) -> np.ndarray:
    """How far each geometry reaches into the polygon's interior (pixels; 0 if it only touches).

    The part of the geometry inside the polygon is cut into pieces of at most ``DEPTH_STEP``;
    the depth is the largest distance to the polygon's boundary over the pieces' ends and
    midpoints, so it is positive exactly when the geometry enters the interior and within
    ``DEPTH_STEP / 4`` of the true depth.
    """
    depth = np.zeros(len(geoms))
    boundary = poly.boundary
    for k in np.nonzero(shapely.distance(geoms, poly) == 0.0)[0]:
        g = geoms[k]
        if shapely.length(g) == 0.0:  # a point (the robot does not move relative to it)
            pts = shapely.get_coordinates(g)[:1]
        else:
            clip = shapely.segmentize(shapely.intersection(g, poly), DEPTH_STEP)
            parts = [shapely.get_coordinates(p) for p in getattr(clip, "geoms", [clip])]
            parts = [c for c in parts if len(c) >= 2]
            if not parts:
                continue
            pts = np.concatenate([np.vstack([c, 0.5 * (c[:-1] + c[1:])]) for c in parts])
        inside = shapely.contains_xy(poly, pts[:, 0], pts[:, 1])
        if np.any(inside):
            depth[k] = float(np.max(shapely.distance(shapely.points(pts[inside]), boundary)))
    return depth


def _shape_distance(shape, lines: np.ndarray) -> np.ndarray:
    """Signed distance (pixels) from each line to the raw shape: negative when it goes inside.

    Circles exactly (distance to the centre minus the radius); polygons by their distance, or
    minus the penetration depth (:func:`_polygon_depth`).
    """
    if isinstance(shape, CircleObstacle):
        return shapely.distance(lines, shapely.Point(shape.center)) - shape.radius
    poly = shape if not isinstance(shape, PolygonObstacle) else shapely.Polygon(shape.vertices)
    return shapely.distance(lines, poly) - _polygon_depth(lines, poly)


def _split(collisions, moving: np.ndarray, times) -> dict:
    """The collisions split by ``moving[step]``, with the start time of each kind's first."""
    out = {}
    for name, want in (("active", True), ("passive", False)):
        part = tuple(c for c in collisions if bool(moving[c[0]]) == want)
        first = float(times[part[0][0]]) if part and times is not None else np.nan
        out[name], out[name + "_time"] = part, first
    return out


def _report(
    clearance: np.ndarray, tol: float, moving, times=None, out_of_map=(), excess=None
) -> CheckReport:
    """The report; ``moving[s]``: the robot moves during step ``s``; ``times``: the steps'
    start times (time steps); ``excess``: how far each step's disc leaves the map (pixels)."""
    steps, obs = np.nonzero(clearance < -tol)
    collisions = tuple((int(s), int(o)) for s, o in zip(steps, obs, strict=True))
    min_c = float(clearance.min()) if clearance.size else np.inf
    border, worst = (), -np.inf
    if excess is not None:
        border = tuple(int(s) for s in np.nonzero(excess > tol)[0])
        worst = float(excess.max())
    ok = not collisions and not out_of_map and not border
    return CheckReport(
        ok, collisions, min_c, clearance, tuple(out_of_map), border, worst,
        **_split(collisions, moving, times),
    )  # fmt: skip


def _moving(p: np.ndarray) -> np.ndarray:
    """Per step ``p[s] -> p[s + 1]``: the robot moves (by more than ``REST_TOL`` px)."""
    return np.hypot(*np.diff(p, axis=0).T) > REST_TOL


def _border_excess(p: np.ndarray, radius: float, width: float, height: float) -> np.ndarray:
    """How far the robot disc leaves the map over each step ``p[s] -> p[s + 1]`` (pixels;
    negative: its distance inside). A disc moving straight stays in the convex box exactly
    when it does at both ends, so the worst end decides."""
    inner = np.min(np.column_stack([p[:, 0], p[:, 1], width - p[:, 0], height - p[:, 1]]), axis=1)
    out = radius - inner
    return np.maximum(out[:-1], out[1:])


def _as_points(path, what: str) -> np.ndarray:
    p = np.asarray(path, dtype=float)
    if p.ndim != 2 or p.shape[1] != 2 or len(p) < 1:
        raise ValueError(f"{what} must have shape (k, 2) with k >= 1, got {p.shape}")
    if not np.all(np.isfinite(p)):
        raise ValueError(f"{what} must be finite")
    return p


def _relative_coords(o, p: np.ndarray, times: np.ndarray, steps) -> list[np.ndarray]:
    """Per step in ``steps``, the vertices of the robot centre's polyline in moving obstacle
    ``o``'s frame (one straight piece per constant-velocity piece of its motion; at least
    two vertices)."""
    coords = []
    for s in steps:
        ta, tb = times[s], times[s + 1]
        tk, ok = o.knots(ta, tb)
        frac = (tk - ta) / (tb - ta) if tb > ta else np.zeros_like(tk)
        robot = p[s] + frac[:, None] * (p[s + 1] - p[s])
        rel = robot - ok  # robot centre in the obstacle's frame, linear per piece
        if len(rel) == 1:
            rel = np.vstack([rel, rel])
        coords.append(rel)
    return coords


def _linestrings(coords: list[np.ndarray]) -> np.ndarray:
    """One shapely linestring per vertex array, made in one call."""
    index = np.repeat(np.arange(len(coords)), [len(c) for c in coords])
    return shapely.linestrings(np.concatenate(coords), indices=index)


def _relative_lines(o, p: np.ndarray, times: np.ndarray, steps) -> np.ndarray:
    """Per step in ``steps``, the robot centre's polyline in moving obstacle ``o``'s frame
    (one straight piece per constant-velocity piece of its motion), as shapely linestrings."""
    return _linestrings(_relative_coords(o, p, times, steps))


def _moving_circle_clearances(circles, p, times, steps_of, r: float, clearance) -> None:
    """``clearance[steps, o.index]`` of every moving circle ``o`` (its ``steps_of(o)``): the
    same distances as :func:`_shape_distance` gives one obstacle at a time, measured for all
    of them in one shapely call (a guard checks some forty moves a step among many people)."""
    coords, rows, cols, centres, radii = [], [], [], [], []
    for o in circles:
        steps = steps_of(o)
        if not len(steps):
            continue
        coords += _relative_coords(o, p, times, steps)
        rows.append(steps)
        cols += [o.index] * len(steps)
        centres += [o.shape.center] * len(steps)
        radii += [float(o.shape.radius)] * len(steps)
    if not coords:
        return
    gap = shapely.distance(_linestrings(coords), shapely.points(np.array(centres, dtype=float)))
    clearance[np.concatenate(rows), np.array(cols)] = (gap - np.array(radii)) - r


def check_trajectory(
    positions,
    scenario: Scenario,
    t0: float = 0.0,
    tol: float = DEFAULT_TOL,
    times=None,
    reach: float | None = None,
) -> CheckReport:
    """Check an executed trajectory against the scenario's moving and static obstacles.

    Parameters
    ----------
    positions : array_like, shape (k, 2)
        Robot centre at times ``t0, t0 + 1, ..., t0 + k - 1`` (pixels), moving in a straight
        line at constant speed in between. A single position is checked at ``t0`` only.
    scenario : Scenario
        Obstacles, their motion and the robot radius.
    t0 : float
        Time of the first position (time steps), >= 0.
    tol : float
        Clearance below ``-tol`` (pixels) is a collision.
    times : array_like, shape (k,), optional
        Explicit, non-decreasing times of the positions (time steps), e.g. the vertices of a
        path followed at constant speed; overrides ``t0``.
    reach : float, optional
        Measure a moving obstacle only over the steps where its swept box comes within
        ``reach`` px of the robot's disc (:mod:`~mawdo.planning.judge.check_index`); the other
        pairs are more than ``reach`` px apart and hold ``inf`` in ``clearance``. Collisions,
        and every clearance up to ``reach``, are those of measuring every pair. ``inf``:
        measure every pair. None (default): :data:`INDEX_REACH` robot radii with
        :data:`INDEX_MOVERS` moving obstacles or more and :data:`INDEX_STEPS` steps or more,
        else ``inf``.

    Returns
    -------
    CheckReport
        ``collisions`` lists ``(step, obstacle)``: step ``s`` is the move from position ``s`` to
        ``s + 1`` (step 0 for a single position, the robot at rest); ``active`` and ``passive``
        split them by whether the robot moves in that step; ``border`` the steps whose robot
        disc leaves the map (:meth:`CheckReport.describe` says by how much).

    Raises
    ------
    ValueError
        Positions or times of the wrong shape, non-finite, decreasing or negative times, or a
        negative ``reach``.

    Notes
    -----
    The map's border counts as a wall (see the module docstring).
    """
    p = _as_points(positions, "positions")
    if times is None:
        times = t0 + np.arange(len(p), dtype=float)
    else:
        times = np.asarray(times, dtype=float)
        if times.shape != (len(p),) or not np.all(np.isfinite(times)):
            raise ValueError(f"times must be finite with shape ({len(p)},), got {times.shape}")
        if np.any(np.diff(times) < 0):
            raise ValueError("times must be non-decreasing")
    if times.size and times[0] < 0:
        raise ValueError(f"times must be >= 0, got {times[0]!r}")
    if len(p) == 1:
        p = np.vstack([p, p])
        times = np.array([times[0], times[0]])
    r = scenario.robot_radius
    W, H = scenario.width, scenario.height
    outside = np.nonzero((p[:, 0] < 0) | (p[:, 0] > W) | (p[:, 1] < 0) | (p[:, 1] > H))[0]
    n_steps = len(p) - 1
    clearance = np.full((n_steps, len(scenario.obstacles)), np.inf)
    static_lines = shapely.linestrings(np.stack([p[:-1], p[1:]], axis=1))
    if reach is None:
        many = len(scenario.obstacles) - len(scenario.static_indices) >= INDEX_MOVERS
        reach = INDEX_REACH * r if many and n_steps >= INDEX_STEPS else np.inf
    elif not reach >= 0:
        raise ValueError(f"reach must be >= 0 px (inf: every pair), got {reach!r}")
    grown = robot_boxes(p, r + reach) if np.isfinite(reach) else None

    def steps_of(o):
        return np.arange(n_steps) if grown is None else near_steps(o, p, times, grown)

    circles, posts = [], []
    for o in scenario.obstacles:
        if o.is_static and isinstance(o.shape, CircleObstacle):
            posts.append(o)
        elif o.is_static:  # no knots: the relative trajectory is the route itself
            clearance[:, o.index] = _shape_distance(o.shape, static_lines) - r
        elif isinstance(o.shape, CircleObstacle):
            circles.append(o)
        else:
            steps = steps_of(o)
            if len(steps):
                lines = _relative_lines(o, p, times, steps)
                clearance[steps, o.index] = _shape_distance(o.shape, lines) - r
    _moving_circle_clearances(circles, p, times, steps_of, r, clearance)
    if posts:  # standing circles: every step against every centre, in one call
        centres = shapely.points(np.array([o.shape.center for o in posts], dtype=float))
        gap = shapely.distance(static_lines[:, None], centres[None, :])
        radii = np.array([float(o.shape.radius) for o in posts])
        clearance[:, [o.index for o in posts]] = (gap - radii) - r
    return _report(
        clearance, tol, _moving(p), times[:-1], [int(i) for i in outside],
        _border_excess(p, r, W, H),
    )  # fmt: skip


def check_static_path(
    path, obstacles, radius: float = 0.0, tol: float = DEFAULT_TOL
) -> CheckReport:
    """Check a polyline against obstacles that do not move.

    Parameters
    ----------
    path : array_like, shape (k, 2)
        Path vertices (pixels).
    obstacles : sequence
        Shapely geometries, or obstacle shapes from a scenario (``CircleObstacle`` /
        ``PolygonObstacle``, tested exactly at offset zero).
    radius : float
        Robot radius (pixels) subtracted from every distance (0 if the obstacles are inflated).
    tol : float
        Clearance below ``-tol`` (pixels) is a collision.

    Returns
    -------
    CheckReport
        ``collisions`` lists ``(segment, obstacle)`` (segment 0 for a single point);
        ``active`` those on segments of non-zero length, ``passive`` those at a point.
    """
    p = _as_points(path, "path")
    if len(p) == 1:
        p = np.vstack([p, p])
    lines = shapely.linestrings(np.stack([p[:-1], p[1:]], axis=1))
    clearance = np.full((len(lines), len(obstacles)), np.inf)
    for j, ob in enumerate(obstacles):
        clearance[:, j] = _shape_distance(ob, lines) - radius
    return _report(clearance, tol, _moving(p))
