"""Plan of the planning arena: scene families x planners x scenes.

An :class:`ArenaPlan` is a :class:`~mawdo.experiments.protocol.Study` of kind ``arena``. Its
problems are scene families and its run ``k`` of a family is scene ``k`` of that family,
generated on the worker by :func:`mawdo.planning.scenes.generate_scene` from
``(family, params, seed, k)``; so the harness's ``(algorithm, problem, run)`` key is
``(planner, family, scene index)`` and resume, pools and Dask work unchanged.

Seeding: scene ``k`` of a family is a pure function of ``(family, params, seed, k)``; every
stochastic planner plans scene ``k`` with the seed ``seed_word([seed, name_word(family), k])``
(common random seeds across planners), so no run depends on its batch or on the workers.
"""

from __future__ import annotations

import difflib
from typing import Annotated, Any, ClassVar, Literal

from pydantic import Field, ValidationInfo, field_validator, model_validator

from mawdo.experiments.plans import PlanError, StudyPlanBase
from mawdo.experiments.protocol import Task, missing_run_tasks
from mawdo.streams import name_word, seed_word

ARENA_SCHEMA = 1
ORACLE = "oracle_follower"
BASELINE_ALIASES = {"oracle": ORACLE}


def _unknown(what: str, name: str, known) -> ValueError:
    close = difflib.get_close_matches(name, list(known), n=3, cutoff=0.5)
    hint = f" Did you mean {', '.join(map(repr, close))}?" if close else ""
    return ValueError(f"unknown {what} {name!r}.{hint} Known: {', '.join(known)}.")


def check_family(name: str) -> str:
    """A registered scene family's name; ``ValueError`` with close names otherwise."""
    from mawdo.planning.scenes import FAMILIES

    key = str(name).strip().lower()
    if key not in FAMILIES:
        raise _unknown("scene family", str(name), FAMILIES)
    return key


def check_baseline(name: str) -> str:
    """A baseline's canonical name: a registered planner not driven by an optimizer
    (:data:`~mawdo.planning.run.planners.PLANNERS`; ``oracle`` is the oracle follower)."""
    from mawdo.planning.run.planners import PLANNERS

    key = str(name).strip().lower()
    key = BASELINE_ALIASES.get(key, key)
    if key not in PLANNERS or PLANNERS[key].optimizer is not None:
        known = [n for n in PLANNERS if PLANNERS[n].optimizer is None]
        raise _unknown("baseline", str(name), ["oracle", *(n for n in known if n != ORACLE)])
    return PLANNERS[key].name


def _unique(names, check, field: str) -> tuple[str, ...]:
    out: list[str] = []
    for i, n in enumerate(names):
        try:
            c = check(n)
        except (ValueError, KeyError) as exc:
            msg = exc.args[0] if exc.args else str(exc)
            raise ValueError(f"{field}[{i}]: {msg}") from None
        if c in out:
            raise ValueError(f"{field}[{i}]: {c!r} is listed twice")
        out.append(c)
    return tuple(out)


def _check_algorithm(name: str) -> str:
    """A planner driven by an optimizer (a registered optimizer or a variant such as
    ``mawdo_literal``); ``KeyError`` with close names otherwise."""
    from mawdo.planning.run.planners import PLANNERS

    spec = PLANNERS[str(name).strip()]
    if spec.optimizer is None:
        raise ValueError(f"{spec.name!r} is a baseline: list it under baselines")
    return spec.name


