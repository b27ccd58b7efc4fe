"""Experiment plans: which algorithms, functions, runs and budgets a sweep covers.

The paper's protocol and our readings of it: ``docs/deviations.md#d-protocol``.

A plan is data. It is validated once, with messages that name the offending field
(``runs: must be >= 1``, ``algorithms[2]: unknown algorithm 'mawod'. Did you mean 'mawdo'?``),
and cut into :class:`Task` objects, the unit of work a runner hands to a worker.

Seeding
-------
Run ``k`` of function ``f`` uses run ``k`` of the seed sequence
``SeedSequence([seed, crc32(f)])``, whatever the algorithm. Every algorithm therefore sees the
same per-run seeds on a function, and each function has its own independent streams. This is
not a claim of common random numbers (algorithms consume their streams differently), only a
deterministic, order-free derivation: a run's numbers depend on (seed, function, run) and the
plan's settings, never on the batch, the worker or the order of execution.

The shifted suite moves each function's optimum by a seed derived from ``(seed, f)`` alone, so
all algorithms face the same shifted optimum.
"""

from __future__ import annotations

import difflib
from collections.abc import Iterable
from pathlib import Path
from typing import Annotated, Any, ClassVar, Literal

from pydantic import AfterValidator, Field, field_validator

from mawdo.experiments.plans import PlanError, PositiveInt, StudyPlanBase, reject_duplicates
from mawdo.experiments.protocol import Task, missing_run_tasks
from mawdo.functions import FUNCTIONS, PAPER_SUITE
from mawdo.optimizers import (
    ABLATION_ALGORITHMS,
    HOLDOUT_ALGORITHMS,
    OPTIMIZERS,
    PAPER_ALGORITHMS,
    make_optimizer,
)
from mawdo.streams import name_word, seed_word

PAPER_SEED = 20251125
"""Master seed of the paper presets (the paper's arXiv submission date)."""

PLAN_SCHEMA = 1
"""Bumped when the meaning of a plan field changes; part of the plan hash."""

# Salt that separates the shift-seed stream from the run-seed stream of the same function.
_SHIFT_SALT = 0x53484654  # "SHFT"


def _check_algorithm(name: str) -> str:
    # OPTIMIZERS raises UnknownNameError with close-name suggestions; reuse its message.
    return OPTIMIZERS[name].name


def _check_function(name: str) -> str:
    # Paper ids ("F7") resolve to canonical names so a plan has one spelling per function.
    return FUNCTIONS.canonical(name)


AlgorithmName = Annotated[str, AfterValidator(_check_algorithm)]
FunctionName = Annotated[str, AfterValidator(_check_function)]


