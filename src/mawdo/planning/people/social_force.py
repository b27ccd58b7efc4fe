"""People who walk by the social force model (Helbing & Molnár 1995, with the circular
body-surface repulsion of Helbing, Farkas & Vicsek 2000), vectorised in NumPy.

A person ``i`` at ``x_i`` with velocity ``v_i``, radius ``r_i`` and desired velocity ``v0_i``
(toward its goal, see :func:`~mawdo.planning.people.base.preferred_velocities`) accelerates by

    F_i = (v0_i - v_i) / tau                                 [HM1995, acceleration term F0]
        + sum_j w(e_i, x_j - x_i) A exp((r_ij - d_ij) / B) n_ij  [HFV2000 Eq. (2); HM1995 w]
        + sum_W A_W exp((r_i - d_iW) / B_W) n_iW                 [HFV2000 Eq. (3)]

with ``r_ij = r_i + r_j``, ``d_ij`` the centre distance, ``n_ij = (x_i - x_j) / d_ij``, ``d_iW``
the distance to the nearest point of wall ``W`` and ``n_iW`` the unit vector from it, and
HM1995's field of view weight ``w(e, u) = 1`` if ``e . u >= |u| cos(phi)`` (the other is within
``phi`` of the walking direction ``e``), ``c`` otherwise. The speed is capped at
``v_max = 1.3 |v0|`` (HM1995's ``v = w g(v_max / |w|)``). The contact terms of HFV2000 (body
force and sliding friction, which act only when discs overlap) are left out; the move guard
keeps people out of the walls instead.

Units: pixels, time steps; :meth:`SocialForceParams.from_metres` converts the published values.
Parameter values, what is left out and the sub-steps: docs/deviations.md#d-social-force.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from mawdo.planning.people.base import People, preferred_velocities
from mawdo.planning.people.orca import cap_speed
from mawdo.planning.people.walls import Walls, point_segment_distance

__all__ = [
    "SocialForceParams",
    "SocialForcePeople",
    "agent_repulsion",
    "desired_force",
    "fov_weight",
    "integrate",
    "total_force",
    "wall_repulsion",
]


@dataclass(frozen=True)
class SocialForceParams:
    """Social force parameters in pixels and time steps.

    Parameters
    ----------
    tau : float
        Relaxation time of the desired force (time steps), > 0.
    agent_strength, agent_range : float
        ``A`` (pixels per step squared, >= 0) and ``B`` (pixels, > 0) of the repulsion between
        people (and from the robot).
    wall_strength, wall_range : float
        ``A_W`` (pixels per step squared, >= 0) and ``B_W`` (pixels, > 0) of the walls.
    fov_angle : float
        ``phi``, half the field of view (radians, in [0, pi]).
    fov_weight : float
        ``c``, weight of the others outside the field of view, in [0, 1].
    max_speed_factor : float
        ``v_max / |v0|``, >= 1.
    substeps : int
        Semi-implicit Euler sub-steps per time step, >= 1.
    """

    tau: float
    agent_strength: float
    agent_range: float
    wall_strength: float
    wall_range: float
    fov_angle: float
    fov_weight: float
    max_speed_factor: float
    substeps: int

    def __post_init__(self) -> None:
        checks = {
            "tau": self.tau > 0,
            "agent_strength": self.agent_strength >= 0,
            "agent_range": self.agent_range > 0,
            "wall_strength": self.wall_strength >= 0,
            "wall_range": self.wall_range > 0,
            "fov_angle": 0 <= self.fov_angle <= np.pi,
            "fov_weight": 0 <= self.fov_weight <= 1,
            "max_speed_factor": self.max_speed_factor >= 1,
        }
        for name, ok in checks.items():
            v = getattr(self, name)
            if not (np.isfinite(v) and ok):
                raise ValueError(f"SocialForceParams.{name}={v!r} is out of range (see its doc)")
        if not (isinstance(self.substeps, int | np.integer) and self.substeps >= 1):
            raise ValueError(f"SocialForceParams.substeps={self.substeps!r} must be an int >= 1")

    @classmethod
    def from_metres(
        cls,
        res: float,
        dt: float,
        *,
        tau: float = 0.5,
        agent_strength: float = 2.1 / 0.3,
        agent_range: float = 0.3,
        wall_strength: float = 10.0 / 0.2,
        wall_range: float = 0.2,
        fov_angle: float = np.deg2rad(100.0),
        fov_weight: float = 0.5,
        max_speed_factor: float = 1.3,
        substeps: int = 8,
    ) -> SocialForceParams:
        """Convert metre/second parameters at resolution ``res`` (m/px, > 0) and time step
        ``dt`` (s, > 0). Defaults: HM1995's ``tau = 0.5 s``, ``V0 = 2.1 m^2/s^2``,
        ``sigma = 0.3 m`` (so ``A = V0 / sigma`` at contact, ``B = sigma``), ``U0 = 10 m^2/s^2``,
        ``R = 0.2 m``, ``2 phi = 200 deg``, ``c = 0.5``, ``v_max = 1.3 v0``."""
        if not (res > 0 and dt > 0):
            raise ValueError(f"res={res!r} m/px and dt={dt!r} s must be > 0")
        acc = dt * dt / res  # m/s^2 -> px/step^2
        return cls(
            tau / dt,
            agent_strength * acc,
            agent_range / res,
            wall_strength * acc,
            wall_range / res,
            float(fov_angle),
            float(fov_weight),
            float(max_speed_factor),
            int(substeps),
        )


def desired_force(velocities: np.ndarray, desired: np.ndarray, tau: float) -> np.ndarray:
    """HM1995's acceleration term: ``(v0 - v) / tau``, shape (n, 2) (pixels per step squared)."""
    return (desired - velocities) / tau


