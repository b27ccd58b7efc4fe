"""Obstacle geometry: shapely shapes, inflation by the robot radius, flat arrays for the kernel.

Inflation
---------
Planning treats the robot as a point and grows every obstacle by the robot radius ``r`` (the
Minkowski sum of the shape and a disc of radius ``r``). Two representations are used:

* **Exact, as a distance test** (cost kernel, checker): a point is in the inflated obstacle iff its
  distance to the raw shape is ``<= r``; a circle of radius ``R`` becomes a circle of radius
  ``R + r``. No approximation at all.
* **Containing polygon** (:func:`inflate`, for the oracle and drawings): the disc is replaced by a
  regular ``CIRCLE_SEGMENTS``-gon *circumscribed* about it, and the shape is Minkowski-summed with
  that polygon. The result contains the true inflated shape, so paths that avoid it are truly
  collision-free, and it exceeds it by at most ``r (1 / cos(pi / n) - 1)`` pixels
  (0.019 px for ``r = 4``, ``n = 32``). The polygon's flat sides are aligned with the axes, so an
  axis-aligned box grows by exactly ``r`` on each side.

The map's border is a wall too: grown by ``r`` it leaves the centre the map shrunk by ``r`` on
every side (:func:`centre_box`).
"""

from __future__ import annotations

import functools
import math
import weakref
from dataclasses import dataclass

import numpy as np
import shapely

from mawdo.planning.world.scenario import CircleObstacle, Obstacle, Scenario

__all__ = [
    "CIRCLE_SEGMENTS",
    "FlatObstacles",
    "centre_box",
    "MotionTable",
    "circumscribed_polygon",
    "inflate",
    "inflated_obstacles",
    "shape_geometry",
]

#: Sides of the regular polygon that replaces a disc (circles and round corners).
CIRCLE_SEGMENTS = 32


def centre_box(scenario: Scenario, margin: float) -> tuple[float, float, float, float]:
    """Where the robot's centre may go: the map shrunk by ``margin`` (pixels, >= 0; the robot
    radius, plus any clearance) on every side, as ``(xmin, ymin, xmax, ymax)``.

    A map narrower than ``2 margin`` leaves the line (or point) through its middle, so the box
    is never inverted.
    """
    mx = min(float(margin), 0.5 * float(scenario.width))
    my = min(float(margin), 0.5 * float(scenario.height))
    return (mx, my, float(scenario.width) - mx, float(scenario.height) - my)


def circumscribed_polygon(center, radius: float, n: int = CIRCLE_SEGMENTS) -> shapely.Polygon:
    """Regular ``n``-gon whose inscribed circle is the disc ``(center, radius)`` (pixels).

    Vertices sit at angles ``(2k + 1) pi / n`` so the edge normals point along ``2k pi / n``,
    i.e. along the axes when ``n`` is a multiple of 4.
    """
    if radius <= 0:
        return shapely.Point(center)
    cos_a, sin_a, inv = _unit_polygon(int(n))
    rho = radius / inv  # circumradius of a polygon with apothem `radius`
    x = center[0] + rho * cos_a
    y = center[1] + rho * sin_a
    return shapely.Polygon(np.column_stack([x, y]))


@functools.lru_cache(maxsize=16)
def _unit_polygon(n: int) -> tuple[np.ndarray, np.ndarray, float]:
    """Cosines and sines of the ``n``-gon's vertex angles and ``cos(pi / n)``, computed once
    per ``n`` (the oracle follower builds hundreds of polygons per run)."""
    angles = (2.0 * np.arange(n) + 1.0) * np.pi / n
    cos_a, sin_a = np.cos(angles), np.sin(angles)
    cos_a.flags.writeable = sin_a.flags.writeable = False
    return cos_a, sin_a, np.cos(np.pi / n)