class ExperimentPlan(StudyPlanBase):
    """A benchmark sweep: ``algorithms x functions x runs`` under one budget and master seed.

    Parameters
    ----------
    name : str
        A label for reports (does not affect numbers).
    algorithms : sequence of str
        Registered algorithm names (``mawdo list``); case-insensitive, no duplicates.
    functions : sequence of str
        Registered function names or paper ids (``"F7"`` becomes ``"rastrigin"``).
    runs : int
        Independent runs per (algorithm, function), >= 1.
    pop_size : int
        Population size of every algorithm, >= 2.
    max_iter : int
        Iterations (``budget="iterations"``), or the iteration count that defines the
        evaluation budget ``pop_size * max_iter`` (``budget="evals"``).
    seed : int
        Master seed, >= 0.
    shifted : bool
        Run the shifted suite (optimum moved to a seeded point, docs/functions.md#f-shift).
    budget : {"iterations", "evals"}
        ``iterations`` (the paper): every algorithm runs ``max_iter`` iterations, so algorithms
        that spend extra evaluations (MAWDO's OBL) get more. ``evals``: every run gets exactly
        ``pop_size * max_iter`` evaluations, so the extra evaluations are paid for.
    bounds_preset : {"paper", "standard"}
        Bounds preset of the benchmark functions (docs/functions.md#f-preset).
    options : dict of str to dict
        Per-algorithm options passed to the optimizer (``{"mawdo": {"groups": 4}}``).
    batch_size : int
        Runs per task (one vectorised batch on one worker). Does not affect numbers.
    """

    study_kind: ClassVar[str] = "benchmark"
    kind: Literal["benchmark"] = "benchmark"
    name: str = "custom"
    algorithms: Annotated[tuple[AlgorithmName, ...], Field(min_length=1)]
    functions: Annotated[tuple[FunctionName, ...], Field(min_length=1)]
    runs: PositiveInt = 30
    pop_size: Annotated[int, Field(strict=True, ge=2)] = 50
    max_iter: PositiveInt = 500
    seed: Annotated[int, Field(strict=True, ge=0)] = PAPER_SEED
    shifted: Annotated[bool, Field(strict=True)] = False
    budget: Literal["iterations", "evals"] = "iterations"
    bounds_preset: Literal["paper", "standard"] = "paper"
    options: dict[str, dict[str, Any]] = Field(default_factory=dict)
    batch_size: PositiveInt = 10

    @field_validator("algorithms", "functions")
    @classmethod
    def _no_duplicates(cls, names: tuple[str, ...], info) -> tuple[str, ...]:
        return reject_duplicates(names, info.field_name)

    @field_validator("options")
    @classmethod
    def _check_options(cls, options: dict[str, dict[str, Any]], info) -> dict[str, dict[str, Any]]:
        # Options are checked by building each optimizer once, so a typo fails at plan time,
        # not minutes into a sweep on a remote worker. Fields validate in declaration order, so
        # algorithms and pop_size are in info.data unless they failed themselves.
        algorithms = info.data.get("algorithms")
        pop_size = info.data.get("pop_size", 50)
        canon: dict[str, dict[str, Any]] = {}
        for key, opts in options.items():
            try:
                algo = OPTIMIZERS[key].name
            except KeyError as exc:
                raise ValueError(f"options.{key}: {exc}") from None
            if algorithms is not None and algo not in algorithms:
                raise ValueError(
                    f"options.{key}: {algo!r} is not one of the plan's algorithms "
                    f"({', '.join(algorithms)})"
                )
            if "pop_size" in opts:
                raise ValueError(
                    f"options.{key}.pop_size: set the population with the plan's pop_size field"
                )
            try:
                make_optimizer(algo, pop_size=pop_size, **opts)
            except (TypeError, ValueError) as exc:
                raise ValueError(f"options.{key}: {exc}") from None
            if opts:
                canon[algo] = dict(opts)
        # Canonical keys and no empty entries, so equal plans hash equally.
        return canon

    # ----------------------------------------------------------------------- construction
    @classmethod
    def from_toml(cls, path: str | Path) -> ExperimentPlan:
        """Load a plan from a TOML file (:meth:`StudyPlanBase.from_file`)."""
        return cls.from_file(path)

    @classmethod
    def preset(cls, name: str) -> ExperimentPlan:
        """The named preset (``preset = "paper-table3"`` in a plan file)."""
        return preset_plan(name)

    def _adjust_overrides(self, data: dict[str, Any], changes: dict[str, Any]) -> dict[str, Any]:
        names = changes.get("algorithms")
        if isinstance(names, str | list | tuple) and "options" not in changes:
            # Options of algorithms no longer in the plan would be an error; drop them.
            keep = {str(a).lower() for a in ([names] if isinstance(names, str) else names)}
            data["options"] = {k: v for k, v in data["options"].items() if k in keep}
        return data

    # ----------------------------------------------------------------------- identity
    def numbers_spec(self) -> dict[str, Any]:
        """Everything that affects stored numbers, as plain JSON data.

        ``name`` and ``batch_size`` are left out: runs are identical whatever the batch
        (``mawdo.minimize`` guarantees it) and a label changes nothing.
        """
        return {
            "schema": PLAN_SCHEMA,
            "algorithms": list(self.algorithms),
            "functions": list(self.functions),
            "runs": self.runs,
            "pop_size": self.pop_size,
            "max_iter": self.max_iter,
            "seed": self.seed,
            "shifted": self.shifted,
            "budget": self.budget,
            "bounds_preset": self.bounds_preset,
            "options": {k: self.options[k] for k in sorted(self.options)},
        }

    # ----------------------------------------------------------------------- seeds
    def function_seed(self, function: str) -> list[int]:
        """Entropy of the seed sequence whose run ``k`` child seeds run ``k`` on ``function``."""
        return [self.seed, name_word(function)]

    def shift_seed(self, function: str) -> int:
        """Seed of ``function``'s shifted optimum: one 32-bit word from ``(seed, function)``."""
        return seed_word([*self.function_seed(function), _SHIFT_SALT])

    # ----------------------------------------------------------------------- work
    @property
    def total_runs(self) -> int:
        return len(self.algorithms) * len(self.functions) * self.runs

    def tasks(self, done: Iterable[tuple[str, str, int]] = ()) -> list[Task]:
        """Tasks computing every run not in ``done`` (``(algorithm, function, run)`` keys; the
        task's ``problem`` is the function).

        Missing runs of each (algorithm, function) are grouped into maximal consecutive
        stretches, each cut into batches of at most ``batch_size``; with nothing done this is
        the plan's regular grid of tasks. Order: function, then algorithm, then run.
        """
        done_set = set(done)
        out: list[Task] = []
        for fn in self.functions:
            for algo in self.algorithms:
                out += missing_run_tasks(algo, fn, self.runs, done_set, self.batch_size)
        return out

    def task_spec(self, task: Task) -> dict[str, Any]:
        """Everything a worker needs to compute ``task``, as plain picklable data."""
        return {
            "kind": self.kind,
            **task.key(),
            "seed_entropy": self.function_seed(task.problem),
            "shifted": self.shifted,
            "shift_seed": self.shift_seed(task.problem) if self.shifted else None,
            "pop_size": self.pop_size,
            "max_iter": self.max_iter,
            "budget": self.budget,
            "bounds_preset": self.bounds_preset,
            "options": dict(self.options.get(task.algorithm, {})),
        }

    def describe(self) -> str:
        """One line for logs and messages."""
        return (
            f"{self.name}: {len(self.algorithms)} algorithms x {len(self.functions)} functions x "
            f"{self.runs} runs, pop {self.pop_size}, {self.max_iter} iterations"
            f"{' (equal evaluations)' if self.budget == 'evals' else ''}"
            f"{', shifted' if self.shifted else ''}, seed {self.seed}"
        )