def fov_weight(direction: np.ndarray, toward: np.ndarray, phi: float, c: float) -> np.ndarray:
    """HM1995's field of view weight: 1 where ``toward`` (n, k, 2) lies within ``phi`` of the
    walking ``direction`` (n, 2, unit or zero), ``c`` elsewhere; shape (n, k)."""
    dot = np.einsum("nk,njk->nj", direction, toward)
    return np.where(dot >= np.hypot(toward[..., 0], toward[..., 1]) * np.cos(phi), 1.0, c)


def agent_repulsion(
    positions, radii, others, other_radii, strength: float, reach: float
) -> tuple[np.ndarray, np.ndarray]:
    """HFV2000 Eq. (2), first term: ``A exp((r_i + r_j - d_ij) / B) n_ij`` for every pair.

    Parameters
    ----------
    positions : numpy.ndarray, shape (n, 2)
    radii : numpy.ndarray, shape (n,)
    others : numpy.ndarray, shape (k, 2)
    other_radii : numpy.ndarray, shape (k,)
    strength, reach : float
        ``A`` (pixels per step squared) and ``B`` (pixels).

    Returns
    -------
    force : numpy.ndarray, shape (n, k, 2)
        Force on ``i`` from ``j`` (zero for coincident centres).
    toward : numpy.ndarray, shape (n, k, 2)
        ``x_j - x_i``, for the field of view.
    """
    toward = others[None, :, :] - positions[:, None, :]
    d = np.hypot(toward[..., 0], toward[..., 1])
    mag = strength * np.exp((radii[:, None] + other_radii[None, :] - d) / reach)
    unit = -toward / np.where(d > 0, d, np.inf)[..., None]
    return mag[..., None] * unit, toward


def wall_repulsion(positions, radii, walls: Walls, strength: float, reach: float) -> np.ndarray:
    """HFV2000 Eq. (3), first term, summed over the walls: ``A_W exp((r_i - d_iW) / B_W) n_iW``
    with ``d_iW`` the distance to the nearest point of wall ``W``; shape (n, 2)."""
    out = np.zeros_like(positions)
    for poly in walls.polygons:
        a = poly
        b = np.roll(poly, -1, axis=0)
        dist, nearest = point_segment_distance(positions, a, b)
        k = dist.argmin(axis=1)
        d = dist[np.arange(len(positions)), k]
        away = positions - nearest[np.arange(len(positions)), k]
        unit = away / np.where(d > 0, d, np.inf)[:, None]
        out += (strength * np.exp((radii - d) / reach))[:, None] * unit
    return out