def shape_geometry(shape, offset=(0.0, 0.0), n: int = CIRCLE_SEGMENTS):
    """Shapely geometry of a raw (not inflated) obstacle shape translated by ``offset``.

    A circle becomes its circumscribed ``n``-gon (contains the disc).
    """
    dx, dy = float(offset[0]), float(offset[1])
    if isinstance(shape, CircleObstacle):
        return circumscribed_polygon((shape.center[0] + dx, shape.center[1] + dy), shape.radius, n)
    return shapely.Polygon(np.asarray(shape.vertices, dtype=float) + (dx, dy))


def inflate(shape, r: float, offset=(0.0, 0.0), n: int = CIRCLE_SEGMENTS) -> shapely.Polygon:
    """Polygon containing the obstacle shape grown by the robot radius ``r`` (pixels).

    Parameters
    ----------
    shape : CircleObstacle or PolygonObstacle
        Obstacle shape spec.
    r : float
        Robot radius (pixels), ``>= 0``.
    offset : array_like, shape (2,)
        Translation of the shape (pixels).
    n : int
        Sides of the polygon replacing a disc.

    Returns
    -------
    shapely.Polygon
        Contains ``shape (+) disc(r)``; the excess is at most ``(R + r)(1/cos(pi/n) - 1)`` px
        for a circle of radius ``R`` and ``r (1/cos(pi/n) - 1)`` px for a polygon.
    """
    dx, dy = float(offset[0]), float(offset[1])
    if isinstance(shape, CircleObstacle):
        c = (shape.center[0] + dx, shape.center[1] + dy)
        return circumscribed_polygon(c, shape.radius + r, n)
    poly = shapely.Polygon(np.asarray(shape.vertices, dtype=float) + (dx, dy))
    if r <= 0:
        return poly
    # P (+) Q = P  u  union over edges of hull(a + Q, b + Q), exact for a simple polygon P and a
    # convex Q; Q is the circumscribed n-gon, which contains the disc.
    q = np.asarray(circumscribed_polygon((0.0, 0.0), r, n).exterior.coords)[:-1]
    ring = np.asarray(poly.exterior.coords)
    a, b = ring[:-1], ring[1:]
    pts = np.concatenate([a[:, None, :] + q[None], b[:, None, :] + q[None]], axis=1)
    hulls = shapely.convex_hull(shapely.multipoints(pts))
    return shapely.union_all(np.concatenate([[poly], hulls]))


_STATIC_INFLATED: weakref.WeakKeyDictionary = weakref.WeakKeyDictionary()


def inflated_obstacles(
    scenario: Scenario, t: float = 0.0, indices=None, n: int = CIRCLE_SEGMENTS
) -> list[shapely.Polygon]:
    """Containing polygons of the scenario's obstacles at time ``t`` (time steps).

    Parameters
    ----------
    indices : sequence of int, optional
        Which obstacles (default all); ``scenario.static_indices`` gives the static ones.
    """
    idx = range(len(scenario.obstacles)) if indices is None else indices
    r = scenario.robot_radius
    # static shapes are the same at every t: inflated once per scenario (the oracle follower
    # asks at every step); shapely geometries are immutable, so sharing them is safe
    cache = _STATIC_INFLATED.setdefault(scenario, {})
    out = []
    for i in idx:
        o = scenario.obstacles[i]
        if o.is_static:
            off = o.offset(float(t))
            key = (i, float(r), int(n), float(off[0]), float(off[1]))
            if key not in cache:
                cache[key] = inflate(o.shape, r, off, n)
            out.append(cache[key])
        else:
            out.append(inflate(o.shape, r, o.offset(float(t)), n))
    return out


def _hull_halfplanes(vertices: np.ndarray, r: float) -> np.ndarray:
    """Convex hull edges of ``vertices`` as ``(nx, ny, n . c + r + 1e-9)`` rows (pixels)."""
    hull = shapely.geometry.polygon.orient(shapely.MultiPoint(vertices).convex_hull, 1.0)
    ring = np.asarray(hull.exterior.coords)  # counter-clockwise, closed
    e = np.diff(ring, axis=0)
    length = np.hypot(e[:, 0], e[:, 1])
    keep = length > 0
    normal = np.column_stack([e[keep, 1], -e[keep, 0]]) / length[keep, None]  # outward (CCW)
    d = np.sum(normal * ring[:-1][keep], axis=1) + r + 1e-9
    return np.column_stack([normal, d])


