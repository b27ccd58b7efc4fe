"""Independent check of kinematic limits (issue 27, item 3): speed, acceleration and turn
rate of an executed trajectory, from its positions alone (NumPy only; shares no code with
:mod:`mawdo.planning.safety.kinematics`, which makes the motion).

The trajectory is the robot's positions at integer time steps, straight and uniform in
between; the robot starts at rest. Step ``s`` is the move from position ``s`` to ``s + 1``.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

__all__ = ["KinematicReport", "check_kinematics"]

#: A move this short (pixels) is the robot at rest: it has no heading.
REST_TOL = 1e-9


@dataclass(frozen=True)
class KinematicReport:
    """Steps of a trajectory over kinematic limits (:func:`check_kinematics`).

    Attributes
    ----------
    speed, accel, turn : tuple of int
        Steps ``s`` (the move from position ``s`` to ``s + 1``) whose speed, change of
        velocity from step ``s - 1`` (step 0 from rest) or change of heading from step
        ``s - 1`` exceed the limit.
    worst : dict
        Largest speed (px per step), acceleration (px per step squared) and turn (radians per
        step) of the trajectory.
    """

    speed: tuple[int, ...]
    accel: tuple[int, ...]
    turn: tuple[int, ...]
    worst: dict

    @property
    def count(self) -> int:
        """Steps over at least one limit."""
        return len(set(self.speed) | set(self.accel) | set(self.turn))

    @property
    def ok(self) -> bool:
        return self.count == 0

    def describe(self) -> str:
        """The violations in words (``"ok"`` without any)."""
        parts = [
            f"{len(getattr(self, k))} steps over the {k} limit (worst {self.worst[k]:.4g})"
            for k in ("speed", "accel", "turn")
            if getattr(self, k)
        ]
        return "; ".join(parts) if parts else "ok"


def check_kinematics(
    positions, max_speed=None, max_accel=None, max_turn=None, tol: float = 1e-7
) -> KinematicReport:
    """Check a trajectory (positions at integer time steps, straight and uniform in between)
    against kinematic limits; ``None`` leaves a quantity free.

    Parameters
    ----------
    positions : array_like, shape (k, 2)
        Robot centre at consecutive time steps (pixels); the robot starts at rest.
    max_speed : float, optional
        Most distance per step (px per step).
    max_accel : float, optional
        Most change of velocity per step (px per step squared), the velocity before the first
        step being zero.
    max_turn : float, optional
        Most angle between two consecutive moves (radians per step); a step from rest or to
        rest (a move shorter than ``REST_TOL``) has no heading and never counts.
    tol : float
        Relative slack: a value counts as over a limit only above ``limit * (1 + tol)``.

    Returns
    -------
    KinematicReport
    """
    p = np.asarray(positions, dtype=float)
    if p.ndim != 2 or p.shape[1] != 2 or len(p) < 1 or not np.all(np.isfinite(p)):
        raise ValueError(f"positions must be finite with shape (k, 2), k >= 1; got {p.shape}")
    u = np.diff(p, axis=0)  # velocity of each step
    speed = np.linalg.norm(u, axis=1)
    accel = np.linalg.norm(np.diff(np.vstack([np.zeros((1, 2)), u]), axis=0), axis=1)
    turn = np.zeros(len(u))
    if len(u) > 1:
        a, b = u[:-1], u[1:]
        na, nb = speed[:-1], speed[1:]
        both = (na > REST_TOL) & (nb > REST_TOL)
        cos = np.sum(a * b, axis=1) / np.where(both, na * nb, 1.0)
        turn[1:] = np.where(both, np.arccos(np.clip(cos, -1.0, 1.0)), 0.0)
    over = {}
    for name, values, limit in (
        ("speed", speed, max_speed),
        ("accel", accel, max_accel),
        ("turn", turn, max_turn),
    ):
        bad = () if limit is None else np.nonzero(values > limit * (1.0 + tol))[0]
        over[name] = tuple(int(s) for s in bad)
    worst = {k: float(v.max()) if v.size else 0.0
             for k, v in (("speed", speed), ("accel", accel), ("turn", turn))}  # fmt: skip
    return KinematicReport(over["speed"], over["accel"], over["turn"], worst)
