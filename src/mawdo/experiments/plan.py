"""Experiment plans: which algorithms, functions, runs and budgets a sweep covers (SPEC 3).

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
import hashlib
import json
import tomllib
import zlib
from collections.abc import Iterable, Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import Annotated, Any, Literal

import numpy as np
from pydantic import (
    AfterValidator,
    BaseModel,
    ConfigDict,
    Field,
    ValidationError,
    field_validator,
)

from mawdo.functions import FUNCTIONS, PAPER_SUITE
from mawdo.optimizers import ABLATION_ALGORITHMS, OPTIMIZERS, PAPER_ALGORITHMS, make_optimizer

PAPER_SEED = 20251125
"""Master seed of the paper presets (the paper's arXiv submission date)."""

PLAN_SCHEMA = 1
"""Bumped when the meaning of a plan field changes; part of the plan hash."""

# Salt that separates the shift-seed stream from the run-seed stream of the same function.
_SHIFT_SALT = 0x53484654  # "SHFT"


class PlanError(ValueError):
    """An invalid experiment plan; the message has one ``field: problem`` line per error."""


def _check_algorithm(name: str) -> str:
    # OPTIMIZERS raises UnknownNameError with close-name suggestions; reuse its message.
    return OPTIMIZERS[name].name


def _check_function(name: str) -> str:
    # Paper ids ("F7") resolve to canonical names so a plan has one spelling per function.
    return FUNCTIONS.canonical(name)


AlgorithmName = Annotated[str, AfterValidator(_check_algorithm)]
FunctionName = Annotated[str, AfterValidator(_check_function)]
# strict: a TOML ``runs = 3.5`` or ``runs = true`` is an error, not silently 3 or 1.
PositiveInt = Annotated[int, Field(strict=True, ge=1)]


@dataclass(frozen=True, order=True)
class Task:
    """The unit of work: runs ``first_run .. first_run + n_runs - 1`` of one algorithm on one
    function, executed as one vectorised batch.

    Attributes
    ----------
    algorithm : str
        Registered algorithm name.
    function : str
        Canonical function name.
    first_run : int
        Index of the first run (runs are numbered ``0 .. plan.runs - 1``).
    n_runs : int
        Number of consecutive runs.
    """

    algorithm: str
    function: str
    first_run: int
    n_runs: int

    @property
    def runs(self) -> range:
        """The run indices this task computes."""
        return range(self.first_run, self.first_run + self.n_runs)


class ExperimentPlan(BaseModel):
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
        Run the shifted suite (optimum moved to a seeded point, SPEC 2).
    budget : {"iterations", "evals"}
        ``iterations`` (the paper): every algorithm runs ``max_iter`` iterations, so algorithms
        that spend extra evaluations (MAWDO's OBL) get more. ``evals``: every run gets exactly
        ``pop_size * max_iter`` evaluations, so the extra evaluations are paid for.
    bounds_preset : {"paper", "standard"}
        Bounds preset of the benchmark functions (SPEC 2).
    options : dict of str to dict
        Per-algorithm options passed to the optimizer (``{"mawdo": {"groups": 4}}``).
    batch_size : int
        Runs per task (one vectorised batch on one worker). Does not affect numbers.
    """

    model_config = ConfigDict(frozen=True, extra="forbid")

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
        first: dict[str, int] = {}
        for i, n in enumerate(names):
            if n in first:
                raise ValueError(
                    f"{info.field_name}[{i}]: {n!r} is listed twice "
                    f"(also {info.field_name}[{first[n]}])"
                )
            first[n] = i
        return names

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
    def from_dict(cls, data: Mapping[str, Any]) -> ExperimentPlan:
        """Validate ``data`` (e.g. parsed TOML); raise :class:`PlanError` naming each field."""
        if not isinstance(data, Mapping):
            raise PlanError(f"a plan must be a table of fields, got {type(data).__name__}")
        try:
            return cls.model_validate(dict(data))
        except ValidationError as exc:
            raise PlanError(format_errors(exc, cls)) from None

    @classmethod
    def from_toml(cls, path: str | Path) -> ExperimentPlan:
        """Load a plan from a TOML file.

        The file holds the fields at top level, or under a ``[plan]`` table; a ``preset = "..."``
        key starts from that preset and the other keys override it.
        """
        path = Path(path)
        try:
            text = path.read_text(encoding="utf-8")
        except OSError as exc:
            raise PlanError(f"cannot read plan file {path}: {exc.strerror or exc}") from None
        try:
            data = tomllib.loads(text)
        except tomllib.TOMLDecodeError as exc:
            raise PlanError(f"{path}: not valid TOML: {exc}") from None
        if "plan" in data and isinstance(data["plan"], dict) and len(data) == 1:
            data = data["plan"]
        data = dict(data)
        preset = data.pop("preset", None)
        try:
            if preset is not None:
                if not isinstance(preset, str):
                    raise PlanError(f"preset: must be a string, got {preset!r}")
                return preset_plan(preset).with_overrides(**data)
            return cls.from_dict(data)
        except PlanError as exc:
            raise PlanError(f"{path}: {exc}") from None

    def with_overrides(self, **changes: Any) -> ExperimentPlan:
        """A new, re-validated plan with some fields replaced (``None`` values are ignored)."""
        changes = {k: v for k, v in changes.items() if v is not None}
        if not changes:
            return self
        data = self.model_dump()
        data.update(changes)
        if "algorithms" in changes and "options" not in changes:
            # Options of algorithms no longer in the plan would be an error; drop them.
            names = changes["algorithms"]
            keep = {str(a).lower() for a in ([names] if isinstance(names, str) else names)}
            data["options"] = {k: v for k, v in data["options"].items() if k in keep}
        return type(self).from_dict(data)

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

    @property
    def plan_hash(self) -> str:
        """SHA-256 of the canonical JSON of :meth:`numbers_spec` (hex)."""
        blob = json.dumps(self.numbers_spec(), sort_keys=True, separators=(",", ":"))
        return hashlib.sha256(blob.encode("utf-8")).hexdigest()

    def to_json(self) -> str:
        """The full plan (name and batch size included) as JSON, for the store's meta table."""
        return json.dumps(self.model_dump(mode="json"), sort_keys=True)

    @classmethod
    def from_json(cls, text: str) -> ExperimentPlan:
        return cls.from_dict(json.loads(text))

    # ----------------------------------------------------------------------- seeds
    def function_seed(self, function: str) -> list[int]:
        """Entropy of the seed sequence whose run ``k`` child seeds run ``k`` on ``function``."""
        return [self.seed, zlib.crc32(function.encode("utf-8"))]

    def shift_seed(self, function: str) -> int:
        """Seed of ``function``'s shifted optimum: one 32-bit word from ``(seed, function)``."""
        ss = np.random.SeedSequence([*self.function_seed(function), _SHIFT_SALT])
        return int(ss.generate_state(1, dtype=np.uint32)[0])

    # ----------------------------------------------------------------------- work
    @property
    def total_runs(self) -> int:
        return len(self.algorithms) * len(self.functions) * self.runs

    def tasks(self, done: Iterable[tuple[str, str, int]] = ()) -> list[Task]:
        """Tasks computing every run not in ``done`` (``(algorithm, function, run)`` keys).

        Missing runs of each (algorithm, function) are grouped into maximal consecutive
        stretches, each cut into batches of at most ``batch_size``; with nothing done this is
        the plan's regular grid of tasks. Order: function, then algorithm, then run.
        """
        done_set = set(done)
        out: list[Task] = []
        for fn in self.functions:
            for algo in self.algorithms:
                missing = [k for k in range(self.runs) if (algo, fn, k) not in done_set]
                for start, stop in _stretches(missing):
                    for first in range(start, stop, self.batch_size):
                        out.append(Task(algo, fn, first, min(self.batch_size, stop - first)))
        return out

    def task_spec(self, task: Task) -> dict[str, Any]:
        """Everything a worker needs to compute ``task``, as plain picklable data."""
        return {
            "algorithm": task.algorithm,
            "function": task.function,
            "first_run": task.first_run,
            "n_runs": task.n_runs,
            "seed_entropy": self.function_seed(task.function),
            "shifted": self.shifted,
            "shift_seed": self.shift_seed(task.function) if self.shifted else None,
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


def _stretches(indices: list[int]) -> list[tuple[int, int]]:
    """``[0,1,2,5,6]`` -> ``[(0,3), (5,7)]`` (half-open)."""
    out: list[tuple[int, int]] = []
    for k in indices:
        if out and out[-1][1] == k:
            out[-1] = (out[-1][0], k + 1)
        else:
            out.append((k, k + 1))
    return out


# --------------------------------------------------------------------------- error messages
def format_errors(exc: ValidationError, model: type[BaseModel] = ExperimentPlan) -> str:
    """One ``field: problem`` line per pydantic error, in the project's wording."""
    errors = exc.errors()
    # A list whose every item failed is also reported "too short" by pydantic; the item
    # errors already say what is wrong.
    failed_items = {e["loc"][0] for e in errors if len(e["loc"]) > 1}
    errors = [e for e in errors if not (e["type"] == "too_short" and e["loc"][0] in failed_items)]
    return "\n".join(_format_one(err, model) for err in errors)


def _loc(loc: tuple) -> str:
    out = ""
    for part in loc:
        if isinstance(part, int):
            out += f"[{part}]"
        else:
            out += f".{part}" if out else str(part)
    return out


def _format_one(err: dict, model: type[BaseModel]) -> str:
    typ, ctx, loc = err["type"], err.get("ctx") or {}, _loc(err["loc"])
    got = err.get("input")
    if typ == "greater_than_equal":
        msg = f"must be >= {ctx['ge']} (got {got!r})"
    elif typ in ("int_type", "int_parsing", "int_from_float"):
        msg = f"must be an integer (got {got!r})"
    elif typ == "bool_type":
        msg = f"must be true or false (got {got!r})"
    elif typ == "string_type":
        msg = f"must be a string (got {got!r})"
    elif typ == "literal_error":
        msg = f"must be one of {ctx['expected']} (got {got!r})"
    elif typ == "too_short":
        msg = "must not be empty: list at least one name"
    elif typ == "missing":
        msg = "is required"
    elif typ == "extra_forbidden":
        fields = list(model.model_fields)
        close = difflib.get_close_matches(str(err["loc"][-1]), fields, n=1)
        hint = f" Did you mean {close[0]!r}?" if close else ""
        msg = f"unknown field.{hint} Plan fields: {', '.join(fields)}"
    elif typ in ("tuple_type", "list_type"):
        msg = f"must be a list of names (got {got!r})"
    elif typ == "dict_type":
        msg = f"must be a table (got {got!r})"
    elif typ == "value_error":
        msg = str(ctx.get("error", err["msg"]))
        # Validators that know a finer location put it in front of their message.
        if not loc or msg.startswith(f"{loc}[") or msg.startswith(f"{loc}."):
            return msg
    else:
        msg = err["msg"]
    return f"{loc}: {msg}" if loc else msg


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


PRESETS: dict[str, dict[str, Any]] = {
    "paper-table3": _paper("paper-table3"),
    "paper-table3-shifted": _paper("paper-table3-shifted", shifted=True),
    "paper-table3-evals": _paper("paper-table3-evals", budget="evals"),
    "paper-ablation": _paper("paper-ablation", ABLATION_ALGORITHMS),
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
"""Named plans. ``paper-*`` follow SPEC 3 (pop 50, 500 iterations, 30 runs, F1-F16)."""

PRESET_HELP = {
    "paper-table3": "paper Table 3: GWO, WOA, WDO, AWDO, MEWDO, MAWDO on F1-F16, 30 runs",
    "paper-table3-shifted": "paper-table3 on the shifted suite (optimum moved off the centre)",
    "paper-table3-evals": "paper-table3 with equal evaluation budgets (50 x 500 per run)",
    "paper-ablation": "paper Table 5: MAWDO-1..4 and MAWDO on F1-F16, 30 runs",
    "smoke": "a few seconds: 4 algorithms, 3 functions, 4 tiny runs",
}


def preset_plan(name: str) -> ExperimentPlan:
    """The named preset plan; an unknown name raises :class:`PlanError` listing the presets."""
    if name not in PRESETS:
        close = difflib.get_close_matches(name, list(PRESETS), n=1)
        hint = f" Did you mean {close[0]!r}?" if close else ""
        raise PlanError(f"preset: unknown preset {name!r}.{hint} Presets: {', '.join(PRESETS)}")
    return ExperimentPlan.from_dict(PRESETS[name])