@dataclass(frozen=True)
class FlatObstacles:
    """Obstacle shapes as flat, padded arrays for the Numba kernel (at offset zero).

    Attributes
    ----------
    is_circle : numpy.ndarray of bool, shape (n,)
    thresh : numpy.ndarray, shape (n,)
        Hit distance (pixels): a point hits obstacle ``i`` iff its distance to the centre
        (circles) or to the raw polygon (polygons) is ``<= thresh[i]``; that is ``R + r`` for
        circles and ``r`` for polygons (exact inflation).
    verts : numpy.ndarray, shape (n, m, 2)
        Polygon vertices (pixels), padded; ring not closed.
    nverts : numpy.ndarray of int64, shape (n,)
        Number of vertices (0 for circles).
    bound : numpy.ndarray, shape (n, 7)
        ``(xmin, ymin, xmax, ymax, cx, cy, rho)``: bounding box and bounding circle of the
        inflated shape (pixels); for a circle obstacle ``(cx, cy, rho)`` is the inflated circle.
    hull : numpy.ndarray, shape (n, h, 3)
        Per polygon, its convex hull's edges as half-planes ``(nx, ny, d)``: unit outward
        normal and ``d = n . c + r + 1e-9`` (pixels); a point with ``n . p > d`` is more than
        ``r`` outside the polygon (exact separating-axis rejections in the kernel).
    nhull : numpy.ndarray of int64, shape (n,)
        Hull edges per obstacle (0 for circles).
    """

    is_circle: np.ndarray
    thresh: np.ndarray
    verts: np.ndarray
    nverts: np.ndarray
    bound: np.ndarray
    hull: np.ndarray
    nhull: np.ndarray

    @classmethod
    def from_obstacles(cls, obstacles: tuple[Obstacle, ...], r: float) -> FlatObstacles:
        """Flatten ``obstacles`` inflated by the robot radius ``r`` (pixels)."""
        n = len(obstacles)
        m = max([len(o.shape.vertices) for o in obstacles if not o.is_circle] + [1])
        is_circle = np.zeros(n, dtype=np.bool_)
        thresh = np.zeros(n)
        verts = np.zeros((n, m, 2))
        nverts = np.zeros(n, dtype=np.int64)
        bound = np.zeros((n, 7))
        hulls = [np.zeros((0, 3))] * n
        for i, o in enumerate(obstacles):
            s = o.shape
            box = np.asarray(s.bounds()) + (-r, -r, r, r)
            if o.is_circle:
                is_circle[i] = True
                thresh[i] = s.radius + r
                bound[i] = (*box, *s.center, s.radius + r)
            else:
                v = np.asarray(s.vertices, dtype=float)
                verts[i, : len(v)] = v
                nverts[i] = len(v)
                thresh[i] = r
                c = 0.5 * (v.min(axis=0) + v.max(axis=0))
                rho = np.max(np.hypot(*(v - c).T)) + r
                # pad rho by a relative hair so rounding never rejects a true hit
                bound[i] = (*box, *c, rho * (1.0 + 1e-12) + 1e-12)
                hulls[i] = _hull_halfplanes(v, r)
        h = max([len(x) for x in hulls] + [1])
        hull = np.zeros((n, h, 3))
        nhull = np.zeros(n, dtype=np.int64)
        for i, x in enumerate(hulls):
            hull[i, : len(x)] = x
            nhull[i] = len(x)
        return cls(is_circle, thresh, verts, nverts, bound, hull, nhull)

    @classmethod
    def from_scenario(cls, scenario: Scenario) -> FlatObstacles:
        return cls.from_obstacles(scenario.obstacles, scenario.robot_radius)

    def arrays(self) -> tuple:
        """``(is_circle, thresh, verts, nverts, bound, hull, nhull)`` as the kernel takes them."""
        return (
            self.is_circle,
            self.thresh,
            self.verts,
            self.nverts,
            self.bound,
            self.hull,
            self.nhull,
        )


