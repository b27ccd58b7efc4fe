"""Bounds on obstacle motion in a scenario file: speeds and knot counts the planner can honour.

An obstacle is refused, with the bound that works, when it moves faster than the map's
diagonal per time step (it would cross the whole map between two steps, so no step-wise
plan can see it), when its motion would change direction more than :data:`MAX_TURNS_PER_STEP`
times per step (a border bounce of a constant velocity, a corner of a patrol: every turn is a
knot that the cost kernel, the guard and the checker evaluate, so the work of a run grows with
them), or when a patrol has more than :data:`MAX_WAYPOINTS` waypoints. The robot's own speed is
bounded in :mod:`mawdo.planning.world.scenario_schema` by the steps a run may take.
"""

from __future__ import annotations

import math

import numpy as np

__all__ = ["MAX_TURNS_PER_STEP", "MAX_WAYPOINTS", "motion_errors"]

#: Most changes of direction per time step an obstacle's motion may make.
MAX_TURNS_PER_STEP = 16
#: Most waypoints of one patrol.
MAX_WAYPOINTS = 10_000


def motion_errors(spec, offset_bounds) -> list[tuple[str, str]]:
    """``(field, message)`` for each obstacle motion of ``spec`` (a validated
    :class:`~mawdo.planning.world.scenario_schema.ScenarioSpec`) beyond the bounds above;
    ``offset_bounds(shape, W, H)`` gives the offsets that keep a shape inside the map."""
    W, H = spec.width, spec.height
    diag = math.hypot(W, H)
    errors = []
    for i, ob in enumerate(spec.obstacles):
        m, path = ob.motion, f"obstacles[{i}].motion"
        if m.model == "constant_velocity":
            errors += _velocity_errors(path, m.velocity, *offset_bounds(ob, W, H), diag)
        elif m.model == "patrol":
            errors += _patrol_errors(path, m, diag)
        elif m.model == "bounded_random_walk" and m.step > diag:
            errors.append((f"{path}.step", _too_fast(m.step, diag)))
    return errors


def _too_fast(speed: float, diag: float) -> str:
    return (
        f"{speed:g} px per step crosses the whole map (diagonal {diag:.4g} px) between two time "
        f"steps, where no plan can see it; give a speed of at most {diag:.4g} px per step"
    )


def _velocity_errors(path: str, velocity, lo, hi, diag: float) -> list[tuple[str, str]]:
    speed = math.hypot(*velocity)
    if speed > diag:
        return [(f"{path}.velocity", _too_fast(speed, diag))]
    for axis, name in enumerate("xy"):
        span, v = float(hi[axis] - lo[axis]), abs(float(velocity[axis]))
        if span > 0.0 and v > MAX_TURNS_PER_STEP * span:
            return [
                (
                    f"{path}.velocity",
                    f"bounces off the map border {v / span:.3g} times per time step along "
                    f"{name} (it has {span:.4g} px to move in); at most {MAX_TURNS_PER_STEP}: "
                    f"give at most {MAX_TURNS_PER_STEP * span:.4g} px per step along {name}",
                )
            ]
    return []


def _patrol_errors(path: str, m, diag: float) -> list[tuple[str, str]]:
    if len(m.waypoints) > MAX_WAYPOINTS:
        n = len(m.waypoints)
        return [(f"{path}.waypoints", f"{n:,} waypoints; a patrol may have {MAX_WAYPOINTS:,}")]
    if m.speed > diag:
        return [(f"{path}.speed", _too_fast(m.speed, diag))]
    pts = np.vstack([np.zeros((1, 2)), np.asarray(m.waypoints, dtype=float)])
    legs = np.hypot(*np.diff(pts, axis=0).T)
    closing = float(np.hypot(*pts[-1]))
    lap = float(legs.sum()) * 2.0 if m.cycle == "back_and_forth" else float(legs.sum()) + closing
    corners = 2 * len(m.waypoints) if m.cycle == "back_and_forth" else len(m.waypoints) + 1
    if lap > 0.0 and m.speed * corners / lap > MAX_TURNS_PER_STEP:
        top = MAX_TURNS_PER_STEP * lap / corners
        return [
            (
                f"{path}.speed",
                f"{m.speed:g} px per step turns {m.speed * corners / lap:.3g} corners per time "
                f"step on this {lap:.4g} px patrol; at most {MAX_TURNS_PER_STEP}: give a speed "
                f"of at most {top:.4g} px per step",
            )
        ]
    return []
