"""Plan of the path-planning study (paper Table 6): algorithms x runs on a scenario.

A :class:`StudyPlan` is a :class:`~mawdo.experiments.protocol.Study` of kind ``planning``; its
tasks are computed by
:func:`~mawdo.experiments.kinds.planning.execute.execute_planning_task` through the same runner
and store as every other kind (resume, local pool, Dask).

Seeding: run ``k`` of every algorithm plans with the seed
``seed_word([seed, name_word(scenario), k])`` (:mod:`mawdo.streams`), so all algorithms face
the same seeds (common random seeds) and a run does not depend on its batch.
"""

from __future__ import annotations

import hashlib
import json
from pathlib import Path
from typing import Annotated, Any, ClassVar, Literal

from pydantic import Field, PositiveInt, ValidationInfo, field_validator, model_validator

from mawdo.experiments.plans import PlanError, StudyPlanBase
from mawdo.experiments.protocol import Task
from mawdo.optimizers import PAPER_ALGORITHMS
from mawdo.streams import name_word, seed_word

PAPER_SEED = 20251125
"""Master seed of the paper presets (the paper's arXiv submission date; as the benchmark's)."""

STUDY_SCHEMA = 2
"""2: the scenario's contents are part of the plan (and its hash), not its name."""
BASELINE = "oracle_follower"


def _check_algorithm(name: str) -> str:
    """A registered planner's name (:data:`~mawdo.planning.run.planners.PLANNERS`)."""
    from mawdo.planning.run.planners import PLANNERS

    try:
        return PLANNERS[name].name
    except KeyError as exc:
        raise ValueError(str(exc.args[0])) from None


def _scenario_sha256(contents: dict[str, Any]) -> str:
    blob = json.dumps(contents, sort_keys=True, separators=(",", ":"))
    return hashlib.sha256(blob.encode("utf-8")).hexdigest()


def _resolve_scenario(data: dict[str, Any], stored: bool) -> dict[str, Any]:
    """Fill ``scenario_spec`` (validated contents) and ``scenario`` (their name) in ``data``.

    A plan keeps the scenario itself, never a name or a path to look up later: an edited copy
    of a built-in map runs as edited whatever its ``name``, and a store can never make a
    report open a file. Plans read from a store (``stored``)
    must carry their contents; nothing outside the plan is consulted.
    """
    from mawdo.planning import ScenarioError, get_scenario, load_scenario, scenario_from_dict

    contents = data.get("scenario_spec")
    try:
        if contents is not None:
            sc = scenario_from_dict(contents, source="the plan's scenario_spec")
        elif stored:
            raise ValueError(
                "the stored plan has no scenario contents (scenario_spec); stores keep their "
                "scenario inline and never refer to files or names"
            )
        else:
            ref = data.get("scenario", "paper")
            if not isinstance(ref, str | Path):
                raise ValueError(f"expected a scenario name or file, got {type(ref).__name__}")
            ref = str(ref)
            p = Path(ref)
            sc = load_scenario(p) if p.suffix.lower() in (".toml", ".json") else get_scenario(ref)
    except ScenarioError as exc:
        raise ValueError(str(exc)) from None
    except (KeyError, FileNotFoundError) as exc:
        raise ValueError(str(exc.args[0]) if exc.args else str(exc)) from None
    spec = sc.to_dict()
    sha = _scenario_sha256(spec)
    if data.get("scenario_sha256") not in (None, sha):
        raise ValueError(
            f"scenario_sha256 {str(data['scenario_sha256'])[:12]} does not match the stored "
            f"scenario contents ({sha[:12]}): the plan was edited"
        )
    return {**data, "scenario": sc.name, "scenario_spec": spec, "scenario_sha256": sha}


