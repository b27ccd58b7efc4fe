"""Scene families: parameters with ranges, seeded drafts, validation and the exact optimum ``L*``.

A *family* draws scenario drafts (plain dicts in the scenario schema) from a random generator and
its resolved parameters. :func:`generate_scene` turns a draft into a :class:`Scene` only after it
validates as a scenario, its start and goal are free by ``robot_radius + clearance`` (from the
obstacles and from the map's border), and the exact oracle finds a static route; the optimum's
length is stored as ``l_star``. A draft that fails is redrawn from the next attempt's stream, at
most ``MAX_ATTEMPTS`` times, then the scene is rejected with every attempt's reason: an unsolvable
draw is never returned.

Seeding: scene ``index`` of ``(family, seed)`` draws attempt ``a`` from the stream at spawn key
``(crc32(family), index, a)`` below ``seed`` (:func:`mawdo.streams.keyed_seed_sequence`), so
a scene does not depend on how many scenes were generated or in which order.

Units: pixels, time steps, pixels per time step; obstacle speeds are given relative to the robot's.
"""

from __future__ import annotations

import difflib
import math
import zlib
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field, replace
from typing import Any

import numpy as np

from mawdo.planning.guide.oracle import scenario_optimum
from mawdo.planning.world.scenario import (
    SCHEMA_VERSION,
    Scenario,
    ScenarioError,
    scenario_from_dict,
)
from mawdo.streams import keyed_seed_sequence

__all__ = [
    "COMMON_PARAMS",
    "MAX_ATTEMPTS",
    "Family",
    "Param",
    "Redraw",
    "Scene",
    "SceneRejected",
    "draft",
    "endpoint_problems",
]

#: Draws per scene before it is rejected.
MAX_ATTEMPTS = 20


class Redraw(Exception):
    """Raised by a family's draft function when a draw cannot give a valid scene."""


class SceneRejected(ValueError):
    """No valid scene after ``MAX_ATTEMPTS`` draws; ``reasons`` lists each attempt's reason."""

    def __init__(self, family: str, seed: int, index: int, reasons: list[str]) -> None:
        self.family, self.seed, self.index, self.reasons = family, seed, index, list(reasons)
        counts: dict[str, int] = {}
        for r in reasons:
            counts[r] = counts.get(r, 0) + 1
        why = "; ".join(f"{r} (x{c})" for r, c in counts.items())
        super().__init__(
            f"{family} scene {index} (seed {seed}) rejected after {len(reasons)} draws: {why}. "
            "Relax the family's parameters (fewer or smaller obstacles, wider gaps)."
        )


@dataclass(frozen=True)
class Param:
    """A family parameter: default and inclusive range ``[low, high]``, or a set of choices.

    Attributes
    ----------
    name : str
    default : int, float or str
    low, high : float
        Inclusive range (ignored when ``choices`` is given).
    integer : bool
        The value must be an integer.
    doc : str
        Meaning and unit.
    choices : tuple of str
        Allowed values of a text parameter.
    """

    name: str
    default: Any
    low: float = -math.inf
    high: float = math.inf
    integer: bool = False
    doc: str = ""
    choices: tuple[str, ...] = ()

    def check(self, family: str, value: Any) -> Any:
        """``value`` converted to the parameter's type; ``ValueError`` naming the range if not."""
        where = f"{family} parameter {self.name!r}"
        if self.choices:
            if value not in self.choices:
                raise ValueError(f"{where} must be one of {list(self.choices)}, got {value!r}")
            return value
        if isinstance(value, bool) or not isinstance(value, int | float | np.integer | np.floating):
            raise ValueError(f"{where} must be a number, got {value!r}")
        if self.integer and float(value) != int(value):
            raise ValueError(f"{where} must be an integer, got {value!r}")
        if not (self.low <= value <= self.high):
            raise ValueError(
                f"{where} = {value!r} is out of range [{self.low:g}, {self.high:g}] ({self.doc})"
            )
        return int(value) if self.integer else float(value)


#: Parameters every family has.
COMMON_PARAMS = (
    Param("size", 366.0, 100.0, 2000.0, doc="map side, pixels"),
    Param("robot_radius", 4.0, 0.0, 20.0, doc="robot disc radius, pixels"),
    Param("robot_speed", 4.0, 0.5, 20.0, doc="robot speed, pixels per time step"),
    Param("clearance", 2.0, 0.0, 20.0, doc="free margin around start and goal, pixels"),
)


