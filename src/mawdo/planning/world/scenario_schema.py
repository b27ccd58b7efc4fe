"""The scenario file's schema (version 1): its fields, validated by pydantic, the checks of the
scenario as a whole, and the messages that name each problem's field path
(``obstacles[2].radius: must be > 0``), collected in one :class:`ScenarioError`.

Units: positions and sizes in pixels, time in time steps, speeds in pixels per time step (see
:mod:`mawdo.planning.world.scenario`); or, with ``units = "m"``, ``dt`` (seconds per time step)
and ``resolution`` (metres per pixel), metres, seconds and metres per second
(:mod:`mawdo.planning.world.units`).

File layout (TOML)::

    schema_version = 1
    name = "example"
    seed = 7                       # seeds the random-walk obstacles
    width = 366.0                  # pixels
    height = 366.0
    start = [20.0, 20.0]
    goal = [346.0, 346.0]
    robot = { radius = 4.0, speed = 4.0 }
    spots = [[60.0, 300.0]]        # optional: waiting spots (bays, corners) for the time guide

    [[obstacles]]                  # static polygon (motion omitted = static)
    shape = "polygon"
    vertices = [[100, 100], [160, 100], [130, 150]]

    [[obstacles]]                  # moving circle; a motion table without `model`
    shape = "circle"               # is constant_velocity (reflects at the border)
    center = [200, 80]
    radius = 12
    motion = { velocity = [1.5, 0.5] }

Other motions: ``{ model = "patrol", waypoints = [[dx, dy], ...], speed = 2.0 }`` (offsets from
the written position; the route is closed through ``(0, 0)``; ``cycle = "back_and_forth"`` retraces
it instead; ``waits = [w0, w1, ...]`` stops it for that many steps at each point) and
``{ model = "bounded_random_walk", step = 1.5, hold = 5 }`` (speed at most
``step``, a new random velocity every ``hold`` steps).

A file in metres and seconds adds (and must give ``width``, ``height`` and ``robot``: the pixel
defaults mean nothing in metres)::

    units = "m"
    dt = 0.25                      # seconds per time step
    resolution = 0.05              # metres per pixel
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Annotated, Any, Literal

import numpy as np
import shapely
from pydantic import (
    BaseModel,
    ConfigDict,
    Discriminator,
    Field,
    Tag,
    ValidationError,
    ValidationInfo,
    field_serializer,
    field_validator,
)
from pydantic_core import PydanticCustomError

from mawdo.planning.world.crowd_schema import CrowdSpec, crowd_errors
from mawdo.planning.world.motion_bounds import motion_errors
from mawdo.planning.world.units import PIXELS, Units

__all__ = [
    "MAX_RUN_STEPS",
    "SCHEMA_VERSION",
    "CircleObstacle",
    "PolygonObstacle",
    "ScenarioError",
    "ScenarioSpec",
    "field_errors",
    "offset_bounds",
    "pixel_note",
    "semantic_errors",
]

SCHEMA_VERSION = 1
# Coordinates are bounded so that geometry stays far from float overflow (pixels).
MAX_COORD = 1e6
MAX_MAP_SIZE = 1e5
# Most time steps any run may take: a robot too slow to cross its map's diagonal in this many
# steps is refused (robot.speed = 1e-6 once set a step limit of 9e8, days of computing).
MAX_RUN_STEPS = 1_000_000
# Start and goal closer than this (px) are one point: there is no route to plan or measure.
SAME_POINT = 1e-9

Coord = Annotated[float, Field(ge=-MAX_COORD, le=MAX_COORD)]
Point = tuple[Coord, Coord]


class ScenarioError(ValueError):
    """An invalid scenario: ``errors`` lists ``(field_path, message)`` pairs.

    Parameters
    ----------
    errors : list of (str, str)
        Field paths (``obstacles[2].radius``; empty for the whole file) and messages.
    source : str, optional
        Where the scenario came from (a file name), for the message.
    """

    def __init__(self, errors: list[tuple[str, str]], source: str | None = None) -> None:
        self.errors = list(errors)
        self.source = source
        where = f" {source!r}" if source else ""
        lines = [f"{p}: {m}" if p else m for p, m in self.errors]
        super().__init__(f"invalid scenario{where}:\n  " + "\n  ".join(lines))


class _Model(BaseModel):
    # Unknown keys are typos; NaN/inf would poison geometry; frozen so specs can be shared.
    model_config = ConfigDict(extra="forbid", frozen=True, allow_inf_nan=False)


class StaticMotion(_Model):
    """The obstacle never moves."""

    model: Literal["static"] = "static"


class ConstantVelocityMotion(_Model):
    """Constant velocity (pixels per time step), reflecting at the map border."""

    model: Literal["constant_velocity"] = "constant_velocity"
    velocity: Point


class PatrolMotion(_Model):
    """Patrol through offsets (pixels) from the written position at ``speed`` px per step;
    ``waits`` (optional, time steps >= 0): how long it stands at the written position and at
    each waypoint before leaving (one more than the waypoints; retraced with the route)."""

    model: Literal["patrol"] = "patrol"
    waypoints: list[Point] = Field(min_length=1)
    speed: float = Field(ge=0)
    cycle: Literal["loop", "back_and_forth"] = "loop"
    waits: list[Annotated[float, Field(ge=0)]] | None = None


class RandomWalkMotion(_Model):
    """Seeded random walk: speed at most ``step`` px per step, a new velocity every ``hold``
    steps (a metre file: ``hold`` in seconds, a whole number of time steps)."""

    model: Literal["bounded_random_walk"] = "bounded_random_walk"
    step: float = Field(ge=0, le=MAX_MAP_SIZE)
    hold: int = Field(default=1, ge=1, le=10_000)

    @field_validator("hold", mode="wrap")
    @classmethod
    def _hold_seconds(cls, value: Any, handler, info: ValidationInfo):
        # a metre file (validation context units "m") gives seconds, checked as a whole
        # number of steps once dt is known (units.spec_to_pixels); a pixel file an integer
        if (info.context or {}).get("units") != "m":
            return handler(value)
        if isinstance(value, bool) or not isinstance(value, int | float):
            raise PydanticCustomError("float_type", "must be a number (seconds)")
        if not value > 0 or not math.isfinite(value):
            raise PydanticCustomError("greater_than", "", {"gt": 0})
        return float(value)

    @field_serializer("hold")
    def _hold_out(self, value):
        return value  # int steps, or float seconds in a metre file


_MOTION_TAGS = ("static", "constant_velocity", "patrol", "bounded_random_walk")


def _motion_tag(value: Any) -> str | None:
    # A motion table without `model` is the default moving model (constant velocity).
    if isinstance(value, dict):
        tag = value.get("model", "constant_velocity")
        return tag if isinstance(tag, str) else None
    return getattr(value, "model", None)


MotionSpec = Annotated[
    Annotated[StaticMotion, Tag("static")]
    | Annotated[ConstantVelocityMotion, Tag("constant_velocity")]
    | Annotated[PatrolMotion, Tag("patrol")]
    | Annotated[RandomWalkMotion, Tag("bounded_random_walk")],
    Discriminator(
        _motion_tag,
        custom_error_type="unknown_motion",
        custom_error_message=f"model must be one of {', '.join(_MOTION_TAGS)}",
    ),
]


class CircleObstacle(_Model):
    """A disc: ``center`` (pixels) and ``radius`` (pixels, > 0)."""

    shape: Literal["circle"]
    id: str | None = None
    center: Point
    radius: float = Field(gt=0, le=MAX_MAP_SIZE)
    motion: MotionSpec = StaticMotion()

    def bounds(self) -> tuple[float, float, float, float]:
        """``(xmin, ymin, xmax, ymax)`` at offset zero (pixels)."""
        (x, y), r = self.center, self.radius
        return (x - r, y - r, x + r, y + r)

    def distance(self, point) -> float:
        """Euclidean distance from ``point`` to the disc at offset zero (pixels; 0 inside)."""
        return max(math.dist(point, self.center) - self.radius, 0.0)


class PolygonObstacle(_Model):
    """A simple polygon (no holes) given by >= 3 vertices (pixels), in either orientation."""

    shape: Literal["polygon"]
    id: str | None = None
    vertices: list[Point] = Field(min_length=3)
    motion: MotionSpec = StaticMotion()

    def bounds(self) -> tuple[float, float, float, float]:
        """``(xmin, ymin, xmax, ymax)`` at offset zero (pixels)."""
        v = np.asarray(self.vertices)
        return (*v.min(axis=0), *v.max(axis=0))

    def distance(self, point) -> float:
        """Euclidean distance from ``point`` to the polygon at offset zero (pixels; 0 inside)."""
        return float(shapely.Polygon(self.vertices).distance(shapely.Point(point)))


ObstacleSpec = Annotated[CircleObstacle | PolygonObstacle, Field(discriminator="shape")]


class RobotSpec(_Model):
    """Disc robot: ``radius`` (pixels, >= 0; 0 is a point robot), ``speed`` (px per step, > 0)."""

    radius: float = Field(default=4.0, ge=0, le=MAX_MAP_SIZE)
    speed: float = Field(default=4.0, gt=0, le=MAX_MAP_SIZE)


class ScenarioSpec(_Model):
    """The scenario file, schema version 1 (see the module docstring for the layout)."""

    schema_version: Literal[1]
    name: str = "unnamed"
    description: str = ""
    seed: int = Field(default=0, ge=0, lt=2**63)
    #: ``"m"``: the file is in metres and seconds, with ``dt`` (seconds per time step) and
    #: ``resolution`` (metres per pixel); the default ``"px"`` is left out of
    #: :meth:`Scenario.to_dict`, so pixel files read and hash as before.
    units: Literal["px", "m"] = "px"
    dt: float | None = None
    resolution: float | None = None
    width: float = Field(default=366.0, gt=0, le=MAX_MAP_SIZE)
    height: float = Field(default=366.0, gt=0, le=MAX_MAP_SIZE)
    start: Point
    goal: Point
    robot: RobotSpec = RobotSpec()
    obstacles: list[ObstacleSpec] = Field(default_factory=list)
    #: Waiting spots (pixels): free points where a timed route may stop or turn (bays,
    #: corners), added to the safe-interval guide's roadmap. None (the default) is left out
    #: of :meth:`Scenario.to_dict`, so files without spots read and hash as before.
    spots: list[Point] | None = None
    #: People who react (:mod:`mawdo.planning.world.crowd_schema`); None is left out of
    #: :meth:`Scenario.to_dict`.
    crowd: CrowdSpec | None = None


def _format_loc(loc: tuple) -> str:
    """``('obstacles', 2, 'circle', 'radius')`` -> ``obstacles[2].radius`` (union tags dropped)."""
    tags = {"circle", "polygon", *_MOTION_TAGS}
    parts: list[str] = []
    prev: Any = None
    for item in loc:
        # pydantic inserts the tag of a discriminated union after the list index / `motion`
        if isinstance(item, str) and item in tags and (isinstance(prev, int) or prev == "motion"):
            prev = item
            continue
        if isinstance(item, int):
            parts.append(f"[{item}]")
        else:
            parts.append(("." if parts else "") + str(item))
        prev = item
    return "".join(parts)


def _num(x) -> str:
    return f"{x:g}" if isinstance(x, float) else str(x)


_MESSAGES: dict[str, Callable[[dict], str]] = {
    "greater_than": lambda c: f"must be > {_num(c['gt'])}",
    "greater_than_equal": lambda c: f"must be >= {_num(c['ge'])}",
    "less_than": lambda c: f"must be < {_num(c['lt'])}",
    "less_than_equal": lambda c: f"must be <= {_num(c['le'])}",
    "missing": lambda c: "required field is missing",
    "extra_forbidden": lambda c: "unknown field",
    "too_short": lambda c: f"needs at least {c['min_length']} items",
    "finite_number": lambda c: "must be a finite number",
    "union_tag_invalid": lambda c: (
        f"{c['discriminator'].strip(chr(39))} must be one of {c['expected_tags']}, got {c['tag']!r}"
    ),
    "union_tag_not_found": lambda c: f"needs a {c['discriminator']} field",
}


def field_errors(exc: ValidationError) -> list[tuple[str, str]]:
    out = []
    for err in exc.errors(include_url=False):
        make = _MESSAGES.get(err["type"])
        msg = make(err.get("ctx") or {}) if make else err["msg"]
        if err["type"] == "literal_error" and err["loc"] == ("schema_version",):
            msg = f"unsupported schema version {err['input']!r} (supported: {SCHEMA_VERSION})"
        elif err["type"] == "literal_error" and err["loc"] == ("units",):
            got = err["input"]
            msg = f'must be "px" (pixels, time steps) or "m" (metres, seconds), got {got!r}'
        out.append((_format_loc(err["loc"]), msg))
    return out


def offset_bounds(shape, width: float, height: float) -> tuple[np.ndarray, np.ndarray]:
    """Offsets ``[lo, hi]`` per axis that keep the shape's bounding box in the map (pixels)."""
    xmin, ymin, xmax, ymax = shape.bounds()
    return np.array([-xmin, -ymin]), np.array([width - xmax, height - ymax])


