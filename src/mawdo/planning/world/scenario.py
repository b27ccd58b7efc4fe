"""World model for path planning: map, start and goal, robot, obstacles and their motion.

A scenario is read from a dict (TOML or JSON file, schema version 1), validated field by field by
pydantic and then checked as a whole (start and goal inside the map with the whole robot disc
(its centre at least the radius from the border) and clear of obstacles,
polygons simple, moving obstacles inside the map). Every problem is reported with the path of the
offending field, e.g. ``obstacles[2].radius: must be > 0``, in one :class:`ScenarioError`.

Units: positions and sizes in pixels (x right, y up, origin at the lower-left map corner), time in
time steps, speeds in pixels per time step. A file may be written in metres and seconds instead
(``units = "m"`` with ``dt`` and ``resolution``): :attr:`Scenario.spec` is then its pixel
conversion, what every caller reads, while :meth:`Scenario.to_dict` writes the file back in
metres and :attr:`Scenario.units` converts what the user reads (see
:mod:`mawdo.planning.world.units` for why the conversion happens here).

The file format (fields, validation and messages) is :mod:`mawdo.planning.world.scenario_schema`;
its layout is shown there.
"""

from __future__ import annotations

import tomllib
from collections.abc import Callable
from dataclasses import dataclass
from importlib import resources
from pathlib import Path
from typing import Any

import numpy as np
from pydantic import ValidationError

from mawdo.planning.world.motion import BoundedRandomWalk, ConstantVelocity, Motion, Patrol, Static
from mawdo.planning.world.scenario_schema import (
    MAX_MAP_SIZE,
    MAX_RUN_STEPS,
    SCHEMA_VERSION,
    CircleObstacle,
    ConstantVelocityMotion,
    PatrolMotion,
    PolygonObstacle,
    RandomWalkMotion,
    ScenarioError,
    ScenarioSpec,
    field_errors,
    offset_bounds,
    pixel_note,
    semantic_errors,
)
from mawdo.planning.world.scenario_text import ScenarioTextError, parse_scenario_text
from mawdo.planning.world.uncertainty import Uncertainty
from mawdo.planning.world.units import PIXELS, Units, spec_to_pixels, spec_units, units_errors
from mawdo.registry import Registry

__all__ = [
    "MAX_RUN_STEPS",
    "SCENARIOS",
    "SCHEMA_VERSION",
    "CircleObstacle",
    "Obstacle",
    "PolygonObstacle",
    "Scenario",
    "ScenarioError",
    "ScenarioSpec",
    "Units",
    "get_scenario",
    "load_scenario",
    "scenario_from_dict",
]


# --------------------------------------------------------------------------------------------
# runtime objects


@dataclass(frozen=True, eq=False)
class Obstacle:
    """One obstacle of a scenario: its shape (at offset zero) and its motion.

    Attributes
    ----------
    index : int
        Position in ``Scenario.obstacles``.
    id : str
        Name from the file, or ``obstacle-<index>``.
    shape : CircleObstacle or PolygonObstacle
        The validated shape spec (pixels), as written in the file (a metre file: converted).
    motion : Motion
        Translation of the shape over time (see :mod:`mawdo.planning.world.motion`).
    """

    index: int
    id: str
    shape: CircleObstacle | PolygonObstacle
    motion: Motion

    @property
    def is_static(self) -> bool:
        return self.motion.is_static

    @property
    def is_circle(self) -> bool:
        return isinstance(self.shape, CircleObstacle)

    def offset(self, t) -> np.ndarray:
        """Translation of the shape at times ``t`` (time steps): ``t.shape + (2,)`` pixels."""
        return self.motion.offset(t)

    def knots(self, t0: float, t1: float) -> tuple[np.ndarray, np.ndarray]:
        """Constant-velocity pieces of ``[t0, t1]``; see :meth:`Motion.knots`."""
        return self.motion.knots(t0, t1)


