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
from collections.abc import Iterable
from typing import Annotated, Any, ClassVar, Literal

from pydantic import Field, ValidationInfo, field_validator, model_validator

from mawdo.experiments.kinds.suite.components import component_presets, plus_component_presets
from mawdo.experiments.kinds.suite.holdout import HOLDOUT_HELP, HOLDOUT_PRESETS
from mawdo.experiments.kinds.suite.keys import parse_key, problem_key
from mawdo.experiments.kinds.suite.numbering import (
    check_numbering,
    computed_by,
    default_numbering,
    numbering_note,
)
from mawdo.experiments.kinds.suite.official import OFFICIAL_HELP, OFFICIAL_PRESETS
from mawdo.experiments.kinds.suite.variants import canonical_name, check_variants, describe_setup
from mawdo.experiments.plans import PlanError, PositiveInt, StudyPlanBase, reject_duplicates
from mawdo.experiments.protocol import Task, missing_run_tasks
from mawdo.optimizers import PAPER_ALGORITHMS, make_optimizer
from mawdo.streams import name_word
from mawdo.suites import SUITES, evaluation_budget
from mawdo.suites.base import format_dims

PLAN_SCHEMA = 1
"""Bumped when the meaning of a plan field changes; part of the plan hash."""

BBOB_SEED = 20251125
"""Master seed of the presets (the paper presets' seed)."""

KIND = "suite"
"""The kind's name (its plans' ``kind``)."""

OLD_KIND_NAMES = ("bbob",)
"""Names the kind had before (stores and plan files made then say ``kind = "bbob"``): read as
:data:`KIND`. The plan hash never held the kind, so their hashes stay valid."""