@dataclass(frozen=True)
class MotionTable:
    """Every obstacle's motion over ``[t_lo, t_hi]`` as padded knot arrays for the kernel.

    Between consecutive knots an obstacle moves with constant velocity; static obstacles have a
    single knot. After ``t_hi`` the kernel extrapolates the last piece, so callers build a table
    that covers every time they query.

    Attributes
    ----------
    times : numpy.ndarray, shape (n, K)
        Knot times (time steps), padded with ``+inf``.
    offsets : numpy.ndarray, shape (n, K, 2)
        Offsets at the knots (pixels).
    velocity : numpy.ndarray, shape (n, K, 2)
        Velocity on the piece that starts at each knot (pixels per time step; 0 after the last).
    nknots : numpy.ndarray of int64, shape (n,)
    t_lo, t_hi : float
        Covered interval (time steps).
    """

    times: np.ndarray
    offsets: np.ndarray
    velocity: np.ndarray
    nknots: np.ndarray
    t_lo: float
    t_hi: float

    @classmethod
    def build(cls, obstacles: tuple[Obstacle, ...], t_lo: float, t_hi: float) -> MotionTable:
        pieces = []
        for o in obstacles:
            if o.is_static:
                pieces.append((np.array([t_lo]), np.zeros((1, 2))))
            else:
                pieces.append(o.knots(t_lo, t_hi))
        n = len(obstacles)
        K = max([len(t) for t, _ in pieces] + [1])
        times = np.full((n, K), np.inf)
        offsets = np.zeros((n, K, 2))
        velocity = np.zeros((n, K, 2))
        nknots = np.zeros(n, dtype=np.int64)
        for i, (t, off) in enumerate(pieces):
            times[i, : len(t)] = t
            offsets[i, : len(t)] = off
            offsets[i, len(t) :] = off[-1]
            nknots[i] = len(t)
        # every piece's velocity in one array operation (elementwise: the numbers of one
        # np.diff per obstacle); the padding after the last knot moves at 0
        if K > 1:
            inside = np.arange(K - 1)[None, :] < (nknots - 1)[:, None]
            step = np.where(inside, times[:, 1:], 1.0) - np.where(inside, times[:, :-1], 0.0)
            v = (offsets[:, 1:] - offsets[:, :-1]) / step[..., None]
            velocity[:, :-1] = np.where(inside[..., None], v, 0.0)
        return cls(times, offsets, velocity, nknots, float(t_lo), float(t_hi))

    @classmethod
    def frozen(cls, n: int) -> MotionTable:
        """A table in which ``n`` obstacles never move (one knot each at t = 0)."""
        return cls(
            np.zeros((n, 1)), np.zeros((n, 1, 2)), np.zeros((n, 1, 2)), np.ones(n, np.int64), 0, 0
        )

    def kernel_arrays(self, t0: float) -> tuple:
        """``(times, offsets, velocity, nknots, start_indices(t0))`` as the kernel takes them."""
        return (self.times, self.offsets, self.velocity, self.nknots, self.start_indices(t0))

    def covers(self, t_lo: float, t_hi: float) -> bool:
        """True if the table spans ``[t_lo, t_hi]`` (time steps)."""
        return self.t_lo <= t_lo and t_hi <= self.t_hi

    def start_indices(self, t: float) -> np.ndarray:
        """Per obstacle, the index of the piece that contains time ``t`` (int64, shape (n,)).

        That is the last knot ``<= t``, capped so that a following knot exists (0 for a single
        knot).
        """
        # knot times strictly increase along a row (Motion.knots), so the knots <= t are the
        # row's first ones and their count is searchsorted(side="right"): one pass over the
        # table instead of a search per obstacle (~330 us for a crowd of 45 movers). A NaN
        # sorts last in a search, as +inf does
        t = math.inf if math.isnan(t) else float(t)
        valid = np.arange(self.times.shape[1]) < self.nknots[:, None]
        k = np.count_nonzero((self.times <= t) & valid, axis=1) - 1
        return np.minimum(np.maximum(k, 0), np.maximum(self.nknots - 2, 0)).astype(np.int64)