@dataclass(frozen=True, eq=False)
class Scenario:
    """A validated scenario ready for planning.

    Build one with :func:`scenario_from_dict`, :func:`load_scenario`, :func:`get_scenario` or the
    raster loaders in :mod:`mawdo.planning.world.rasters`.

    Attributes
    ----------
    spec : ScenarioSpec
        The validated scenario in pixels and time steps: the file's contents, or for a file in
        metres (``units = "m"``) their conversion (:func:`~mawdo.planning.world.units
        .spec_to_pixels`).
    obstacles : tuple of Obstacle
        Runtime obstacles, in file order.
    file_spec : ScenarioSpec or None
        The metre file's contents as written (round-trip with :meth:`to_dict`); None for a
        pixel scenario, whose ``spec`` is its file. Replacing ``spec`` of a metre scenario
        (``dataclasses.replace``) is refused: build it again from its dict instead.
    derived_units : Units or None
        The units of the scenario a derived one (a prediction, the realised world of a
        stepped run: :mod:`mawdo.planning.world.stepped`) was made from, when it has no file of
        its own; None otherwise.
    uncertainty : Uncertainty or None
        For a prediction scenario, how far its movers' true centres may stray from the
        predicted ones (:mod:`mawdo.planning.world.uncertainty`); None for a scenario whose
        motions are known.
    """

    spec: ScenarioSpec
    obstacles: tuple[Obstacle, ...]
    file_spec: ScenarioSpec | None = None
    derived_units: Units | None = None
    uncertainty: Uncertainty | None = None

    def __post_init__(self) -> None:
        if self.file_spec is None:
            return
        px = pixel_spec(self.file_spec, self.units, None)
        if px.model_dump() != self.spec.model_dump():
            raise ValueError(
                f"scenario {self.file_spec.name!r}: spec is not the pixel conversion of "
                "file_spec; change a metre scenario through its dict (to_dict, then "
                "scenario_from_dict), not by replacing its spec"
            )

    @property
    def units(self) -> Units:
        """The units its user reads and writes: metres and seconds for a file with
        ``units = "m"``, else pixels and time steps (every conversion the identity)."""
        if self.file_spec is None:
            return PIXELS if self.derived_units is None else self.derived_units
        return spec_units(self.file_spec)

    @property
    def name(self) -> str:
        return self.spec.name

    @property
    def width(self) -> float:
        """Map width (pixels)."""
        return self.spec.width

    @property
    def height(self) -> float:
        """Map height (pixels)."""
        return self.spec.height

    @property
    def bounds(self) -> tuple[float, float, float, float]:
        """Map box ``(0, 0, width, height)`` (pixels)."""
        return (0.0, 0.0, self.spec.width, self.spec.height)

    @property
    def start(self) -> np.ndarray:
        """Start position (pixels), shape (2,)."""
        return np.array(self.spec.start, dtype=float)

    @property
    def goal(self) -> np.ndarray:
        """Goal position (pixels), shape (2,)."""
        return np.array(self.spec.goal, dtype=float)

    @property
    def robot_radius(self) -> float:
        """Robot disc radius ``r`` (pixels); obstacles are inflated by it."""
        return self.spec.robot.radius

    @property
    def robot_speed(self) -> float:
        """Robot speed ``v`` (pixels per time step)."""
        return self.spec.robot.speed

    @property
    def seed(self) -> int:
        return self.spec.seed

    @property
    def static_indices(self) -> list[int]:
        """Indices of obstacles that never move."""
        return [o.index for o in self.obstacles if o.is_static]

    @property
    def moving_indices(self) -> list[int]:
        """Indices of obstacles that move."""
        return [o.index for o in self.obstacles if not o.is_static]

    @property
    def spots(self) -> np.ndarray:
        """Waiting spots (pixels), shape ``(k, 2)``; ``(0, 2)`` when the file gives none."""
        return np.asarray(self.spec.spots or [], dtype=float).reshape(-1, 2)

    def straight_line_length(self) -> float:
        """Length of the straight start-goal segment (pixels)."""
        return float(np.hypot(*(self.goal - self.start)))

    def offsets(self, t) -> np.ndarray:
        """Every obstacle's translation at times ``t`` (time steps).

        Parameters
        ----------
        t : float or array_like
            Times (time steps), any shape.

        Returns
        -------
        numpy.ndarray
            Shape ``t.shape + (n_obstacles, 2)``, pixels. Deterministic in the scenario's seed.
        """
        t = np.asarray(t, dtype=float)
        if not self.obstacles:
            return np.zeros(t.shape + (0, 2))
        return np.stack([o.offset(t) for o in self.obstacles], axis=-2)

    def to_dict(self) -> dict:
        """The scenario as a plain dict (JSON-compatible) that validates back to an equal one,
        in its file's units (a metre file's own values; ``units`` only when ``"m"``)."""
        spec = self.spec if self.file_spec is None else self.file_spec
        out = spec.model_dump(mode="json", exclude_none=True)
        if out.get("units") == "px":
            del out["units"]  # pixel files read and hash as they did before units existed
        return out


