"""The data a policy receives each step, the tracker's estimates, and the policy contract.

Units are the world's internal ones: positions in pixels, time in time steps, velocities in
pixels per time step (a metre scenario converts at its resolution and time step).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Protocol

import numpy as np

__all__ = ["Policy", "Reading", "Tracks"]


def _points(a, what: str) -> np.ndarray:
    a = np.asarray(a, dtype=float).reshape(-1, 2)
    if not np.all(np.isfinite(a)):
        raise ValueError(f"{what} must be finite")
    return a


@dataclass(frozen=True, eq=False)
class Reading:
    """One step's observation: the robot's own state (exact) and its detections (noisy).

    Parameters
    ----------
    step : int
        Time step of the reading, >= 0.
    position : array_like, shape (2,)
        Robot centre (pixels).
    velocity : array_like, shape (2,)
        Robot velocity over the last step (pixels per time step); zero at step 0.
    goal : array_like, shape (2,)
        Robot goal (pixels).
    centers : array_like, shape (n, 2)
        Centres of the detected agents (pixels), in no particular order; detections carry no
        identity (the tracker associates them).
    radii : array_like, shape (n,)
        Radii of the detected agents (pixels), > 0. A polygon agent is reported as its
        bounding disc.
    """

    step: int
    position: np.ndarray
    velocity: np.ndarray
    goal: np.ndarray
    centers: np.ndarray
    radii: np.ndarray

    def __post_init__(self) -> None:
        object.__setattr__(self, "position", _points(self.position, "position")[0])
        object.__setattr__(self, "velocity", _points(self.velocity, "velocity")[0])
        object.__setattr__(self, "goal", _points(self.goal, "goal")[0])
        c = _points(self.centers, "centers")
        r = np.asarray(self.radii, dtype=float).reshape(-1)
        if r.shape != (len(c),) or np.any(~(r > 0)):
            raise ValueError(f"radii must be {len(c)} values > 0, got {r!r}")
        object.__setattr__(self, "centers", c)
        object.__setattr__(self, "radii", r)


@dataclass(frozen=True, eq=False)
class Tracks:
    """A tracker's estimate of the agents around the robot at one step.

    Parameters
    ----------
    ids : array_like of int, shape (n,)
        Track identities, stable while a track lives.
    centers : array_like, shape (n, 2)
        Estimated centres (pixels).
    velocities : array_like, shape (n, 2)
        Estimated velocities (pixels per time step).
    radii : array_like, shape (n,)
        Agent radii (pixels), > 0.
    position_sd : array_like, shape (n,)
        Standard deviation of each centre estimate (pixels), >= 0.
    velocity_sd : array_like, shape (n,)
        Standard deviation of each velocity estimate (pixels per time step), >= 0.
    missed : array_like of int, shape (n,), optional
        Steps since each track was last detected (0: detected in this reading, the default
        for every track). A missed track's centre and velocity are a constant-velocity guess
        from its last detection, which a person who turned meanwhile does not follow.
    """

    ids: np.ndarray
    centers: np.ndarray
    velocities: np.ndarray
    radii: np.ndarray
    position_sd: np.ndarray
    velocity_sd: np.ndarray
    missed: np.ndarray | None = None

    def __post_init__(self) -> None:
        c = _points(self.centers, "centers")
        n = len(c)
        object.__setattr__(self, "centers", c)
        object.__setattr__(self, "velocities", _points(self.velocities, "velocities"))
        object.__setattr__(self, "ids", np.asarray(self.ids, dtype=np.int64).reshape(-1))
        for name in ("radii", "position_sd", "velocity_sd"):
            object.__setattr__(self, name, np.asarray(getattr(self, name), float).reshape(-1))
        missed = np.zeros(n, np.int64) if self.missed is None else self.missed
        object.__setattr__(self, "missed", np.asarray(missed, dtype=np.int64).reshape(-1))
        for name in ("ids", "velocities", "radii", "position_sd", "velocity_sd", "missed"):
            if len(getattr(self, name)) != n:
                raise ValueError(f"tracks: {name} has {len(getattr(self, name))} rows, not {n}")
        if np.any(self.missed < 0):
            raise ValueError(f"tracks: missed must be >= 0 steps, got {self.missed!r}")

    def __len__(self) -> int:
        return len(self.centers)


class Policy(Protocol):
    """A robot controller the stepped world drives one step at a time.

    ``reset`` is called once per episode with what the robot knows beforehand (the scenario's
    map, start, goal and robot; its moving obstacles only when the policy is granted the
    ``oracle`` knowledge) and the episode's seed; ``act`` is called at every step with that
    step's :class:`Reading` and returns the velocity to drive for one time step (pixels per
    time step, its norm at most the robot's speed; the world clips longer ones).
    """

    def reset(self, scenario, seed) -> None: ...

    def act(self, reading: Reading) -> np.ndarray: ...