@dataclass(frozen=True)
class Family:
    """A registered scene family.

    Attributes
    ----------
    name : str
    description : str
    params : tuple of Param
        Family-specific parameters (:data:`COMMON_PARAMS` are added).
    draw : callable
        ``draw(rng, params) -> dict``: a scenario draft (see :func:`draft`); raises
        :class:`Redraw` when the draw cannot work.
    moving : bool
        Whether the family's scenes have moving obstacles.
    check : callable, optional
        ``check(params)`` raises ``ValueError`` for parameter combinations that can never give
        a solvable scene (e.g. a door narrower than the robot).
    timed : bool
        Time decides the scene: a draw is valid only if the earliest arrival ``T*``
        exists (:func:`mawdo.planning.guide.sipp.optimum.scenario_time_optimum`, with the draft's
        waiting spots, key ``"_spots"``, and dodge spots along the static optimum), and the
        scene stores it.
    """

    name: str
    description: str
    params: tuple[Param, ...]
    draw: Callable[[np.random.Generator, dict], dict]
    moving: bool = False
    check: Callable[[dict], None] | None = None
    timed: bool = False
    all_params: tuple[Param, ...] = field(init=False)

    def __post_init__(self) -> None:
        object.__setattr__(self, "all_params", (*COMMON_PARAMS, *self.params))

    def resolve(self, params: Mapping[str, Any] | None = None) -> dict[str, Any]:
        """Defaults overridden by ``params``, each checked against its range.

        Raises
        ------
        ValueError
            For an unknown parameter (close names suggested) or a value out of range.
        """
        known = {p.name: p for p in self.all_params}
        params = dict(params or {})
        for key in params:
            if key not in known:
                close = difflib.get_close_matches(key, known, n=2, cutoff=0.5)
                hint = f" Did you mean {', '.join(map(repr, close))}?" if close else ""
                raise ValueError(
                    f"unknown {self.name} parameter {key!r}.{hint} Known: {', '.join(known)}."
                )
        out = {n: p.check(self.name, params.get(n, p.default)) for n, p in known.items()}
        if self.check is not None:
            self.check(out)
        return out

    def key(self) -> int:
        """Stable integer key of the family name (spawn-key entry)."""
        return zlib.crc32(self.name.encode())


def draft(p: Mapping[str, Any], start, goal, obstacles: list[dict]) -> dict:
    """A scenario dict (schema version 1) on a ``size x size`` map from resolved parameters."""
    return {
        "schema_version": SCHEMA_VERSION,
        "width": p["size"],
        "height": p["size"],
        "start": [float(start[0]), float(start[1])],
        "goal": [float(goal[0]), float(goal[1])],
        "robot": {"radius": p["robot_radius"], "speed": p["robot_speed"]},
        "obstacles": obstacles,
    }


def endpoint_problems(scenario: Scenario, clearance: float) -> list[str]:
    """Why start or goal is not free: closer than ``robot_radius + clearance`` to an obstacle
    at t = 0 or to the map's border, a wall like the obstacles (empty list: both free)."""
    need = scenario.robot_radius + clearance
    out = []
    for name, p in (("start", scenario.start), ("goal", scenario.goal)):
        if min(p[0], p[1], scenario.width - p[0], scenario.height - p[1]) < need:
            out.append(f"{name} within robot radius + clearance of the map border")
        for ob in scenario.obstacles:
            if ob.shape.distance(p) <= need:
                out.append(f"{name} within robot radius + clearance of an obstacle")
                break
    return out


