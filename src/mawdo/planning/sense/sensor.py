"""The robot's sensor: which agents it detects at one step, and how noisily.

A detection needs three things: the agent's disc comes within the sensor's range of the robot
centre, a line of sight to the disc is not cut by a static wall (when occlusion is on), and the
detection is not missed at random. The reported centres carry Gaussian noise and come in a random
order, without identities: telling who is who is the tracker's job.

Lines of sight go from the robot centre to three points of each disc: its centre and its two
tangent points (where the sight lines graze the disc, the edges of its silhouette). The agent is
visible when any of the three is, so a person half behind a pillar is still seen
(docs/deviations.md#d-sight-lines). Tests run in shapely, all sight lines of a step in one query.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
import shapely

from mawdo.planning.sense.reading import Reading
from mawdo.util.validate import check_bool, check_real

__all__ = ["Sensor", "Walls", "sight_points", "visible"]


def sight_points(position, centers, radii) -> np.ndarray:
    """The points of each disc the robot looks at: centre and the two tangent points.

    Parameters
    ----------
    position : array_like, shape (2,)
        Robot centre (pixels).
    centers : array_like, shape (n, 2)
        Disc centres (pixels).
    radii : array_like, shape (n,)
        Disc radii (pixels), > 0.

    Returns
    -------
    numpy.ndarray, shape (n, 3, 2)
        Per disc: its centre, then the tangent points of the two sight lines from the robot
        centre that graze it (pixels). A disc that holds the robot centre gives its centre three
        times (the robot is touching it; nothing can hide it).
    """
    p = np.asarray(position, dtype=float).reshape(2)
    c = np.asarray(centers, dtype=float).reshape(-1, 2)
    r = np.asarray(radii, dtype=float).reshape(-1)
    to_robot = p - c
    d = np.hypot(to_robot[:, 0], to_robot[:, 1])
    outside = d > r
    u = to_robot / np.where(outside, d, 1.0)[:, None]
    n = np.column_stack([-u[:, 1], u[:, 0]])
    # the tangent point T on the disc sees the robot at a right angle: the angle at the centre
    # between (T - c) and (p - c) is arccos(r / d)
    cos_a = np.where(outside, r / np.where(outside, d, 1.0), 1.0)
    sin_a = np.sqrt(np.clip(1.0 - cos_a**2, 0.0, None))
    rim = r[:, None] * cos_a[:, None] * u
    side = r[:, None] * sin_a[:, None] * n
    tangents = np.stack([c + rim + side, c + rim - side], axis=1)
    tangents = np.where(outside[:, None, None], tangents, c[:, None, :])
    return np.concatenate([c[:, None, :], tangents], axis=1)


class Walls:
    """Static wall polygons, built and indexed once for many sight-line queries.

    :meth:`Sensor.read` and :func:`visible` take the vertex arrays themselves too; a world that
    reads every step passes one ``Walls`` to skip rebuilding the shapes (half the cost of a read
    with 200 walls).

    Parameters
    ----------
    walls : sequence of array_like, each shape (k, 2)
        Wall polygons, their vertices in order (pixels), k >= 3.
    """

    def __init__(self, walls: Sequence) -> None:
        polys = [shapely.Polygon(np.asarray(w, dtype=float).reshape(-1, 2)) for w in walls]
        self.polygons = np.array(polys, dtype=object)
        self.tree = shapely.STRtree(self.polygons)

    @classmethod
    def of(cls, walls) -> Walls:
        """``walls`` itself when it is a ``Walls``, else the ``Walls`` of those polygons."""
        return walls if isinstance(walls, cls) else cls(walls)

    def __len__(self) -> int:
        return len(self.polygons)


def visible(position, centers, radii, walls) -> np.ndarray:
    """Which discs the robot centre can see past the walls.

    A disc is visible when the segment from the robot centre to at least one of its
    :func:`sight_points` does not cross a wall: a segment crosses a wall when it meets the wall's
    interior; one that only grazes a wall's boundary (a corner, an edge it runs along) does not.

    Parameters
    ----------
    position : array_like, shape (2,)
        Robot centre (pixels).
    centers : array_like, shape (n, 2)
        Disc centres (pixels).
    radii : array_like, shape (n,)
        Disc radii (pixels), > 0.
    walls : Walls or sequence of array_like, each shape (k, 2)
        Static wall polygons, their vertices in order (pixels), k >= 3.

    Returns
    -------
    numpy.ndarray of bool, shape (n,)
    """
    c = np.asarray(centers, dtype=float).reshape(-1, 2)
    n = len(c)
    seen = np.ones(n, dtype=bool)
    if n == 0 or len(walls) == 0:
        return seen
    ends = sight_points(position, c, radii).reshape(-1, 2)
    start = np.broadcast_to(np.asarray(position, dtype=float).reshape(1, 2), ends.shape)
    lines = shapely.linestrings(np.stack([start, ends], axis=1))
    walls = Walls.of(walls)
    line_i, wall_i = walls.tree.query(lines, predicate="intersects")
    grazes = shapely.touches(lines[line_i], walls.polygons[wall_i])
    blocked = np.zeros(len(lines), dtype=bool)
    blocked[line_i[~grazes]] = True
    return ~blocked.reshape(n, 3).all(axis=1)


@dataclass(frozen=True)
class Sensor:
    """A range-limited, occluded, noisy detector of the agents around the robot.

    Parameters
    ----------
    range : float
        Detection range (pixels), > 0, ``inf`` for none: an agent is in range when the nearest
        point of its disc is within ``range`` of the robot centre.
    noise : float
        Standard deviation of the Gaussian error added to each coordinate of a detected centre
        (pixels), >= 0.
    miss_rate : float
        Probability that an agent in sight is not detected at a step, in [0, 1); each agent and
        step independently.
    occlusion : bool
        Whether static walls hide the agents behind them (see :func:`visible`).

    Notes
    -----
    Every call of :meth:`read` draws the same amount of randomness per agent (its miss, its noise,
    its place in the order), whether or not the agent is in range or in sight, so two robots that
    drive differently through the same world with the same seed see the same errors on the agents
    both detect.
    """

    range: float = math.inf
    noise: float = 0.0
    miss_rate: float = 0.0
    occlusion: bool = True

    def __post_init__(self) -> None:
        reach = self.range
        if not (isinstance(reach, float) and reach == math.inf):  # inf: no range limit
            try:
                reach = check_real("range", reach, 0.0, low_open=True)
            except ValueError as err:
                raise type(err)(f"{err} (pixels), or inf for an unlimited range") from None
        object.__setattr__(self, "range", reach)
        object.__setattr__(self, "noise", check_real("noise", self.noise, 0.0))
        object.__setattr__(
            self, "miss_rate", check_real("miss_rate", self.miss_rate, 0.0, 1.0, high_open=True)
        )
        object.__setattr__(self, "occlusion", check_bool("occlusion", self.occlusion))

    def detects(self, position, centers, radii, walls) -> np.ndarray:
        """Which agents are in range and in sight (before random misses), ``(n,)`` bool."""
        c = np.asarray(centers, dtype=float).reshape(-1, 2)
        r = np.asarray(radii, dtype=float).reshape(-1)
        gap = np.hypot(*(c - np.asarray(position, dtype=float).reshape(1, 2)).T) - r
        keep = gap <= self.range
        if self.occlusion and len(walls) and keep.any():
            keep[keep] = visible(position, c[keep], r[keep], walls)
        return keep

    def read(self, step, position, velocity, goal, centers, radii, walls, rng) -> Reading:
        """One step's reading of the agents around the robot.

        Parameters
        ----------
        step : int
            Time step (>= 0).
        position, velocity, goal : array_like, shape (2,)
            The robot's centre (pixels), velocity over the last step (pixels per time step) and
            goal (pixels); passed through exactly.
        centers : array_like, shape (n, 2)
            True centres of every agent (pixels).
        radii : array_like, shape (n,)
            Their radii (pixels), > 0 (reported exactly).
        walls : Walls or sequence of array_like, each shape (k, 2)
            Static wall polygons (pixels).
        rng : numpy.random.Generator
            Source of the misses, the noise and the order.

        Returns
        -------
        Reading
            The detected agents, their centres with noise, in random order.
        """
        if not isinstance(rng, np.random.Generator):
            raise TypeError(
                f"rng must be a numpy.random.Generator (np.random.default_rng(seed)), "
                f"not {type(rng).__name__}"
            )
        c = np.asarray(centers, dtype=float).reshape(-1, 2)
        r = np.asarray(radii, dtype=float).reshape(-1)
        if len(r) != len(c):
            raise ValueError(f"radii has {len(r)} values for {len(c)} centres; give one each")
        n = len(c)
        # drawn for every agent, seen or not (see Notes): misses, order keys, noise
        draws = rng.random((n, 2))
        error = rng.normal(0.0, 1.0, (n, 2)) * self.noise
        keep = self.detects(position, c, r, walls) & (draws[:, 0] >= self.miss_rate)
        idx = np.flatnonzero(keep)
        idx = idx[np.argsort(draws[idx, 1], kind="stable")]
        return Reading(
            step=step,
            position=position,
            velocity=velocity,
            goal=goal,
            centers=c[idx] + error[idx],
            radii=r[idx],
        )