class _Say:
    """Numbers of a message in the file's units: lengths given in pixels are written in
    ``units`` (metres for a metre file), with their label."""

    def __init__(self, units: Units) -> None:
        self.u, self.L = units, units.length_label

    def __call__(self, *px: float) -> str | tuple[str, ...]:
        out = tuple(f"{self.u.length(x):g}" for x in px)
        return out[0] if len(out) == 1 else out


def _border_message(x: float, y: float, W: float, H: float, r: float, say: _Say) -> str:
    """Why a point is refused for the robot's centre: its disc leaves the map."""
    (x, y, Wu, Hu, ru), L = say(x, y, W, H, r), say.L
    if W < 2 * r or H < 2 * r:
        return (
            f"({x}, {y}): the robot disc (radius {ru} {L}) does not fit in the "
            f"{Wu} x {Hu} {L} map; use a smaller robot radius or a larger map"
        )
    lo_x, hi_x, hi_y = say(r, W - r, H - r)
    return (
        f"({x}, {y}) is closer than the robot radius {ru} {L} to the map border (the disc "
        f"would leave the map); allowed: [{lo_x}, {hi_x}] x [{lo_x}, {hi_y}]"
    )


def _outside(x: float, y: float, W: float, H: float, say: _Say) -> str:
    x, y, W, H = say(x, y, W, H)
    return f"({x}, {y}) is outside the map [0, {W}] x [0, {H}]"


