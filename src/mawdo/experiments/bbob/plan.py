"""Plans of the standard black-box study: algorithms x (function, instance, dimension) x runs.

One plan covers one registered suite (``bbob``, ``cec2017``, ``cec2022``): the grid of its
functions, instances and dimensions is the list of *problems*; each algorithm makes ``runs``
runs on each problem (COCO counts runs per instance), under a budget in evaluations per
dimension (COCO's convention: ``budget = 1e4`` gives ``1e4 * D`` evaluations per run).

Seeding
-------
Run ``k`` of problem ``p`` (``"f03_i02_d20"``) uses the ``k``-th child of
``SeedSequence([seed, crc32(suite), crc32(p)])``, whatever the algorithm, the batch or the
worker; so a store's numbers depend on the plan's numbers spec only.
"""

from __future__ import annotations

import difflib
import re
from collections.abc import Iterable
from typing import Annotated, Any, ClassVar, Literal

from pydantic import AfterValidator, Field, field_validator, model_validator

from mawdo.experiments.plans import PlanError, StudyPlanBase
from mawdo.experiments.protocol import Task, missing_run_tasks
from mawdo.optimizers import OPTIMIZERS, PAPER_ALGORITHMS, make_optimizer
from mawdo.streams import name_word
from mawdo.suites import SUITES, evaluation_budget
from mawdo.suites.base import format_dims, require

PLAN_SCHEMA = 1
"""Bumped when the meaning of a plan field changes; part of the plan hash."""

BBOB_SEED = 20251125
"""Master seed of the presets (the paper presets' seed)."""

LIBRARY = {
    "bbob": "ioh",
    "cec2017": "opfunu.cec_based.cec2017",
    "cec2022": "opfunu.cec_based.cec2022",
}


def _check_algorithm(name: str) -> str:
    return OPTIMIZERS[name].name


AlgorithmName = Annotated[str, AfterValidator(_check_algorithm)]
PositiveInt = Annotated[int, Field(strict=True, ge=1)]


def problem_key(fid: int, iid: int, dim: int) -> str:
    """The canonical name of one problem: ``"f03_i02_d20"`` (sorts by function, then instance)."""
    return f"f{fid:02d}_i{iid:02d}_d{dim:02d}"


def parse_key(key: str) -> tuple[int, int, int]:
    """``"f03_i02_d20"`` -> ``(3, 2, 20)``."""
    m = re.fullmatch(r"f(\d+)_i(\d+)_d(\d+)", key)
    if m is None:
        raise ValueError(f"{key!r} is not a problem key of the form f03_i02_d20")
    return int(m[1]), int(m[2]), int(m[3])


def parse_ids(text: str, what: str = "ids") -> list[int | str]:
    """Command-line id lists: ``"1-24"``, ``"1,3,5-7"``; non-numeric items stay names.

    Raises
    ------
    ValueError
        An empty list or a reversed range, naming ``what``.
    """
    out: list[int | str] = []
    for item in (t.strip() for t in str(text).split(",")):
        if not item:
            continue
        m = re.fullmatch(r"(\d+)\s*-\s*(\d+)", item)
        if m:
            lo, hi = int(m[1]), int(m[2])
            if lo > hi:
                raise ValueError(f"{what}: range {item!r} runs backwards; write {hi}-{lo}")
            out.extend(range(lo, hi + 1))
        elif item.isdigit():
            out.append(int(item))
        else:
            out.append(item)
    if not out:
        raise ValueError(f"{what}: give at least one (e.g. 1-24 or 1,3,5)")
    return out


