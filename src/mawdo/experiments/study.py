"""The path-planning study (paper Table 6): algorithms x runs on a scenario, through the same
runner and store as the benchmark sweeps (resume, local pool, Dask).

A :class:`StudyPlan` offers the interface :func:`~mawdo.experiments.runner.run_plan` and
:class:`~mawdo.experiments.store.Store` use (``tasks``, ``task_spec``, ``plan_hash`` ...); its
task specs carry ``kind="planning"`` and :func:`execute_study_task` computes them. Each stored
run keeps its metrics (JSON) and its executed route and replans (``.npz`` bytes), so the report
draws every figure from the store without planning again.
"""

from __future__ import annotations

import hashlib
import json
import os
import socket
import time
import traceback
import zlib
from typing import Annotated, Any, Literal

import numpy as np
from pydantic import BaseModel, ConfigDict, Field, PositiveInt, ValidationError, field_validator

from mawdo.experiments.plan import PAPER_SEED, PlanError, Task, format_errors
from mawdo.optimizers import OPTIMIZERS, PAPER_ALGORITHMS

STUDY_SCHEMA = 1
BASELINE = "oracle_follower"


def _check_algorithm(name: str) -> str:
    if name.lower() == BASELINE:
        return BASELINE
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


class StudyPlan(BaseModel):
    """A planning study.

    Parameters
    ----------
    name : str
        Label for reports.
    algorithms : sequence of str
        Registered optimizers, and optionally ``"oracle_follower"`` (the deterministic baseline:
        one run, whatever ``runs`` says).
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

    model_config = ConfigDict(frozen=True, extra="forbid")

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
    shifted: Literal[False] = False  # the store's key has a shifted flag; studies never shift

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

    # ---------------------------------------------------------------- construction
    @classmethod
    def from_dict(cls, data) -> StudyPlan:
        try:
            return cls.model_validate(dict(data))
        except ValidationError as exc:
            raise PlanError(format_errors(exc, cls)) from None

    @classmethod
    def from_json(cls, text: str) -> StudyPlan:
        return cls.from_dict(json.loads(text))

    def with_overrides(self, **changes) -> StudyPlan:
        changes = {k: v for k, v in changes.items() if v is not None}
        return self if not changes else type(self).from_dict({**self.model_dump(), **changes})

    # ---------------------------------------------------------------- identity
    def numbers_spec(self) -> dict[str, Any]:
        d = self.model_dump(mode="json")
        d.pop("name")
        d.pop("batch_size")
        d["schema"] = STUDY_SCHEMA
        return d

    @property
    def plan_hash(self) -> str:
        blob = json.dumps(self.numbers_spec(), sort_keys=True, separators=(",", ":"))
        return hashlib.sha256(blob.encode()).hexdigest()

    def to_json(self) -> str:
        return json.dumps(self.model_dump(mode="json"), sort_keys=True)

    def run_seed(self, run: int) -> int:
        """Seed of run ``run`` (the same for every algorithm)."""
        ss = np.random.SeedSequence([self.seed, zlib.crc32(self.scenario.encode()), run])
        return int(ss.generate_state(1, dtype=np.uint32)[0])

    # ---------------------------------------------------------------- work
    def runs_of(self, algorithm: str) -> int:
        return 1 if algorithm == BASELINE else self.runs

    @property
    def total_runs(self) -> int:
        return sum(self.runs_of(a) for a in self.algorithms)

    @property
    def functions(self) -> tuple[str, ...]:
        return (self.scenario,)

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
        return {
            "kind": "planning",
            "algorithm": task.algorithm,
            "function": task.function,
            "first_run": task.first_run,
            "n_runs": task.n_runs,
            "seeds": [self.run_seed(k) for k in task.runs],
            "planner": self.planner,
            "overrides": dict(self.overrides),
            "snapshots": self.snapshots,
        }

    def describe(self) -> str:
        return (
            f"{self.name}: {len(self.algorithms)} algorithms x {self.runs} runs on "
            f"'{self.scenario}', planner preset {self.planner!r}, seed {self.seed}"
        )


def execute_study_task(spec: dict[str, Any]) -> dict[str, Any]:
    """Plan ``n_runs`` runs of one algorithm; rows carry metrics and the serialised run."""
    from mawdo.experiments.store import library_version
    from mawdo.planning import get_scenario
    from mawdo.planning.metrics import run_metrics, static_optimum
    from mawdo.planning.planner import follow_oracle, plan, result_to_bytes

    t0 = time.perf_counter()
    rows = []
    sc = get_scenario(spec["function"])
    l_star = static_optimum(sc)
    for i, seed in enumerate(spec["seeds"]):
        run = spec["first_run"] + i
        t1 = time.perf_counter()
        try:
            if spec["algorithm"] == BASELINE:
                res = follow_oracle(sc)
            else:
                res = plan(
                    sc,
                    algorithm=spec["algorithm"],
                    seed=seed,
                    config=spec["planner"],
                    **spec["overrides"],
                )
            m = run_metrics(res, l_star=l_star, snapshots=spec["snapshots"])
            rows.append(
                {
                    "run": run,
                    "fun": m["length_px"],
                    "f_star": l_star,
                    "error": m["length_px"] - l_star,
                    "nfev": int(m["nfev"]),
                    "nit": int(m["steps"]),
                    "status": 0 if m["success"] else 1,
                    "wall_time": time.perf_counter() - t1,
                    "params": {"planner": spec["planner"], **spec["overrides"]},
                    "curve": res.replans[0].history if res.replans else np.zeros(0),
                    "curve_nfev": np.zeros(
                        len(res.replans[0].history) if res.replans else 0, dtype=np.int64
                    ),
                    "metrics": m,
                    "payload": result_to_bytes(res),
                    "seed_entropy": [seed],
                    "shift_seed": None,
                    "error_text": None,
                }
            )
        except Exception as exc:  # noqa: BLE001 - a failing run is a row, not a dead study
            rows.append(
                {
                    "run": run,
                    "params": {"planner": spec["planner"]},
                    "wall_time": time.perf_counter() - t1,
                    "seed_entropy": [seed],
                    "shift_seed": None,
                    "error_text": "".join(traceback.format_exception_only(exc)).strip(),
                }
            )
    return {
        "task": {k: spec[k] for k in ("algorithm", "function", "first_run", "n_runs")},
        "rows": rows,
        "wall": time.perf_counter() - t0,
        "worker": f"{socket.gethostname()}:{os.getpid()}",
        "library_version": library_version(),
    }


STUDY_PRESETS: dict[str, dict[str, Any]] = {
    "paper-table6": {
        "name": "paper-table6",
        "algorithms": [*PAPER_ALGORITHMS, BASELINE],
        "scenario": "paper",
        "runs": 50,
        "planner": "study",
    },
    "study-quick": {
        "name": "study-quick",
        "algorithms": [*PAPER_ALGORITHMS, BASELINE],
        "scenario": "paper",
        "runs": 5,
        "planner": "realtime",
        "snapshots": 4,
    },
    "study-smoke": {
        "name": "study-smoke",
        "algorithms": ["gwo", "mawdo", BASELINE],
        "scenario": "paper",
        "runs": 2,
        "planner": "quick",
        "snapshots": 2,
        "overrides": {"max_steps": 25},
    },
}


def study_preset(name: str) -> StudyPlan:
    if name not in STUDY_PRESETS:
        raise PlanError(
            f"preset: unknown study preset {name!r}; presets: {', '.join(STUDY_PRESETS)}"
        )
    return StudyPlan.from_dict(STUDY_PRESETS[name])


def plan_from_json(text: str):
    """The plan stored in a results store, whichever kind it is."""
    from mawdo.experiments.plan import ExperimentPlan

    data = json.loads(text)
    if data.get("kind") == "planning":
        return StudyPlan.from_dict(data)
    return ExperimentPlan.from_dict(data)
