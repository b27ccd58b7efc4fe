"""Independent check of kinematic limits: speed, acceleration and turn
rate of an executed trajectory, from its positions alone (NumPy only; shares no code with
:mod:`mawdo.planning.safety.kinematics`, which makes the motion).

The trajectory is the robot's positions at integer time steps, straight and uniform in
between; the robot starts at rest. Step ``s`` is the move from position ``s`` to ``s + 1``.
A step of at most :data:`REST_TOL` px is the robot standing; it keeps the heading of its
last move, so a turn made while standing is counted against the steps it took: between two
moves ``i < j`` with only standing steps in between, the turn rate is the angle between them
over ``j - i``.
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
        velocity from step ``s - 1`` (step 0 from rest) or turn rate exceed the limit; a move's
        turn rate is the angle from the robot's previous move over the steps between them
        (standing steps turn in place).
    worst : dict
        Largest speed (px per step), acceleration (px per step squared) and turn rate (radians
        per step) of the trajectory.
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
        Most change of heading per step (radians per step): two consecutive moves ``i < j``
        (the steps between them standing: shorter than ``REST_TOL``) may differ by at most
        ``(j - i) max_turn``; the first move may take any heading.
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
    moves = np.nonzero(speed > REST_TOL)[0]
    if len(moves) > 1:  # each move against the robot's previous move, standing steps between
        i, j = moves[:-1], moves[1:]
        cross = u[i, 0] * u[j, 1] - u[i, 1] * u[j, 0]
        turn[j] = np.abs(np.arctan2(cross, np.sum(u[i] * u[j], axis=1))) / (j - i)
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
