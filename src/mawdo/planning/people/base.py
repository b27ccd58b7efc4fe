"""The common part of people who react: state, validation, preferred velocities, the wall guard
and new goals for people who arrive.

Units: pixels, time steps, pixels per time step (see :mod:`mawdo.planning.people`).
"""

from __future__ import annotations

from typing import Protocol

import numpy as np

from mawdo.planning.people.walls import Walls

__all__ = ["GoalPolicy", "KeepGoal", "People", "preferred_velocities"]


def preferred_velocities(positions, goals, preferred_speed, arrival_time: float) -> np.ndarray:
    """Velocities people would take with nobody around: toward the goal at the preferred speed,
    slowing down within ``preferred_speed * arrival_time`` of it.

    CrowdNav's ORCA humans (``crowd_sim/envs/policy/orca.py``) use ``goal - position`` read as
    a velocity (metres as metres per second, i.e. ``arrival_time`` = 1 s) and cut it to the
    unit vector when longer than 1 (their preferred speed, 1 m/s).

    Parameters
    ----------
    positions, goals : numpy.ndarray, shape (n, 2)
        Pixels.
    preferred_speed : numpy.ndarray, shape (n,)
        Pixels per time step, >= 0.
    arrival_time : float
        Time steps, > 0.

    Returns
    -------
    numpy.ndarray, shape (n, 2)
        ``(goal - position) / arrival_time``, its norm cut to ``preferred_speed``.
    """
    want = (np.asarray(goals, float) - np.asarray(positions, float)) / arrival_time
    norm = np.hypot(want[:, 0], want[:, 1])
    scale = np.minimum(1.0, np.asarray(preferred_speed, float) / np.where(norm > 0, norm, 1.0))
    return want * scale[:, None]


class GoalPolicy(Protocol):
    """What a person does when it reaches its goal (comes within its radius of it).

    ``new_goal`` returns the person's next goal (pixels, shape (2,)) or ``None`` to keep the
    current one. It may draw from ``rng`` (the people's generator, so the same seed gives the
    same goals) and should only return goals where ``people.free`` holds for the person's disc.
    """

    def new_goal(
        self, i: int, people: People, robot_position: np.ndarray, robot_radius: float, rng
    ) -> np.ndarray | None: ...


class KeepGoal:
    """A person who arrives stays with its goal (original CrowdNav: it stops there)."""

    def new_goal(self, i, people, robot_position, robot_radius, rng):
        return None


def _array(name: str, value, shape: tuple, fix: str) -> np.ndarray:
    try:
        a = np.asarray(value, dtype=float)
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be numbers; {fix}") from None
    if a.shape != shape:
        raise ValueError(f"{name} must have shape {shape}, got {a.shape}; {fix}")
    bad = np.flatnonzero(~np.isfinite(a).reshape(len(a), -1).all(axis=1)) if a.size else []
    if len(bad):
        raise ValueError(f"{name}[{bad[0]}] = {a[bad[0]].tolist()} is not finite; {fix}")
    return a.copy()