class StudyPlan(StudyPlanBase):
    """A planning study.

    Parameters
    ----------
    name : str
        Label for reports.
    algorithms : sequence of str
        Registered planners (:data:`~mawdo.planning.run.planners.PLANNERS`): optimizers, variants
        such as ``"mawdo_literal"``, and baselines such as ``"oracle_follower"`` (a
        deterministic planner makes one run, whatever ``runs`` says).
    scenario : str
        On input, a built-in scenario name or a scenario file path (``.toml``/``.json``); the
        plan then holds that scenario's name.
    scenario_spec : dict
        The scenario's validated contents (filled from ``scenario`` when not given). Tasks,
        reports and the plan hash use these contents, never a lookup by name.
    scenario_sha256 : str
        SHA-256 of the canonical JSON of ``scenario_spec`` (checked when given).
    runs : int
        Runs per algorithm (the paper: 50).
    planner : {"study", "realtime", "paper", "quick"}
        Planner preset (:data:`mawdo.planning.run.planner.PRESETS`).
    overrides : dict
        Fields of :class:`~mawdo.planning.run.planner.PlannerConfig` to change.
    seed : int
        Master seed; run ``k`` of every algorithm uses the same seed (common random seeds).
    snapshots : int
        Replans per run that get the per-snapshot optimality ratio (oracle calls).
    batch_size : int
        Runs per task.
    """

    study_kind: ClassVar[str] = "planning"
    kind: Literal["planning"] = "planning"
    name: str = "study"
    algorithms: Annotated[tuple[str, ...], Field(min_length=1)]
    scenario: str = "paper"
    scenario_spec: dict[str, Any] = Field(default_factory=dict)
    scenario_sha256: str = ""
    runs: PositiveInt = 50
    planner: Literal["study", "realtime", "paper", "quick"] = "study"
    overrides: dict[str, Any] = Field(default_factory=dict)
    seed: Annotated[int, Field(strict=True, ge=0)] = PAPER_SEED
    snapshots: Annotated[int, Field(ge=0)] = 8
    batch_size: PositiveInt = 1

    @field_validator("algorithms")
    @classmethod
    def _algos(cls, names):
        out = []
        for i, n in enumerate(names):
            try:
                a = _check_algorithm(n)
            except ValueError as exc:
                raise ValueError(f"algorithms[{i}]: {exc}") from None
            if a in out:
                raise ValueError(f"algorithms[{i}]: {a!r} is listed twice")
            out.append(a)
        return tuple(out)

    @model_validator(mode="before")
    @classmethod
    def _scen(cls, data: Any, info: ValidationInfo) -> Any:
        if not isinstance(data, dict):
            return data
        stored = bool((info.context or {}).get("stored"))
        return _resolve_scenario(data, stored)

    def _adjust_overrides(self, data: dict[str, Any], changes: dict[str, Any]) -> dict[str, Any]:
        # a new scenario (name or file) replaces the contents, which are then read afresh
        if "scenario" in changes:
            data.pop("scenario_spec", None)
            data.pop("scenario_sha256", None)
        return data

    def scenario_object(self):
        """The plan's scenario, built from its stored contents (no file, no registry)."""
        from mawdo.planning import scenario_from_dict

        return scenario_from_dict(self.scenario_spec, source=f"plan {self.name!r}")

    @field_validator("overrides")
    @classmethod
    def _over(cls, overrides, info: ValidationInfo):
        from mawdo.planning.run.config import check_overrides

        # against the plan's own preset (an invalid preset is reported on its own field)
        return check_overrides(overrides, info.data.get("planner", "study"))

    # ---------------------------------------------------------------- identity
    def numbers_spec(self) -> dict[str, Any]:
        """Every field but ``name`` and ``batch_size``, plus the study schema."""
        return {**super().numbers_spec(), "schema": STUDY_SCHEMA}

    def run_seed(self, run: int) -> int:
        """Seed of run ``run`` (the same for every algorithm)."""
        return seed_word([self.seed, name_word(self.scenario), run])

    # ---------------------------------------------------------------- work
    def runs_of(self, algorithm: str) -> int:
        """``runs``, or 1 for a deterministic planner (the oracle follower)."""
        from mawdo.planning.run.planners import PLANNERS

        return self.runs if PLANNERS[algorithm].seeded else 1

    @property
    def total_runs(self) -> int:
        return sum(self.runs_of(a) for a in self.algorithms)

    def tasks(self, done=()) -> list[Task]:
        done = set(done)
        out = []
        for algo in self.algorithms:
            missing = [k for k in range(self.runs_of(algo)) if (algo, self.scenario, k) not in done]
            for i in range(0, len(missing), self.batch_size):
                chunk = missing[i : i + self.batch_size]
                # tasks are contiguous stretches so first_run + n_runs describes them
                if chunk == list(range(chunk[0], chunk[0] + len(chunk))):
                    out.append(Task(algo, self.scenario, chunk[0], len(chunk)))
                else:
                    out.extend(Task(algo, self.scenario, k, 1) for k in chunk)
        return out

    def task_spec(self, task: Task) -> dict[str, Any]:
        from mawdo.planning.run.planners import PLANNERS

        planner = PLANNERS[task.algorithm]
        options = planner.optimizer_options
        overrides = dict(self.overrides)
        if options:  # a variant's options win over the plan's for the options it names
            overrides["options"] = {**overrides.get("options", {}), **options}
        return {
            "kind": self.kind,
            **task.key(),
            "optimizer": planner.optimizer,
            "seeds": [self.run_seed(k) for k in task.runs],
            "planner": self.planner,
            "overrides": overrides,
            "snapshots": self.snapshots,
            "scenario": self.scenario_spec,
        }

    def describe(self) -> str:
        return (
            f"{self.name}: {len(self.algorithms)} algorithms x {self.runs} runs on "
            f"'{self.scenario}', planner preset {self.planner!r}, seed {self.seed}"
        )


STUDY_PRESETS: dict[str, dict[str, Any]] = {
    "paper-table6": {
        "name": "paper-table6",
        "algorithms": [*PAPER_ALGORITHMS, "mawdo_literal", BASELINE],
        "scenario": "paper",
        "runs": 50,
        "planner": "study",
    },
    "study-quick": {
        "name": "study-quick",
        "algorithms": [*PAPER_ALGORITHMS, "mawdo_literal", BASELINE],
        "scenario": "paper",
        "runs": 5,
        "planner": "realtime",
        "snapshots": 4,
    },
    "study-smoke": {
        "name": "study-smoke",
        "algorithms": ["gwo", "mawdo", "mawdo_literal", BASELINE],
        "scenario": "paper",
        "runs": 2,
        "planner": "quick",
        "snapshots": 2,
        "overrides": {"max_steps": 25},
    },
}


def study_preset(name: str) -> StudyPlan:
    """The named study preset; an unknown name raises :class:`PlanError` listing the presets."""
    if name not in STUDY_PRESETS:
        raise PlanError(
            f"preset: unknown study preset {name!r}; presets: {', '.join(STUDY_PRESETS)}"
        )
    return StudyPlan.from_dict(STUDY_PRESETS[name])