def semantic_errors(spec: ScenarioSpec, units: Units = PIXELS) -> list[tuple[str, str]]:
    """Whole-scenario checks that single fields cannot express, on a pixel spec; the numbers
    of the messages are written in ``units`` (the file's: a metre file reads its own numbers)."""
    W, H, r = spec.width, spec.height, spec.robot.radius
    say = _Say(units)
    errors = _trip_errors(spec, units)
    for name in ("start", "goal"):
        x, y = getattr(spec, name)
        if not (0.0 <= x <= W and 0.0 <= y <= H):
            errors.append((name, _outside(x, y, W, H, say)))
        elif not (r <= x <= W - r and r <= y <= H - r):  # the border is a wall, as an obstacle
            errors.append((name, _border_message(x, y, W, H, r, say)))
    seen: dict[str, int] = {}
    for i, ob in enumerate(spec.obstacles):
        path = f"obstacles[{i}]"
        if ob.id is not None:
            if ob.id in seen:
                errors.append(
                    (f"{path}.id", f"duplicate id {ob.id!r} (also obstacles[{seen[ob.id]}])")
                )
            seen.setdefault(ob.id, i)
        if isinstance(ob, PolygonObstacle):
            poly = shapely.Polygon(ob.vertices)
            if not poly.is_valid:
                why = shapely.is_valid_reason(poly)
                if not units.is_pixels:  # the reason's point is in pixels
                    why += f"; at {units.resolution:g} m per px"
                errors.append((f"{path}.vertices", f"polygon is not simple/valid ({why})"))
                continue
            if poly.area <= 0.0:
                errors.append((f"{path}.vertices", "polygon has zero area"))
                continue
        lo, hi = offset_bounds(ob, W, H)
        motion = ob.motion
        if not isinstance(motion, StaticMotion) and (np.any(lo > 0) or np.any(hi < 0)):
            errors.append((path, "a moving obstacle must lie inside the map at t=0"))
        if isinstance(motion, PatrolMotion):
            if motion.waits is not None and len(motion.waits) != len(motion.waypoints) + 1:
                errors.append(
                    (
                        f"{path}.motion.waits",
                        f"needs {len(motion.waypoints) + 1} times (the written position and "
                        f"each waypoint), got {len(motion.waits)}",
                    )
                )
            for j, w in enumerate(motion.waypoints):
                if np.any(np.asarray(w) < lo) or np.any(np.asarray(w) > hi):
                    errors.append(
                        (f"{path}.motion.waypoints[{j}]", "moves the obstacle outside the map")
                    )
        for name in ("start", "goal"):
            if ob.distance(getattr(spec, name)) <= r:
                who = f"obstacles[{i}]" + (f" ({ob.id!r})" if ob.id else "")
                errors.append(
                    (name, f"inside {who} inflated by the robot radius {say(r)} {say.L} at t=0")
                )
    moves = motion_errors(spec, offset_bounds)
    if not units.is_pixels:  # its bounds are written in the planner's units
        moves = [(p, f"{m} ({pixel_note(units)})") for p, m in moves]
    return errors + _spot_errors(spec, say) + moves + crowd_errors(spec, units, say)