class SuitePlan(StudyPlanBase):
    """A standard black-box study on one suite (COCO protocol).

    Parameters
    ----------
    name : str
        A label for reports (does not affect numbers).
    suite : str
        Registered suite: ``"bbob"`` (ioh), ``"cec2017"`` or ``"cec2022"`` (the official
        code, batched), ``"cec2017-opfunu"`` or ``"cec2022-opfunu"``.
    variants : dict of str to str
        Labels of named variants mapped to registered optimizers (``{"mawdo-r10": "mawdo"}``):
        each label listed in ``algorithms`` runs that optimizer with ``options[label]`` and is
        stored and reported under the label (:mod:`.variants`).
    algorithms : sequence of str
        Registered optimizers (``mawdo list``), e.g. ``mawdo``, ``wdo``, ``cmaes``, ``random``,
        and variant labels.
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
        Per-algorithm (or per-variant) coefficients (``{"mawdo": {"groups": 4}}``).
    batch_size : int
        Runs per task (one vectorised batch on one worker). Does not affect numbers.
    numbering : {"official", "opfunu"} or None
        CEC suites only, set by the plan itself: ``"official"``, or ``"opfunu"`` for a plan read
        back from a store made when cec2017/cec2022 were opfunu's (:mod:`.numbering`).
    """

    study_kind: ClassVar[str] = KIND
    kind: Literal["suite"] = KIND
    name: str = "custom"
    suite: str = "bbob"
    variants: dict[str, str] = Field(default_factory=dict)  # before algorithms: they name labels
    algorithms: Annotated[tuple[str, ...], Field(min_length=1)]
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
    numbering: Literal["official", "opfunu"] | None = None

    @model_validator(mode="before")
    @classmethod
    def _old_kind_and_default_instances(cls, data: Any, info: ValidationInfo) -> Any:
        if not isinstance(data, dict):
            return data
        if data.get("kind") in OLD_KIND_NAMES:
            data = {**data, "kind": KIND}
        if data.get("numbering") is None:
            suite = str(data.get("suite", "bbob")).strip().lower()
            stored = bool(info.context and info.context.get("stored"))
            data = {**data, "numbering": default_numbering(suite, stored)}
        if data.get("instances") is None:  # the suite's own (CEC: its one; BBOB: COCO's 1-5)
            suite = SUITES.get(str(data.get("suite", "bbob")).strip().lower())
            if suite is not None:  # an unknown suite is named by the suite field's check
                data = {**data, "instances": suite.default_instances}
        return data

    @field_validator("suite")
    @classmethod
    def _check_suite(cls, suite: str) -> str:
        return SUITES[suite.strip().lower()].name

    @field_validator("numbering")
    @classmethod
    def _check_numbering(cls, numbering: str | None, info: ValidationInfo) -> str | None:
        stored = bool(info.context and info.context.get("stored"))
        check_numbering(numbering, info.data.get("suite"), stored)
        return numbering

    @field_validator("budget", mode="before")
    @classmethod
    def _check_budget(cls, budget: Any) -> float:
        # evaluation_budget holds the one wording of this check (number, finite, > 0)
        try:
            evaluation_budget(budget, 1)
        except TypeError as exc:
            raise ValueError(str(exc)) from None
        return float(budget)

    @field_validator("variants")
    @classmethod
    def _check_variants(cls, variants: dict[str, str]) -> dict[str, str]:
        return check_variants(variants)

    @field_validator("algorithms")
    @classmethod
    def _check_algorithms(cls, names: tuple, info) -> tuple[str, ...]:
        if "variants" not in info.data:
            return names  # the variants failed and are reported; their labels are unknown
        variants = info.data["variants"]
        out = []
        for i, name in enumerate(names):
            try:
                out.append(canonical_name(name, variants))
            except KeyError as exc:
                raise ValueError(f"algorithms[{i}]: {exc.args[0]}") from None
        return cls._no_duplicates(tuple(out), info)

    @field_validator("instances", "dims")
    @classmethod
    def _no_duplicates(cls, values: tuple, info) -> tuple:
        return reject_duplicates(values, info.field_name)

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
        if self.numbering == "opfunu":
            return self  # a store's plan: its functions are opfunu's ids, checked when it ran
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
        for label in self.variants:
            if label not in self.algorithms:
                raise ValueError(
                    f"variants.{label}: not one of the plan's algorithms; list it in algorithms "
                    f"(or drop the variant)"
                )
        return self

    @field_validator("options")
    @classmethod
    def _check_options(cls, options: dict[str, dict[str, Any]], info) -> dict[str, dict]:
        # Options are checked by building each optimizer once, so a typo fails at plan time;
        # keys become canonical names, so an option is never silently ignored.
        variants, algorithms = info.data.get("variants", {}), info.data.get("algorithms")
        pop_size = info.data.get("pop_size")
        out: dict[str, dict[str, Any]] = {}
        for key, opts in options.items():
            try:
                name = canonical_name(key, variants)
            except KeyError as exc:
                raise ValueError(f"options.{key}: {exc.args[0]}") from None
            if algorithms is not None and name not in algorithms:
                raise ValueError(
                    f"options.{key}: {name!r} is not one of the plan's algorithms "
                    f"({', '.join(algorithms)})"
                )
            if "pop_size" in opts:
                raise ValueError(f"options.{key}.pop_size: use the plan's pop_size field")
            extra = {} if pop_size is None else {"pop_size": pop_size}
            try:
                make_optimizer(variants.get(name, name), **extra, **opts)
            except (TypeError, ValueError) as exc:
                raise ValueError(f"options.{key}: {exc}") from None
            out[name] = {**out.get(name, {}), **opts}
        return out

    def _adjust_overrides(self, data: dict[str, Any], changes: dict[str, Any]) -> dict[str, Any]:
        if isinstance(changes.get("algorithms"), list | tuple):
            keep = {str(a).lower() for a in changes["algorithms"]}
            for field in ("options", "variants"):
                if field not in changes:
                    data[field] = {k: v for k, v in data[field].items() if k in keep}
        return data

    @classmethod
    def preset(cls, name: str) -> SuitePlan:
        """The named preset (``preset = "bbob-quick"`` in a plan file)."""
        return preset_plan(name)

    def setup(self, algorithm: str) -> str:
        """What runs under ``algorithm``: ``"mawdo (restart_every=10)"``."""
        return describe_setup(algorithm, self.variants, self.options)

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
            # only when used, so the plans (and stores) from before variants keep their hash
            **({"variants": dict(sorted(self.variants.items()))} if self.variants else {}),
            # new CEC plans only: a store of opfunu's cec2017 keeps its hash, and a new plan
            # with the same fields gets another (its function ids mean other functions)
            **({"numbering": "official"} if self.numbering == "official" else {}),
        }

    def computed_by(self, fid: int) -> tuple[str, int]:
        """The registered suite and function id that compute the plan's function ``fid``
        (a store of opfunu's numbering: ``cec2017-opfunu`` and the official id)."""
        return computed_by(self.suite, self.numbering, fid)

    def numbering_note(self) -> str:
        """How the plan's function ids relate to the official ones ("" for official ids)."""
        return numbering_note(self.suite, self.numbering)

    def check_libraries(self) -> None:
        """Import the suite's library and read the data of every problem now (before any worker
        starts); raises :class:`~mawdo.suites.MissingExtraError` naming the ``pip install``
        that fixes a missing library, :class:`ValueError` naming a missing or damaged file."""
        if self.numbering == "opfunu":
            raise ValueError(self.numbering_note() + " Run the official suite into a new store.")
        SUITES[self.suite].check_problems(self.functions, self.dims)

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
        suite, fid = self.computed_by(fid)
        opts = dict(self.options.get(task.algorithm, {}))
        if self.pop_size is not None:
            opts["pop_size"] = self.pop_size
        return {
            "kind": self.kind,
            **task.key(),
            "optimizer": self.variants.get(task.algorithm, task.algorithm),
            "suite": suite,
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
    **HOLDOUT_PRESETS,
    **OFFICIAL_PRESETS,
}
"""Named BBOB plans (``mawdo bench run --preset bbob-quick``)."""

PRESET_HELP = {
    "bbob-quick": "BBOB f1-f24, instances 1-5, D 5 and 20, 1e3 x D evaluations, 2 runs per "
    "instance: MAWDO, WDO, GWO, WOA, CMA-ES, random",
    "bbob-full": "the full protocol: BBOB f1-f24, instances 1-5, D 5 and 20, 1e4 x D "
    "evaluations, 5 runs per instance, the paper's six algorithms + CMA-ES + random",
    **HOLDOUT_HELP,
    **OFFICIAL_HELP,
}
_COMPONENTS, _COMPONENT_HELP = component_presets(BBOB_SEED)
PRESETS.update(_COMPONENTS)
PRESET_HELP.update(_COMPONENT_HELP)
_PLUS, _PLUS_HELP = plus_component_presets()
PRESETS.update(_PLUS)
PRESET_HELP.update(_PLUS_HELP)


def preset_plan(name: str) -> SuitePlan:
    """The named preset; an unknown name raises :class:`PlanError` listing the presets."""
    if name not in PRESETS:
        close = difflib.get_close_matches(name, list(PRESETS), n=1)
        hint = f" Did you mean {close[0]!r}?" if close else ""
        raise PlanError(f"preset: unknown preset {name!r}.{hint} Presets: {', '.join(PRESETS)}")
    return SuitePlan.from_dict(PRESETS[name])