def total_force(
    params: SocialForceParams,
    positions,
    velocities,
    radii,
    desired,
    others,
    other_radii,
    walls: Walls,
    skip=None,
) -> np.ndarray:
    """Sum of the desired, agent and wall forces on each person, shape (n, 2) (pixels per step
    squared). ``skip`` (n, k) bool marks pairs left out (a person and itself)."""
    f = desired_force(velocities, desired, params.tau)
    if len(others):
        pair, toward = agent_repulsion(
            positions, radii, others, other_radii, params.agent_strength, params.agent_range
        )
        speed = np.hypot(desired[:, 0], desired[:, 1])
        e = desired / np.where(speed > 0, speed, np.inf)[:, None]
        w = fov_weight(e, toward, params.fov_angle, params.fov_weight)
        if skip is not None:
            w = np.where(skip, 0.0, w)
        f = f + np.einsum("nj,njk->nk", w, pair)
    if walls.polygons:
        f = f + wall_repulsion(positions, radii, walls, params.wall_strength, params.wall_range)
    return f


def integrate(
    params: SocialForceParams,
    walls: Walls,
    positions,
    velocities,
    radii,
    max_speeds,
    desired_at: Callable[[np.ndarray], np.ndarray],
    others_at: Callable[[float, np.ndarray], tuple[np.ndarray, np.ndarray, np.ndarray | None]],
    guard: bool = True,
) -> np.ndarray:
    """One time step of ``params.substeps`` semi-implicit Euler sub-steps of length ``h``:
    ``v <- cap(v + h F, v_max)``, ``x <- guard(x, h v)``; the velocity kept is the one the guard
    lets through.

    Parameters
    ----------
    desired_at : callable
        ``positions (n, 2) -> desired velocities (n, 2)``.
    others_at : callable
        ``(s, positions) -> (others (k, 2), other_radii (k,), skip (n, k) or None)`` at the
        sub-step's start time ``s`` (fraction of the step).
    guard : bool
        Whether the walls' move guard applies (it needs the discs to start clear of them).

    Returns
    -------
    numpy.ndarray, shape (n, 2)
        Centres after the step (pixels).
    """
    h = 1.0 / params.substeps
    x, v = positions.copy(), velocities.copy()
    for s in range(params.substeps):
        others, other_radii, skip = others_at(s * h, x)
        f = total_force(params, x, v, radii, desired_at(x), others, other_radii, walls, skip)
        v = cap_speed(v + h * f, max_speeds)
        if guard:
            new = walls.guard(x, h * v, radii)
            v = (new - x) / h
            x = new
        else:
            x = x + h * v
    return x


class SocialForcePeople(People):
    """People who walk by the social force model (see the module doc).

    A visible robot repels people like one of them, extrapolated over the step at its last
    velocity (it does not react to forces).

    Parameters
    ----------
    positions, goals, radii, preferred_speed, bounds, obstacles, goal_policy, rng, arrival_time,
    velocities
        See :class:`~mawdo.planning.people.base.People`.
    params : SocialForceParams
        In pixels and time steps (e.g. ``SocialForceParams.from_metres(res, dt)``).
    """

    def __init__(
        self, positions, goals, radii, preferred_speed, *, params: SocialForceParams, **kw
    ):
        super().__init__(positions, goals, radii, preferred_speed, **kw)
        if not isinstance(params, SocialForceParams):
            raise ValueError(
                "params must be a SocialForceParams (e.g. SocialForceParams.from_metres(res, dt))"
            )
        self.params = params

    def _advance(self, robot_position, robot_velocity, robot_radius, visible) -> np.ndarray:
        n = len(self)
        eye = np.eye(n, n + int(visible), dtype=bool)
        all_radii = np.append(self.radii, robot_radius) if visible else self.radii

        def others_at(s, x):
            if visible:
                x = np.vstack([x, robot_position + s * robot_velocity])
            return x, all_radii, eye

        def desired_at(x):
            return preferred_velocities(x, self.goals, self.preferred_speed, self.arrival_time)

        vmax = self.params.max_speed_factor * self.preferred_speed
        return integrate(
            self.params, self.walls, self._pos, self._vel, self.radii, vmax, desired_at, others_at
        )