# --------------------------------------------------------------------------- presets
def _paper(name: str, algorithms=PAPER_ALGORITHMS, **kw) -> dict[str, Any]:
    return {
        "name": name,
        "algorithms": list(algorithms),
        "functions": list(PAPER_SUITE),
        "runs": 30,
        "pop_size": 50,
        "max_iter": 500,
        "seed": PAPER_SEED,
        **kw,
    }


# The hold-out on F1-F16: equal evaluations; the references keep their own population
# rule (CMA-ES 4 + 3 ln D, scipy 15 D), the others the paper's 50.
HOLDOUT = {
    "budget": "evals",
    "options": {"cmaes": {"auto_pop_size": True}, "scipy_de": {"auto_pop_size": True}},
}

PRESETS: dict[str, dict[str, Any]] = {
    "paper-table3": _paper("paper-table3"),
    "paper-table3-shifted": _paper("paper-table3-shifted", shifted=True),
    "paper-table3-evals": _paper("paper-table3-evals", budget="evals"),
    "paper-ablation": _paper("paper-ablation", ABLATION_ALGORITHMS),
    "holdout-paper": _paper("holdout-paper", HOLDOUT_ALGORITHMS, **HOLDOUT),
    "holdout-paper-shifted": _paper(
        "holdout-paper-shifted", HOLDOUT_ALGORITHMS, shifted=True, **HOLDOUT
    ),
    "smoke": {
        "name": "smoke",
        "algorithms": ["gwo", "wdo", "mewdo", "mawdo"],
        "functions": ["sphere", "rastrigin", "six_hump_camel"],
        "runs": 4,
        "pop_size": 10,
        "max_iter": 30,
        "seed": PAPER_SEED,
        "batch_size": 2,
    },
}
"""Named plans. ``paper-*`` follow the paper's protocol (pop 50, 500 iterations, 30 runs,
F1-F16; ``docs/deviations.md#d-protocol``)."""

PRESET_HELP = {
    "paper-table3": "paper Table 3: GWO, WOA, WDO, AWDO, MEWDO, MAWDO on F1-F16, 30 runs",
    "paper-table3-shifted": "paper-table3 on the shifted suite (optimum moved off the centre)",
    "paper-table3-evals": "paper-table3 with equal evaluation budgets (50 x 500 per run)",
    "paper-ablation": "paper Table 5: MAWDO-1..4 and MAWDO on F1-F16, 30 runs",
    "holdout-paper": "WDO+ hold-out: F1-F16, equal evaluations (50 x 500), CMA-ES, scipy "
    "DE, random, the paper's six and WDO+",
    "holdout-paper-shifted": "holdout-paper on the shifted suite (optimum moved off the centre)",
    "smoke": "a few seconds: 4 algorithms, 3 functions, 4 tiny runs",
}


def preset_plan(name: str) -> ExperimentPlan:
    """The named preset plan; an unknown name raises :class:`PlanError` listing the presets."""
    if name not in PRESETS:
        close = difflib.get_close_matches(name, list(PRESETS), n=1)
        hint = f" Did you mean {close[0]!r}?" if close else ""
        raise PlanError(f"preset: unknown preset {name!r}.{hint} Presets: {', '.join(PRESETS)}")
    return ExperimentPlan.from_dict(PRESETS[name])
