"""People in a scenario file: the ``[crowd]`` table and its checks.

A scenario may hold people who react (:mod:`mawdo.planning.people`) beside its scripted
obstacles::

    units = "m"                       # people need metres and seconds (their models' units)
    dt = 0.25
    resolution = 0.05

    [crowd]
    model = "orca"                    # or "social_force"
    visible = false                   # do the people see (and avoid) the robot?
    goal_changing = false             # a person who arrives picks a new goal (else stops)

    [[crowd.people]]
    start = [2.0, 5.0]
    goal = [8.0, 5.0]
    radius = 0.3                      # metres
    speed = 1.0                       # preferred speed, metres per second

The people's models are parameterised in metres and seconds (CrowdNav's ORCA and social-force
settings), so a crowd needs a metre scenario; the loader converts it to pixels with the rest.
"""

from __future__ import annotations

from typing import Literal

import shapely
from pydantic import BaseModel, ConfigDict, Field

__all__ = ["CrowdSpec", "PersonSpec", "crowd_errors"]

Point = tuple[float, float]


class PersonSpec(BaseModel):
    """One person: where they start and head (pixels after loading), radius, preferred speed."""

    model_config = ConfigDict(extra="forbid", frozen=True)

    id: str | None = None
    start: Point
    goal: Point
    radius: float = Field(gt=0)
    speed: float = Field(gt=0)


class CrowdSpec(BaseModel):
    """The people of a scenario and how they move."""

    model_config = ConfigDict(extra="forbid", frozen=True)

    model: Literal["orca", "social_force"] = "orca"
    visible: bool = False
    goal_changing: bool = False
    people: list[PersonSpec] = Field(min_length=1)


def _gap(a, b) -> float:
    return float(shapely.Point(a).distance(shapely.Point(b)))


def _inside_map(p, r: float, W: float, H: float) -> bool:
    return r <= p[0] <= W - r and r <= p[1] <= H - r


def crowd_errors(spec, units, say) -> list[tuple[str, str]]:
    """Whole-scenario checks of ``spec.crowd`` (a pixel spec; messages in the file's units):
    a crowd needs a metre file; every person's start and goal keep their disc inside the map
    and out of the static obstacles; starts do not overlap each other or the robot's."""
    crowd = spec.crowd
    if crowd is None:
        return []
    if units.is_pixels:
        return [("crowd", 'people need a metre scenario (their models are in metres and '
                 'seconds): add units = "m" with dt (s) and resolution (m per unit)')]  # fmt: skip
    W, H = spec.width, spec.height
    walls = [ob for ob in spec.obstacles if ob.motion.model == "static"]
    errors = []
    for i, p in enumerate(crowd.people):
        path = f"crowd.people[{i}]"
        for name in ("start", "goal"):
            xy = getattr(p, name)
            if not _inside_map(xy, p.radius, W, H):
                errors.append((f"{path}.{name}", f"the person's disc (radius {say(p.radius)} "
                               f"{say.L}) must lie inside the map"))  # fmt: skip
                continue
            hit = next((ob for ob in walls if ob.distance(xy) < p.radius), None)
            if hit is not None:
                what = repr(hit.id) if hit.id else "a static obstacle"
                errors.append((f"{path}.{name}", f"the person's disc is inside a wall ({what}): "
                               "move the point out of it"))  # fmt: skip
        if _gap(p.start, spec.start) < p.radius + spec.robot.radius:
            errors.append((f"{path}.start", "overlaps the robot's start"))
        for k in range(i):
            q = crowd.people[k]
            if _gap(p.start, q.start) < p.radius + q.radius:
                errors.append((f"{path}.start", f"overlaps crowd.people[{k}].start"))
    return errors
