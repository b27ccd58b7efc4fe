"""The people of a scenario file's ``[crowd]`` table, built for a stepped world.

See :mod:`mawdo.planning.world.crowd_schema` for the table. The models take CrowdNav's metre and
second settings at the scenario's resolution and time step.
"""

from __future__ import annotations

import numpy as np

from mawdo.planning.people.base import KeepGoal, People

__all__ = ["BackAndForth", "people_of"]


class BackAndForth:
    """A person who arrives walks back to where it started (and so on): ``goal_changing``
    in a scenario file, deterministic (no draw)."""

    def __init__(self, starts, goals) -> None:
        self.starts = np.asarray(starts, dtype=float).reshape(-1, 2)
        self.goals = np.asarray(goals, dtype=float).reshape(-1, 2)

    def new_goal(self, i, people, robot_position, robot_radius, rng):
        here = people.goals[i]
        return self.starts[i] if np.allclose(here, self.goals[i]) else self.goals[i]


def _polygon(shape, n: int = 32) -> np.ndarray:
    """A static shape as a wall polygon (pixels); a circle as the ``n``-gon around it."""
    if hasattr(shape, "vertices"):
        return np.asarray(shape.vertices, dtype=float)
    a = np.linspace(0.0, 2.0 * np.pi, n, endpoint=False)
    r = shape.radius / np.cos(np.pi / n)  # the polygon contains the disc
    return np.asarray(shape.center) + r * np.column_stack([np.cos(a), np.sin(a)])


def people_of(scenario, rng: np.random.Generator | None = None) -> People | None:
    """The scenario's people (``None`` without a ``[crowd]`` table), at their starts.

    Parameters
    ----------
    scenario : Scenario
        A metre scenario (the loader refuses a crowd in a pixel one).
    rng : numpy.random.Generator, optional
        The people's generator (the goal policies of a file draw nothing; default: one seeded
        with the scenario's seed).
    """
    crowd = scenario.spec.crowd
    if crowd is None:
        return None
    units = scenario.units
    rng = np.random.default_rng(scenario.seed) if rng is None else rng
    starts = np.array([p.start for p in crowd.people], dtype=float)
    goals = np.array([p.goal for p in crowd.people], dtype=float)
    radii = np.array([p.radius for p in crowd.people], dtype=float)
    speed = np.array([p.speed for p in crowd.people], dtype=float)
    walls = [_polygon(o.shape) for o in scenario.obstacles if o.is_static]
    policy = BackAndForth(starts, goals) if crowd.goal_changing else KeepGoal()
    common = {
        "bounds": (scenario.width, scenario.height), "obstacles": walls, "goal_policy": policy,
        "rng": rng, "arrival_time": 1.0 / units.dt,  # slow down within 1 s of the goal
    }  # fmt: skip
    if crowd.model == "orca":
        from mawdo.planning.people.orca import OrcaParams, OrcaPeople

        params = OrcaParams.from_metres(units.resolution, units.dt)
        return OrcaPeople(starts, goals, radii, speed, params=params, **common)
    from mawdo.planning.people.social_force import SocialForceParams, SocialForcePeople

    params = SocialForceParams.from_metres(units.resolution, units.dt)
    return SocialForcePeople(starts, goals, radii, speed, params=params, **common)