@dataclass(frozen=True, eq=False)
class Scene:
    """A validated generated scene.

    Attributes
    ----------
    family : str
    seed, index : int
        The scene is a pure function of ``(family, params, seed, index)``.
    params : dict
        Resolved family parameters.
    scenario : Scenario
        Named ``<family>-s<seed>-<index>``; its description records how to regenerate it.
    l_star : float
        Exact static optimum (pixels), static obstacles inflated by the robot radius.
    optimum : numpy.ndarray, shape (k, 2)
        The optimum's vertices (pixels).
    attempts : int
        Draws used (1 = the first draw was valid).
    t_star : float or None
        Earliest arrival at the goal (time steps; :mod:`mawdo.planning.guide.sipp.optimum`) for the
        families where time decides (``Family.timed``); ``None`` for the others.
    spots : numpy.ndarray, shape (k, 2)
        Waiting spots (pixels) ``T*`` was computed with: the family's (bays, a lattice of
        free points) and :func:`~mawdo.planning.guide.sipp.optimum.dodge_spots` along the static
        optimum.
    time_route : TimedRoute or None
        The earliest-arrival route (timed families).
    """

    family: str
    seed: int
    index: int
    params: dict
    scenario: Scenario
    l_star: float
    optimum: np.ndarray
    attempts: int
    t_star: float | None = None
    spots: np.ndarray = field(default_factory=lambda: np.zeros((0, 2)))
    time_route: Any = None

    @property
    def name(self) -> str:
        return self.scenario.name

    def to_toml(self) -> str:
        """The scene as a scenario file (``mawdo plan FILE`` re-runs it)."""
        from mawdo.planning.scenes.toml import scenario_to_toml

        return scenario_to_toml(self.scenario)

    def write(self, path) -> Any:
        """Write :meth:`to_toml` to ``path`` (a ``.toml`` file or a folder); returns the path."""
        from mawdo.planning.scenes.toml import write_scenario

        return write_scenario(self.scenario, path)


def _describe(family: Family, p: dict, seed: int, index: int, l_star: float, t_star=None) -> str:
    args = ", ".join(f"{k}={v!r}" for k, v in p.items())
    timed = "" if t_star is None else f"; earliest arrival T*={t_star:.6f} steps"
    return (
        f"mawdo.planning.scenes: family={family.name}, seed={seed}, index={index}, {args}; "
        f"static optimum L*={l_star:.6f} px{timed}"
    )


def _time_optimum(scenario: Scenario, spots: np.ndarray, path: np.ndarray):
    """``(TimeOptimum, spots, None)`` or ``(None, spots, reason)`` for a timed family's draw:
    its spots, with dodge spots along the static optimum ``path`` added."""
    from mawdo.planning.guide.sipp.optimum import dodge_spots, scenario_time_optimum

    spots = np.vstack([spots, dodge_spots(path, scenario)])
    opt = scenario_time_optimum(scenario, spots=spots)
    if not opt.reachable:
        return None, spots, f"no earliest arrival T* ({opt.reason})"
    return opt, spots, None


def _attempt(family: Family, p: dict, seed: int, index: int, attempt: int):
    """One draw: ``(Scene, None)`` or ``(None, reason)``."""
    ss = keyed_seed_sequence(seed, family.key(), index, attempt)
    rng = np.random.default_rng(ss)
    try:
        data = family.draw(rng, p)
    except Redraw as exc:
        return None, str(exc)
    spots = np.asarray(data.pop("_spots", np.zeros((0, 2))), dtype=float).reshape(-1, 2)
    data["name"] = f"{family.name}-s{seed}-{index}"
    data["seed"] = int(ss.generate_state(1, np.uint64)[0] >> np.uint64(1))
    try:
        scenario = scenario_from_dict(data, source=data["name"])
    except ScenarioError as exc:
        return None, "invalid draft: " + "; ".join(m for _, m in exc.errors[:2])
    problems = endpoint_problems(scenario, p["clearance"])
    if problems:
        return None, problems[0]
    opt = scenario_optimum(scenario)
    if not opt.reachable:
        return None, f"no static route ({opt.reason})"
    timed = None
    if family.timed:
        timed, spots, reason = _time_optimum(scenario, spots, opt.path)
        if timed is None:
            return None, reason
    t_star = None if timed is None else timed.t_star
    # only the description (and a timed family's spots, free at the robot radius by their
    # construction) change: the validated spec is copied, not validated again
    update = {"description": _describe(family, p, seed, index, opt.length, t_star)}
    if timed is not None and len(spots):
        update["spots"] = [(float(x), float(y)) for x, y in spots]
    scenario = replace(scenario, spec=scenario.spec.model_copy(update=update))
    route = None if timed is None else timed.route
    scene = Scene(
        family.name, seed, index, p, scenario, opt.length, opt.path, attempt + 1,
        t_star, spots, route,
    )  # fmt: skip
    return scene, None


def build_scene(family: Family, p: dict, seed: int, index: int) -> Scene:
    """Draw until valid (at most ``MAX_ATTEMPTS``); :class:`SceneRejected` otherwise."""
    reasons = []
    for attempt in range(MAX_ATTEMPTS):
        scene, reason = _attempt(family, p, seed, index, attempt)
        if scene is not None:
            return scene
        reasons.append(reason)
    raise SceneRejected(family.name, seed, index, reasons)