def pixel_note(units: Units) -> str:
    """How a metre file's message written in pixels and time steps says so."""
    return f"in pixels and time steps: {units.resolution:g} m per px, {units.dt:g} s per step"


def _spot_errors(spec: ScenarioSpec, say: _Say) -> list[tuple[str, str]]:
    """Each waiting spot must hold the robot: its disc inside the map and clear of every
    static obstacle (movers may cross it: the time guide waits there only while it is safe)."""
    W, H, r = spec.width, spec.height, spec.robot.radius
    errors = []
    statics = [
        (i, ob) for i, ob in enumerate(spec.obstacles) if isinstance(ob.motion, StaticMotion)
    ]
    for j, (x, y) in enumerate(spec.spots or []):
        path = f"spots[{j}]"
        if not (0.0 <= x <= W and 0.0 <= y <= H):
            errors.append((path, _outside(x, y, W, H, say) + "; move or drop the spot"))
            continue
        if not (r <= x <= W - r and r <= y <= H - r):
            errors.append((path, _border_message(x, y, W, H, r, say) + "; move or drop the spot"))
            continue
        for i, ob in statics:
            if ob.distance((x, y)) <= r:
                who = f"obstacles[{i}]" + (f" ({ob.id!r})" if ob.id else "")
                xs, ys = say(x, y)
                errors.append(
                    (path, f"({xs}, {ys}) is inside static {who} inflated by the robot "
                           f"radius {say(r)} {say.L}; a spot must hold the robot: move or drop it")
                )  # fmt: skip
                break
    return errors