# --------------------------------------------------------------------------------------------
# building and loading


def _build_motion(ob, index: int, spec: ScenarioSpec) -> Motion:
    m = ob.motion
    lo, hi = offset_bounds(ob, spec.width, spec.height)
    if isinstance(m, ConstantVelocityMotion):
        return ConstantVelocity(tuple(m.velocity), tuple(lo), tuple(hi))
    if isinstance(m, PatrolMotion):
        way = np.asarray(m.waypoints, dtype=float)
        route = np.vstack([np.zeros((1, 2)), way])
        waits = None if m.waits is None else np.asarray(m.waits, dtype=float)
        if m.cycle == "back_and_forth":
            route = np.vstack([route, route[-2:0:-1]])  # retrace, the closing leg ends at (0, 0)
            waits = None if waits is None else np.concatenate([waits, waits[-2:0:-1]])
        return Patrol(route, m.speed, waits)
    if isinstance(m, RandomWalkMotion):
        # one independent stream per obstacle, derived from the scenario seed
        seed = np.random.SeedSequence(spec.seed, spawn_key=(index,))
        return BoundedRandomWalk(m.step, tuple(lo), tuple(hi), seed, m.hold)
    return Static()


def scenario_from_spec(spec: ScenarioSpec, source: str | None = None) -> Scenario:
    """Check a parsed spec as a whole and build the runtime :class:`Scenario` (a spec in
    metres is converted to pixels first; its messages keep the file's units)."""
    errors = units_errors(spec)
    if errors:
        raise ScenarioError(errors, source)
    units = spec_units(spec)
    file_spec = None if units.is_pixels else spec
    if file_spec is not None:
        spec = pixel_spec(file_spec, units, source)
    errors = semantic_errors(spec, units)
    if errors:
        raise ScenarioError(errors, source)
    obstacles = tuple(
        Obstacle(i, ob.id or f"obstacle-{i}", ob, _build_motion(ob, i, spec))
        for i, ob in enumerate(spec.obstacles)
    )
    return Scenario(spec, obstacles, file_spec)


def pixel_spec(spec: ScenarioSpec, units: Units, source: str | None) -> ScenarioSpec:
    """A metre spec converted to pixels and time steps, validated as a pixel file (its bounds
    hold in pixels: a 10 km map at 5 cm per pixel is too large)."""
    data = spec_to_pixels(spec.model_dump(exclude_none=True), units)
    side = max(data["width"], data["height"])
    if side > MAX_MAP_SIZE:  # every other bound then fails too: say what causes it
        res, least = units.resolution, max(spec.width, spec.height) / MAX_MAP_SIZE
        why = (
            f"{res:g} m per px makes the {spec.width:g} x {spec.height:g} m map "
            f"{data['width']:.4g} x {data['height']:.4g} px, more than the {MAX_MAP_SIZE:g} px "
            f"a side the planner takes; give a resolution of at least {least:.3g} m per px"
        )
        raise ScenarioError([("resolution", why)], source)
    try:
        return ScenarioSpec.model_validate(data)
    except ValidationError as exc:
        note = pixel_note(units)
        raise ScenarioError([(p, f"{m} ({note})") for p, m in field_errors(exc)], source) from None