class ArenaPlan(StudyPlanBase):
    """A planning arena: ``n`` generated scenes per family, each planned by every planner.

    Parameters
    ----------
    name : str
        Label for reports.
    families : sequence of str
        Registered scene families (:data:`mawdo.planning.scenes.FAMILIES`).
    n : int
        Scenes per family, >= 1.
    algorithms : sequence of str
        Planners driven by an optimizer (:data:`~mawdo.planning.run.planners.PLANNERS`: any
        registered optimizer, ``mawdo_literal``); may be empty if baselines are given.
    baselines : sequence of str
        The other planners: ``oracle`` (the oracle follower), ``straight``, ``rrtstar``,
        ``bitstar``, ``prmstar``, or any registered later.
    params : dict family -> dict
        Family parameters overriding the defaults (checked against their ranges).
    seed : int
        Master seed (scenes and planner seeds), >= 0.
    planner : {"realtime", "large", "study", "paper", "quick"}
        Planner preset (:data:`mawdo.planning.run.config.PRESETS`).
    overrides : dict
        Fields of :class:`~mawdo.planning.run.config.PlannerConfig` to change.
    ompl_time : float
        Time budget of each OMPL solve (seconds, (0, 60]).
    ompl_resolution : float
        OMPL motion-checking resolution (pixels, (0, 10]).
    batch_size : int
        Scenes per task.
    """

    study_kind: ClassVar[str] = "arena"
    kind: Literal["arena"] = "arena"
    name: str = "arena"
    families: Annotated[tuple[str, ...], Field(min_length=1)]
    n: Annotated[int, Field(ge=1)] = 50
    algorithms: tuple[str, ...] = ("mawdo",)
    baselines: tuple[str, ...] = (ORACLE, "straight")
    params: dict[str, dict[str, Any]] = Field(default_factory=dict)
    seed: Annotated[int, Field(strict=True, ge=0)] = 0
    planner: Literal["realtime", "large", "study", "paper", "quick"] = "realtime"
    overrides: dict[str, Any] = Field(default_factory=dict)
    ompl_time: Annotated[float, Field(gt=0, le=60)] = 0.5
    ompl_resolution: Annotated[float, Field(gt=0, le=10)] = 0.5
    batch_size: Annotated[int, Field(ge=1)] = 5

    @field_validator("families")
    @classmethod
    def _fams(cls, names):
        return _unique(names, check_family, "families")

    @field_validator("algorithms")
    @classmethod
    def _algos(cls, names):
        return _unique(names, _check_algorithm, "algorithms")

    @field_validator("baselines")
    @classmethod
    def _bases(cls, names):
        return _unique(names, check_baseline, "baselines")

    @field_validator("overrides")
    @classmethod
    def _over(cls, overrides, info: ValidationInfo):
        from mawdo.planning.run.config import check_overrides

        # against the plan's own preset (an invalid preset is reported on its own field)
        return check_overrides(overrides, info.data.get("planner", "realtime"))

    @model_validator(mode="after")
    def _params_and_planners(self):
        from mawdo.planning.scenes import FAMILIES

        for fam, p in self.params.items():
            if fam not in self.families:
                raise ValueError(
                    f"params: {fam!r} is not one of the plan's families "
                    f"({', '.join(self.families)})"
                )
            FAMILIES[fam].resolve(p)  # ValueError naming the parameter and its range
        if not self.algorithms and not self.baselines:
            raise ValueError("algorithms, baselines: give at least one planner")
        return self

    # ---------------------------------------------------------------- identity
    def numbers_spec(self) -> dict[str, Any]:
        """Every field but ``name`` and ``batch_size``, plus the arena schema."""
        return {**super().numbers_spec(), "schema": ARENA_SCHEMA}

    @property
    def planners(self) -> tuple[str, ...]:
        """Algorithms then baselines: the ``algorithm`` column of the store."""
        return (*self.algorithms, *self.baselines)

    def planner_seed(self, family: str, index: int) -> int:
        """Seed every stochastic planner uses on scene ``index`` of ``family``."""
        return seed_word([self.seed, name_word(family), index])

    # ---------------------------------------------------------------- work
    @property
    def total_runs(self) -> int:
        return len(self.planners) * len(self.families) * self.n

    def tasks(self, done=()) -> list[Task]:
        done = set(done)
        out = []
        for fam in self.families:
            for p in self.planners:
                out += missing_run_tasks(p, fam, self.n, done, self.batch_size)
        return out

    def task_spec(self, task: Task) -> dict[str, Any]:
        fam = task.problem
        return {
            "kind": self.kind,
            **task.key(),
            "seed": self.seed,
            "params": dict(self.params.get(fam, {})),
            "planner_seeds": [self.planner_seed(fam, k) for k in task.runs],
            "preset": self.planner,
            "overrides": dict(self.overrides),
            # each planner takes those of its options it knows (PlannerSpec.options)
            "planner_options": {"time_limit": self.ompl_time, "resolution": self.ompl_resolution},
        }

    def describe(self) -> str:
        return (
            f"{self.name}: {len(self.families)} families ({', '.join(self.families)}) x "
            f"{self.n} scenes x {len(self.planners)} planners ({', '.join(self.planners)}), "
            f"planner preset {self.planner!r}, seed {self.seed}"
        )


# six families decided by the static topology: clutter, walls with doors, a long detour, a
# trap, and two of moving traffic; then six decided by time, each scene with an
# earliest arrival T*: oncoming traffic with bays, a patrolled door, a faster chaser, a crowd,
# a mover parked in the only corridor, gaps barely wider than the robot
STATIC_FAMILIES = ("forest", "rooms", "maze", "u_trap", "crossing", "dense")
TIMED_FAMILIES = ("corridor", "doorway", "chaser", "crowd", "parked", "slalom")
DEFAULT_FAMILIES = STATIC_FAMILIES + TIMED_FAMILIES
# worlds at scale (1000 px, 200 movers by default; T* stored): an open crowd and a warehouse
LARGE_FAMILIES = ("crowd-large", "warehouse-large")

ARENA_PRESETS: dict[str, dict[str, Any]] = {
    "arena-default": {
        "name": "arena-default",
        "families": list(DEFAULT_FAMILIES),
        "n": 50,
        "algorithms": ["mawdo", "woa", "gwo"],
        # guide_only: the same planner with the optimizer switched off (the swarm's share)
        "baselines": ["guide_only", ORACLE, "straight", "bitstar"],
        "planner": "realtime",
    },
    "arena-quick": {
        "name": "arena-quick",
        "families": ["forest", "u_trap", "crossing"],
        "n": 3,
        "algorithms": ["mawdo"],
        "baselines": [ORACLE, "straight"],
        "planner": "quick",
        "overrides": {"max_steps": 150},
        "batch_size": 1,
    },
    # the planner for large worlds (it trusts the predictions 180 steps ahead): a few
    # scenes, the swarm (mawdo) against the same planner with its optimizer off (guide_only),
    # and the straight line as the floor
    "arena-large": {
        "name": "arena-large",
        "families": list(LARGE_FAMILIES),
        "n": 3,
        "algorithms": ["mawdo"],
        "baselines": ["guide_only", "straight"],
        "planner": "large",
        "batch_size": 1,
    },
}


def arena_preset(name: str) -> ArenaPlan:
    """The named arena preset; an unknown name raises :class:`PlanError` listing the presets."""
    if name not in ARENA_PRESETS:
        close = difflib.get_close_matches(name, list(ARENA_PRESETS), n=2)
        hint = f" Did you mean {', '.join(map(repr, close))}?" if close else ""
        raise PlanError(
            f"preset: unknown arena preset {name!r}.{hint} Presets: {', '.join(ARENA_PRESETS)}"
        )
    return ArenaPlan.from_dict(ARENA_PRESETS[name])