def _trip_errors(spec: ScenarioSpec, units: Units) -> list[tuple[str, str]]:
    """A goal away from the start, and a robot fast enough to cross the map in a bounded
    number of steps."""
    errors = []
    say = _Say(units)
    if math.dist(spec.start, spec.goal) <= SAME_POINT:
        x, y = say(*spec.goal)
        errors.append(("goal", f"({x}, {y}) is the start: a run needs a goal away from the start"))
    diagonal, v = math.hypot(spec.width, spec.height), spec.robot.speed
    if diagonal / v > MAX_RUN_STEPS:
        u, V, L, T = units, _per(units.speed_label), say.L, units.time_label
        W, H = say(spec.width, spec.height)
        lo, hi = u.speed(diagonal / MAX_RUN_STEPS), u.speed(MAX_MAP_SIZE)
        m, steps = ("", "") if u.is_pixels else (" m", " steps")  # (pixel wording as it was)
        errors.append(
            (
                "robot.speed",
                f"{u.speed(v):g} {V} is too slow for a {W} x {H}{m} map: crossing its "
                f"diagonal ({u.length(diagonal):.4g} {L}) would take {u.time(diagonal / v):.3g} "
                f"{T}, more than the {MAX_RUN_STEPS:,}{steps} a run may have; give a speed in "
                f"[{lo:.3g}, {hi:g}] {V}",
            )
        )
    return errors


def _per(label: str) -> str:
    """``"px/step"`` as the messages write it (``px per step``); ``"m/s"`` as it is."""
    return "px per step" if label == "px/step" else label
