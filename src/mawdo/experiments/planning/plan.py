"""Plan of the path-planning study (paper Table 6): algorithms x runs on a scenario.

A :class:`StudyPlan` is a :class:`~mawdo.experiments.protocol.Study` of kind ``planning``; its
tasks are computed by :func:`~mawdo.experiments.planning.execute.execute_planning_task` through
the same runner and store as every other kind (resume, local pool, Dask).

Seeding: run ``k`` of every algorithm plans with the seed
``seed_word([seed, name_word(scenario), k])`` (:mod:`mawdo.streams`), so all algorithms face
the same seeds (common random seeds) and a run does not depend on its batch.
"""

from __future__ import annotations

from typing import Annotated, Any, ClassVar, Literal

from pydantic import Field, PositiveInt, field_validator

from mawdo.experiments.plans import PlanError, StudyPlanBase
from mawdo.experiments.protocol import Task
from mawdo.optimizers import OPTIMIZERS, PAPER_ALGORITHMS
from mawdo.streams import name_word, seed_word

PAPER_SEED = 20251125
"""Master seed of the paper presets (the paper's arXiv submission date; as the benchmark's)."""

STUDY_SCHEMA = 1
BASELINE = "oracle_follower"

VARIANTS: dict[str, tuple[str, dict[str, Any]]] = {
    "mawdo_literal": ("mawdo", {"low_dim": 3}),
}
"""Study labels that run a registered optimizer with fixed options: ``label -> (optimizer,
options)``. ``mawdo_literal`` is MAWDO with the paper's low-dimensional threshold (D <= 3, so
the stabilisation is off at the planner's D = 40), beside the planner's default MAWDO, which has
it on (``docs/deviations.md#d-planning-low-dim``)."""


def _check_algorithm(name: str) -> str:
    if name.lower() in (BASELINE, *VARIANTS):
        return name.lower()
    try:
        return OPTIMIZERS[name].name
    except KeyError as exc:
        raise ValueError(str(exc.args[0])) from None


def _check_scenario(name: str) -> str:
    from mawdo.planning import get_scenario

    try:
        return get_scenario(name).name
    except (KeyError, ValueError, FileNotFoundError) as exc:
        raise ValueError(str(exc.args[0]) if exc.args else str(exc)) from None


class StudyPlan(StudyPlanBase):
    """A planning study.

    Parameters
    ----------
    name : str
        Label for reports.
    algorithms : sequence of str
        Registered optimizers, study variants (:data:`VARIANTS`, e.g. ``"mawdo_literal"``) and
        optionally ``"oracle_follower"`` (the deterministic baseline: one run, whatever ``runs``
        says).
    scenario : str
        A built-in scenario name or a scenario file path.
    runs : int
        Runs per algorithm (the paper: 50).
    planner : {"study", "realtime", "paper", "quick"}
        Planner preset (:data:`mawdo.planning.planner.PRESETS`).
    overrides : dict
        Fields of :class:`~mawdo.planning.planner.PlannerConfig` to change.
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

    @field_validator("scenario")
    @classmethod
    def _scen(cls, name):
        return _check_scenario(name)

    @field_validator("overrides")
    @classmethod
    def _over(cls, overrides):
        from dataclasses import replace

        from mawdo.planning.planner import PRESETS

        try:
            replace(PRESETS["study"], **overrides)
        except (TypeError, ValueError) as exc:
            raise ValueError(f"overrides: {exc}") from None
        return dict(overrides)

    # ---------------------------------------------------------------- identity
    def numbers_spec(self) -> dict[str, Any]:
        """Every field but ``name`` and ``batch_size``, plus the study schema."""
        return {**super().numbers_spec(), "schema": STUDY_SCHEMA}

    def run_seed(self, run: int) -> int:
        """Seed of run ``run`` (the same for every algorithm)."""
        return seed_word([self.seed, name_word(self.scenario), run])

    # ---------------------------------------------------------------- work
    def runs_of(self, algorithm: str) -> int:
        return 1 if algorithm == BASELINE else self.runs

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
        optimizer, options = VARIANTS.get(task.algorithm, (task.algorithm, {}))
        overrides = dict(self.overrides)
        if options:  # a variant's options win over the plan's for the options it names
            overrides["options"] = {**overrides.get("options", {}), **options}
        return {
            "kind": self.kind,
            **task.key(),
            "optimizer": optimizer,
            "seeds": [self.run_seed(k) for k in task.runs],
            "planner": self.planner,
            "overrides": overrides,
            "snapshots": self.snapshots,
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