class SuitePlan(StudyPlanBase):
    """A standard black-box study on one suite (COCO protocol).

    Parameters
    ----------
    name : str
        A label for reports (does not affect numbers).
    suite : str
        Registered suite: ``"bbob"`` (ioh), ``"cec2017"`` or ``"cec2022"`` (opfunu).
    algorithms : sequence of str
        Registered optimizers (``mawdo list``), e.g. ``mawdo``, ``wdo``, ``cmaes``, ``random``.
    functions : sequence of int or str
        Function ids of the suite (``3``, ``"f3"``) or its library's names (``"Rastrigin"``);
        stored as ids.
    instances : sequence of int
        Instances, >= 1 (default: 1-5 for BBOB; CEC suites define only instance 1, the default).
    dims : sequence of int
        Dimensions D (BBOB 2-40; CEC: those the suite has data for, see ``mawdo.suites``).
    budget : float
        Evaluations per dimension per run, > 0; a run gets exactly ``ceil(budget * D)``
        evaluations (MAWDO's opposition-based evaluations count).
    runs : int
        Runs per (algorithm, function, instance, dimension), >= 1.
    final_target : float or None
        Precision ``f - f_opt`` at which a run stops (COCO's last target 1e-8); None runs the
        whole budget.
    pop_size : int or None
        Population of every algorithm; None keeps each algorithm's default (CMA-ES:
        ``4 + floor(3 ln D)``; the WDO family: 50).
    seed : int
        Master seed, >= 0.
    options : dict of str to dict
        Per-algorithm coefficients (``{"mawdo": {"groups": 4}}``).
    batch_size : int
        Runs per task (one vectorised batch on one worker). Does not affect numbers.
    """

    study_kind: ClassVar[str] = "bbob"
    kind: Literal["bbob"] = "bbob"
    name: str = "custom"
    suite: str = "bbob"
    algorithms: Annotated[tuple[AlgorithmName, ...], Field(min_length=1)]
    functions: Annotated[tuple[int | str, ...], Field(min_length=1)]
    instances: Annotated[tuple[int, ...], Field(min_length=1)] = (1, 2, 3, 4, 5)
    dims: Annotated[tuple[int, ...], Field(min_length=1)] = (5, 20)
    budget: float = 1e4
    runs: PositiveInt = 5
    final_target: Annotated[float, Field(gt=0, allow_inf_nan=False)] | None = 1e-8
    pop_size: Annotated[int, Field(strict=True, ge=2)] | None = None
    seed: Annotated[int, Field(strict=True, ge=0)] = BBOB_SEED
    options: dict[str, dict[str, Any]] = Field(default_factory=dict)
    batch_size: PositiveInt = 5

    @model_validator(mode="before")
    @classmethod
    def _default_instances(cls, data: Any) -> Any:
        # CEC suites have one instance: their default is (1,), BBOB's COCO's 1-5.
        if isinstance(data, dict) and data.get("instances") is None:
            suite = str(data.get("suite", "bbob")).strip().lower()
            data = {**data, "instances": (1,) if suite.startswith("cec") else (1, 2, 3, 4, 5)}
        return data

    @field_validator("suite")
    @classmethod
    def _check_suite(cls, suite: str) -> str:
        return SUITES[suite.strip().lower()].name

    @field_validator("budget", mode="before")
    @classmethod
    def _check_budget(cls, budget: Any) -> float:
        # evaluation_budget holds the one wording of this check (number, finite, > 0)
        try:
            evaluation_budget(budget, 1)
        except TypeError as exc:
            raise ValueError(str(exc)) from None
        return float(budget)

    @field_validator("algorithms", "instances", "dims")
    @classmethod
    def _no_duplicates(cls, values: tuple, info) -> tuple:
        first: dict[Any, int] = {}
        for i, v in enumerate(values):
            if v in first:
                raise ValueError(
                    f"{info.field_name}[{i}]: {v!r} is listed twice (also {info.field_name}"
                    f"[{first[v]}])"
                )
            first[v] = i
        return values

    @field_validator("functions")
    @classmethod
    def _resolve_functions(cls, functions: tuple, info) -> tuple[int, ...]:
        suite = info.data.get("suite")
        if suite is None:
            return functions  # the suite failed; its error is reported
        spec = SUITES[suite]
        ids = []
        for i, f in enumerate(functions):
            try:
                ids.append(spec.function_id(f))
            except (KeyError, TypeError) as exc:
                raise ValueError(f"functions[{i}]: {str(exc).strip(chr(39))}") from None
        return tuple(cls._no_duplicates(tuple(ids), info))

    @model_validator(mode="after")
    def _check_grid(self) -> SuitePlan:
        spec = SUITES[self.suite]
        for i, iid in enumerate(self.instances):
            if iid < 1 or (spec.max_instance is not None and iid > spec.max_instance):
                top = {None: "instances >= 1", 1: "only instance 1"}.get(
                    spec.max_instance, f"instances 1-{spec.max_instance}"
                )
                raise ValueError(f"instances[{i}]: {self.suite} defines {top}; got {iid}")
        for fid in self.functions:
            allowed = spec.dims(fid)
            bad = [d for d in self.dims if d not in allowed]
            if bad:
                raise ValueError(
                    f"dims: {self.suite} f{fid} is not defined in dimension "
                    f"{', '.join(map(str, bad))}; its dimensions are {format_dims(allowed)}"
                )
        self._check_options()
        return self

    def _check_options(self) -> None:
        # Options are checked by building each optimizer once, so a typo fails at plan time.
        for key, opts in self.options.items():
            try:
                algo = OPTIMIZERS[key].name
            except KeyError as exc:
                raise ValueError(f"options.{key}: {exc}") from None
            if algo not in self.algorithms:
                raise ValueError(f"options.{key}: {algo!r} is not one of the plan's algorithms")
            if "pop_size" in opts:
                raise ValueError(f"options.{key}.pop_size: use the plan's pop_size field")
            extra = {} if self.pop_size is None else {"pop_size": self.pop_size}
            try:
                make_optimizer(algo, **extra, **opts)
            except (TypeError, ValueError) as exc:
                raise ValueError(f"options.{key}: {exc}") from None

    def _adjust_overrides(self, data: dict[str, Any], changes: dict[str, Any]) -> dict[str, Any]:
        if "algorithms" in changes and "options" not in changes:
            keep = {str(a).lower() for a in changes["algorithms"]}
            data["options"] = {k: v for k, v in data["options"].items() if k in keep}
        return data

    # ----------------------------------------------------------------------- identity
    def numbers_spec(self) -> dict[str, Any]:
        """Everything that affects stored numbers (``name`` and ``batch_size`` do not)."""
        return {
            "schema": PLAN_SCHEMA,
            "suite": self.suite,
            "algorithms": list(self.algorithms),
            "functions": list(self.functions),
            "instances": list(self.instances),
            "dims": list(self.dims),
            "budget": self.budget,
            "runs": self.runs,
            "final_target": self.final_target,
            "pop_size": self.pop_size,
            "seed": self.seed,
            "options": {k: self.options[k] for k in sorted(self.options)},
        }

    def check_libraries(self) -> None:
        """Import the suite's library now; raises :class:`~mawdo.suites.MissingExtraError`
        naming the ``pip install`` that fixes it (before any worker starts)."""
        require(LIBRARY[self.suite], self.suite)

    # ----------------------------------------------------------------------- work
    @property
    def problems(self) -> list[str]:
        """Problem keys, largest dimension first (the longest tasks start first)."""
        return [
            problem_key(f, i, d)
            for d in sorted(self.dims, reverse=True)
            for f in self.functions
            for i in self.instances
        ]

    @property
    def total_runs(self) -> int:
        return len(self.algorithms) * len(self.problems) * self.runs

    @property
    def total_evaluations(self) -> int:
        """Evaluations of the whole plan if no run stops early."""
        per = sum(evaluation_budget(self.budget, d) for d in self.dims)
        return per * len(self.algorithms) * len(self.functions) * len(self.instances) * self.runs

    def problem_seed(self, problem: str) -> list[int]:
        """Entropy of the seed sequence whose ``k``-th child seeds run ``k`` on ``problem``."""
        return [self.seed, name_word(self.suite), name_word(problem)]

    def tasks(self, done: Iterable[tuple[str, str, int]] = ()) -> list[Task]:
        """Tasks computing every run not in ``done`` (``(algorithm, problem, run)`` keys)."""
        done_set = set(done)
        out: list[Task] = []
        for prob in self.problems:
            for algo in self.algorithms:
                out += missing_run_tasks(algo, prob, self.runs, done_set, self.batch_size)
        return out

    def task_spec(self, task: Task) -> dict[str, Any]:
        """Everything a worker needs to compute ``task``, as plain picklable data."""
        fid, iid, dim = parse_key(task.problem)
        opts = dict(self.options.get(task.algorithm, {}))
        if self.pop_size is not None:
            opts["pop_size"] = self.pop_size
        return {
            "kind": self.kind,
            **task.key(),
            "suite": self.suite,
            "function_id": fid,
            "instance": iid,
            "dim": dim,
            "budget": self.budget,
            "final_target": self.final_target,
            "seed_entropy": self.problem_seed(task.problem),
            "options": opts,
        }

    def describe(self) -> str:
        """One line for logs and messages."""
        return (
            f"{self.name}: {self.suite}, {len(self.algorithms)} algorithms x "
            f"{len(self.functions)} functions x {len(self.instances)} instances x D "
            f"{','.join(map(str, self.dims))} x {self.runs} runs, budget {self.budget:g} x D "
            f"evaluations, seed {self.seed}"
        )