class People:
    """``n`` people who walk to their goals and avoid each other, the walls and (when it is
    visible to them) the robot. Subclasses give the walking model (:meth:`_advance`).

    Parameters
    ----------
    positions : array_like, shape (n, 2)
        Initial centres (pixels); each disc inside the map, clear of the walls and of the others.
    goals : array_like, shape (n, 2)
        Initial goals (pixels); a disc of the person's radius there lies in the map and clear
        of the walls.
    radii : array_like, shape (n,)
        Disc radii (pixels), > 0.
    preferred_speed : array_like, shape (n,)
        Pixels per time step, >= 0.
    bounds : tuple of float
        ``(width, height)`` of the map box ``[0, width] x [0, height]`` (pixels).
    obstacles : sequence of array_like, optional
        Static walls, each a simple polygon ``(k, 2)`` (pixels). People never enter them nor
        leave the map (see :meth:`Walls.guard`).
    goal_policy : GoalPolicy, optional
        What a person who reaches its goal does; default :class:`KeepGoal`.
    rng : numpy.random.Generator, optional
        Draws new goals; required when ``goal_policy`` is given.
    arrival_time : float
        Time steps over which a person slows down into its goal (see
        :func:`preferred_velocities`), > 0.
    velocities : array_like, shape (n, 2), optional
        Initial velocities (pixels per time step); default zero (CrowdNav starts at rest).
    """

    def __init__(
        self,
        positions,
        goals,
        radii,
        preferred_speed,
        *,
        bounds,
        obstacles=(),
        goal_policy: GoalPolicy | None = None,
        rng: np.random.Generator | None = None,
        arrival_time: float = 1.0,
        velocities=None,
    ) -> None:
        pos = np.asarray(positions, dtype=float)
        n = len(pos.reshape(-1, 2)) if pos.size else 0
        self._pos = _array("positions", pos.reshape(n, 2), (n, 2), "give n (x, y) centres in px")
        self.goals = _array("goals", goals, (n, 2), "give one (x, y) goal in px per person")
        self.radii = _array("radii", radii, (n,), "give one radius in px per person")
        bad = np.flatnonzero(~(self.radii > 0))
        if len(bad):
            raise ValueError(
                f"radii[{bad[0]}] = {self.radii[bad[0]]:g} must be > 0; give the person's disc "
                "radius in pixels"
            )
        self.preferred_speed = _array(
            "preferred_speed", preferred_speed, (n,), "give one speed in px per step per person"
        )
        bad = np.flatnonzero(~(self.preferred_speed >= 0))
        if len(bad):
            raise ValueError(
                f"preferred_speed[{bad[0]}] = {self.preferred_speed[bad[0]]:g} must be >= 0 "
                "pixels per step"
            )
        self._vel = (
            np.zeros((n, 2))
            if velocities is None
            else _array("velocities", velocities, (n, 2), "give (vx, vy) in px per step")
        )
        if not (np.isfinite(arrival_time) and arrival_time > 0):
            raise ValueError(f"arrival_time={arrival_time!r} must be > 0 time steps")
        self.arrival_time = float(arrival_time)
        self.walls = Walls.build(obstacles, bounds)
        if goal_policy is not None and not isinstance(rng, np.random.Generator):
            raise ValueError(
                "rng must be a numpy.random.Generator when a goal_policy is given (it draws the "
                "new goals); pass rng=np.random.default_rng(seed)"
            )
        self.goal_policy = goal_policy if goal_policy is not None else KeepGoal()
        self.rng = rng
        self._check_places()

    def _check_places(self) -> None:
        for name, pts in (("positions", self._pos), ("goals", self.goals)):
            depth = self.walls.clearance(pts)
            bad = np.flatnonzero(depth < self.radii)
            if len(bad):
                i = bad[0]
                where = "outside the map" if self._outside(pts[i]) else "inside or too near a wall"
                raise ValueError(
                    f"{name}[{i}] = {pts[i].tolist()} is {where}: a disc of radius "
                    f"{self.radii[i]:g} px there must lie in the map [0, {self.walls.width:g}] x "
                    f"[0, {self.walls.height:g}] and clear of the obstacles; move it"
                )
        d = np.hypot(*(self._pos[:, None, :] - self._pos[None, :, :]).transpose(2, 0, 1))
        overlap = d < self.radii[:, None] + self.radii[None, :]
        np.fill_diagonal(overlap, False)
        if overlap.any():
            i, j = np.argwhere(overlap)[0]
            raise ValueError(f"positions[{i}] and positions[{j}] overlap; place people apart")

    def _outside(self, p) -> bool:
        return not (0 <= p[0] <= self.walls.width and 0 <= p[1] <= self.walls.height)

    def __len__(self) -> int:
        return len(self._pos)

    def positions(self) -> np.ndarray:
        """Centres now (pixels), shape (n, 2) (a copy)."""
        return self._pos.copy()

    def velocities(self) -> np.ndarray:
        """Velocities over the last step (pixels per time step), shape (n, 2) (a copy)."""
        return self._vel.copy()

    def free(self, points, radii) -> np.ndarray:
        """Whether discs at ``points`` (n, 2) with ``radii`` (n,) lie in the map and clear of
        the walls (pixels); for goal policies."""
        return self.walls.free(np.asarray(points, float).reshape(-1, 2), radii)

    def preferred(self) -> np.ndarray:
        """Preferred velocities now (pixels per time step), shape (n, 2)."""
        return preferred_velocities(self._pos, self.goals, self.preferred_speed, self.arrival_time)

    def step(self, robot_position, robot_velocity, robot_radius, visible: bool) -> None:
        """Advance everyone by one time step.

        Parameters
        ----------
        robot_position : array_like, shape (2,)
            Robot centre at the same time as the people's current state (pixels).
        robot_velocity : array_like, shape (2,)
            Robot velocity over its last step (pixels per time step).
        robot_radius : float
            Pixels, > 0.
        visible : bool
            Whether people see the robot: ``True``, they avoid it as one of them (it does not
            yield, its state is overwritten each step); ``False``, it does not exist for them.
        """
        rp = np.asarray(robot_position, dtype=float).reshape(2)
        rv = np.asarray(robot_velocity, dtype=float).reshape(2)
        rr = float(robot_radius)
        if not (np.isfinite(rp).all() and np.isfinite(rv).all() and rr > 0):
            raise ValueError(
                f"robot state must be finite with radius > 0, got position {rp.tolist()}, "
                f"velocity {rv.tolist()}, radius {robot_radius!r}"
            )
        new = self._advance(rp, rv, rr, bool(visible))
        self._vel = new - self._pos
        self._pos = new
        self._moved()
        self._change_goals(rp, rr)

    def _advance(self, robot_position, robot_velocity, robot_radius, visible) -> np.ndarray:
        """New centres after one step (pixels), shape (n, 2), already through the guard."""
        raise NotImplementedError

    def _moved(self) -> None:
        """Hook after the state changed (ORCA copies it into its simulator)."""

    def _change_goals(self, robot_position, robot_radius) -> None:
        if not len(self):
            return
        d = np.hypot(*(self._pos - self.goals).T)
        for i in np.flatnonzero(d < self.radii):
            g = self.goal_policy.new_goal(int(i), self, robot_position, robot_radius, self.rng)
            if g is None:
                continue
            g = np.asarray(g, dtype=float).reshape(2)
            if not self.free(g, self.radii[i : i + 1])[0]:
                raise RuntimeError(
                    f"goal policy {type(self.goal_policy).__name__} gave person {i} the goal "
                    f"{g.tolist()}, outside the map or in a wall; it must check people.free"
                )
            self.goals[i] = g