def scenario_from_dict(data: Any, source: str | None = None) -> Scenario:
    """Validate a scenario dict (the parsed TOML/JSON file) and build the :class:`Scenario`.

    Parameters
    ----------
    data : dict
        Scenario contents, schema version 1.
    source : str, optional
        Name of the origin, used in error messages.

    Raises
    ------
    ScenarioError
        With every problem found, each prefixed by its field path.
    """
    if not isinstance(data, dict):
        raise ScenarioError([("", f"expected a table/object, got {type(data).__name__}")], source)
    try:
        # a metre file's random-walk hold is in seconds (RandomWalkMotion)
        spec = ScenarioSpec.model_validate(data, context={"units": data.get("units")})
    except ValidationError as exc:
        raise ScenarioError(field_errors(exc), source) from None
    return scenario_from_spec(spec, source)


def load_scenario(path: str | Path) -> Scenario:
    """Read and validate a scenario file (``.toml`` or ``.json``).

    Raises
    ------
    FileNotFoundError
        If the file does not exist.
    ScenarioError
        If the file cannot be parsed or does not validate.
    """
    path = Path(path)
    suffix = path.suffix.lower()
    if suffix not in (".toml", ".json"):
        raise ScenarioError(
            [("", f"unsupported file type {suffix!r} (use .toml or .json)")], str(path)
        )
    if not path.is_file():
        raise FileNotFoundError(f"no such scenario file: {str(path)!r}")
    try:
        raw = path.read_bytes()
    except OSError as exc:
        raise ScenarioError([("", f"cannot read file: {exc}")], str(path)) from None
    try:
        data = parse_scenario_text(raw.decode("utf-8"), suffix[1:])
    except UnicodeDecodeError as exc:
        raise ScenarioError(
            [("", f"cannot parse {suffix[1:].upper()}: {exc}")], str(path)
        ) from None
    except ScenarioTextError as exc:
        raise ScenarioError([("", str(exc))], str(path)) from None
    return scenario_from_dict(data, source=str(path))


# --------------------------------------------------------------------------------------------
# built-in scenarios

#: Named scenarios: each entry is a zero-argument factory returning a fresh :class:`Scenario`.
SCENARIOS: Registry[Callable[[], Scenario]] = Registry("scenario")


def _builtin(filename: str) -> Callable[[], Scenario]:
    def factory() -> Scenario:
        text = resources.files("mawdo.planning").joinpath("data", filename).read_text("utf-8")
        return scenario_from_dict(tomllib.loads(text), source=f"builtin:{filename}")

    return factory


SCENARIOS.register("paper", _builtin("paper.toml"))
# metres and seconds, with people who react (a stepped world: SteppedWorld.of)
SCENARIOS.register("hall", _builtin("hall.toml"))


def get_scenario(name: str | Path) -> Scenario:
    """A built-in scenario by name (see :data:`SCENARIOS`) or a scenario file by path.

    Raises
    ------
    mawdo.registry.UnknownNameError
        For an unknown name that is not an existing file; the message lists close names.
    """
    if not isinstance(name, str | Path):
        raise TypeError(f"scenario name must be a string, got {type(name).__name__}")
    name = str(name)
    if name.lower() not in SCENARIOS and Path(name).suffix.lower() in (".toml", ".json"):
        return load_scenario(name)
    return SCENARIOS[name]()