# --------------------------------------------------------------------------- presets
BBOB_ALGORITHMS = (*PAPER_ALGORITHMS, "cmaes", "random")

PRESETS: dict[str, dict[str, Any]] = {
    "bbob-quick": {
        "name": "bbob-quick",
        "suite": "bbob",
        "algorithms": ["mawdo", "wdo", "gwo", "woa", "cmaes", "random"],
        "functions": list(range(1, 25)),
        "instances": [1, 2, 3, 4, 5],
        "dims": [5, 20],
        "budget": 1e3,
        "runs": 2,
        "seed": BBOB_SEED,
    },
    "bbob-full": {
        "name": "bbob-full",
        "suite": "bbob",
        "algorithms": list(BBOB_ALGORITHMS),
        "functions": list(range(1, 25)),
        "instances": [1, 2, 3, 4, 5],
        "dims": [5, 20],
        "budget": 1e4,
        "runs": 5,
        "seed": BBOB_SEED,
    },
}
"""Named BBOB plans (``mawdo bench run --preset bbob-quick``)."""

PRESET_HELP = {
    "bbob-quick": "BBOB f1-f24, instances 1-5, D 5 and 20, 1e3 x D evaluations, 2 runs per "
    "instance: MAWDO, WDO, GWO, WOA, CMA-ES, random",
    "bbob-full": "issue 13's protocol: BBOB f1-f24, instances 1-5, D 5 and 20, 1e4 x D "
    "evaluations, 5 runs per instance, the paper's six algorithms + CMA-ES + random",
}


def preset_plan(name: str) -> SuitePlan:
    """The named preset; an unknown name raises :class:`PlanError` listing the presets."""
    if name not in PRESETS:
        close = difflib.get_close_matches(name, list(PRESETS), n=1)
        hint = f" Did you mean {close[0]!r}?" if close else ""
        raise PlanError(f"preset: unknown preset {name!r}.{hint} Presets: {', '.join(PRESETS)}")
    return SuitePlan.from_dict(PRESETS[name])
