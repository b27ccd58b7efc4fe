"""What every study kind provides, and the registry the runner and the store look kinds up in.

A *study kind* (the function benchmark, the planning study, ...) is a package under
``mawdo.experiments`` (or anywhere else: a test registers its own) that registers one
:class:`StudyKind` in :data:`STUDY_KINDS`:

- a plan class satisfying :class:`Study` (usually a :class:`~mawdo.experiments.plans.
  StudyPlanBase` subclass), which cuts itself into :class:`Task` objects and turns each into a
  plain, picklable spec;
- ``execute``: a module-level function ``spec -> list of rows`` that computes one task on a
  worker (pickled by reference, so the worker imports the kind's module and registers it);
- ``row``: the kind's typed row (:class:`~mawdo.experiments.rows.RunRow` subclass), which fixes
  the columns of the store's ``runs`` table;
- ``report`` (optional): ``(store_path, out_dir, **options) -> Path``;
- ``presets``: the kind's named plans (``name -> plan fields``), unique across kinds, so that
  ``mawdo study run NAME`` finds the kind from the name alone (:func:`find_preset`).

The runner and the store know only this module; they never import a concrete kind.
"""

from __future__ import annotations

import difflib
import json
from collections.abc import Callable, Iterable, Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Protocol, runtime_checkable

from mawdo.experiments.plans import PlanError, plan_from_data, read_plan_file
from mawdo.experiments.rows import RunRow, schema
from mawdo.registry import Registry


@dataclass(frozen=True, order=True)
class Task:
    """The unit of work: runs ``first_run .. first_run + n_runs - 1`` of one algorithm on one
    problem (a benchmark function, a scenario ...), executed as one batch on one worker.

    Attributes
    ----------
    algorithm : str
        Registered algorithm name (or a kind's baseline).
    problem : str
        Canonical name of what is solved (the kind says what: function, scenario).
    first_run : int
        Index of the first run (runs are numbered ``0 .. runs - 1``).
    n_runs : int
        Number of consecutive runs.
    """

    algorithm: str
    problem: str
    first_run: int
    n_runs: int

    @property
    def runs(self) -> range:
        """The run indices this task computes."""
        return range(self.first_run, self.first_run + self.n_runs)

    def key(self) -> dict[str, Any]:
        """The task as plain data (part of every spec and outcome)."""
        return {
            "algorithm": self.algorithm,
            "problem": self.problem,
            "first_run": self.first_run,
            "n_runs": self.n_runs,
        }


@runtime_checkable
class Study(Protocol):
    """The interface of a plan that :func:`~mawdo.experiments.runner.run_plan` can compute into
    a :class:`~mawdo.experiments.store.Store`.

    Attributes
    ----------
    kind : str
        The registered study kind (also a field of the plan's JSON).
    name : str
        A label for reports and logs.
    plan_hash : str
        Hash of everything that affects stored numbers (ties a store to its plan).
    total_runs : int
        Runs in the plan.
    """

    kind: str
    name: str

    @property
    def plan_hash(self) -> str: ...

    @property
    def total_runs(self) -> int: ...

    def to_json(self) -> str:
        """The full plan as JSON (read back by the kind's plan class ``from_json``)."""

    def numbers_spec(self) -> dict[str, Any]:
        """Everything that affects stored numbers (shown when a store belongs to another plan)."""

    def tasks(self, done: Iterable[tuple[str, str, int]] = ()) -> list[Task]:
        """Tasks computing every run not in ``done`` (``(algorithm, problem, run)`` keys)."""

    def task_spec(self, task: Task) -> dict[str, Any]:
        """Everything a worker needs to compute ``task``, as plain picklable data; includes
        ``kind`` and :meth:`Task.key`."""

    def describe(self) -> str:
        """One line for logs and reports."""


def missing_run_tasks(
    algorithm: str, problem: str, runs: int, done: set, batch_size: int
) -> list[Task]:
    """Tasks computing the runs ``0 .. runs - 1`` of ``(algorithm, problem)`` not in ``done``.

    Missing runs are grouped into contiguous stretches (a task is ``first_run`` + ``n_runs``),
    each cut into batches of at most ``batch_size``; with nothing done this is the regular grid.
    ``done`` holds ``(algorithm, problem, run)`` keys.
    """
    out: list[Task] = []
    start = None
    for k in range(runs + 1):
        missing = k < runs and (algorithm, problem, k) not in done
        if missing and start is None:
            start = k
        elif not missing and start is not None:
            for first in range(start, k, batch_size):
                out.append(Task(algorithm, problem, first, min(batch_size, k - first)))
            start = None
    return out


@dataclass(frozen=True)
class StudyKind:
    """A registered study kind (see the module docstring).

    Attributes
    ----------
    name : str
        Kind name, the ``kind`` field of its plans.
    plan : type
        Plan class: ``from_json``/``from_dict`` classmethods, instances satisfy :class:`Study`.
    execute : callable
        ``spec -> list[row]``: computes one task; module-level (pickled by reference). A run
        whose algorithm raises must become a row with ``error_text``, not an exception.
    row : type
        The kind's :class:`~mawdo.experiments.rows.RunRow` subclass.
    report : callable, optional
        ``(store_path, out_dir, **options) -> Path`` of the main report file.
    description : str
        One line for listings.
    aliases : tuple of str
        Former names of the kind: stores and plans that name it so are read as this kind.
    presets : mapping of str to mapping
        Named plans: preset name -> the plan's fields (``plan.from_dict`` reads them). Names are
        unique across every registered kind (checked by :func:`register_kind`).
    preset_help : mapping of str to str
        One line per preset for listings; a preset without one is described by its plan's
        ``describe()``.
    report_merges_stores : bool
        True: ``report`` takes a list of stores of one study (e.g. one per dimension) and
        reports them together; False: one store.
    """

    name: str
    plan: type
    execute: Callable[[dict[str, Any]], list[RunRow]]
    row: type[RunRow]
    report: Callable[..., Path] | None = None
    description: str = ""
    aliases: tuple[str, ...] = ()
    presets: Mapping[str, Mapping[str, Any]] = field(default_factory=dict)
    preset_help: Mapping[str, str] = field(default_factory=dict)
    report_merges_stores: bool = False

    def __post_init__(self) -> None:
        schema(self.row)  # fails now, at registration, on an undeclared field
        if getattr(self.plan, "study_kind", None) != self.name:
            raise ValueError(
                f"study kind {self.name!r}: its plan class {self.plan.__name__} must set "
                f"study_kind = {self.name!r}"
            )
        unknown = sorted(set(self.preset_help) - set(self.presets))
        if unknown:
            raise ValueError(f"study kind {self.name!r}: help for unknown presets {unknown}")

    def preset_plan(self, name: str) -> Any:
        """The plan of the preset ``name`` (validated); an unknown name raises
        :class:`PlanError` with the closest names."""
        if name not in self.presets:
            raise PlanError(_unknown_preset(name, self.presets))
        return self.plan.from_dict(self.presets[name])

    def preset_line(self, name: str) -> str:
        """One line describing the preset ``name``."""
        return self.preset_help.get(name) or self.preset_plan(name).describe()


DEFAULT_KIND = "benchmark"
"""The kind of a plan that names none (plans and stores written before kinds existed)."""

STUDY_KINDS: Registry[StudyKind] = Registry("study kind")
"""Every registered study kind. The built-in kinds register when :mod:`mawdo.experiments` is
imported; a plug-in kind registers when its module is."""


def register_kind(kind: StudyKind) -> StudyKind:
    """Add ``kind`` to :data:`STUDY_KINDS` and return the registered kind.

    Registering again under a name the same plan class already holds (a reload of the kind's
    module) keeps the first registration; a different plan class under a taken name is an error,
    and so is a preset name another kind already has (``mawdo study run NAME`` must know which
    kind NAME means).
    """
    if kind.name in STUDY_KINDS:
        old = STUDY_KINDS[kind.name]
        if f"{old.plan.__module__}.{old.plan.__qualname__}" == (
            f"{kind.plan.__module__}.{kind.plan.__qualname__}"
        ):
            return old
    taken = all_presets()
    for name in kind.presets:
        if name in taken:
            raise ValueError(
                f"study kind {kind.name!r}: preset {name!r} is already a preset of the "
                f"{taken[name].name!r} kind; preset names are unique across kinds, rename it"
            )
    STUDY_KINDS.register(kind.name, kind)
    for old_name in kind.aliases:
        STUDY_KINDS.add_alias(old_name, kind.name)
    return kind


def all_presets() -> dict[str, StudyKind]:
    """Every registered preset name -> the kind it belongs to, in registration order."""
    return {name: kind for kind in STUDY_KINDS.values() for name in kind.presets}


def _unknown_preset(name: str, known: Iterable[str]) -> str:
    known = list(known)
    close = difflib.get_close_matches(name, known, n=2, cutoff=0.5)
    hint = f" Did you mean {' or '.join(map(repr, close))}?" if close else ""
    return f"preset: unknown preset {name!r}.{hint} Presets: {', '.join(known)}"


def find_preset(name: str) -> Any:
    """The plan of the preset ``name``, whichever registered kind has it.

    Raises
    ------
    PlanError
        No kind has a preset of that name; the message gives the closest names and the list.
    """
    presets = all_presets()
    if name not in presets:
        raise PlanError(_unknown_preset(name, presets))
    return presets[name].preset_plan(name)


def load_plan_file(path: str | Path) -> Any:
    """The plan in a TOML (or ``.json``) plan file, of whichever registered kind it names.

    A ``preset`` key decides the kind (the other keys override the preset's fields; a ``kind``
    key must agree); else the file's ``kind`` field, else the one kind whose plan has every
    field the file sets, else ``benchmark`` (plan files written before kinds existed).

    Raises
    ------
    PlanError
        An unreadable file, an unknown kind or preset, or an invalid field; the message names
        the file.
    """
    return plan_from_data(path, read_plan_file(path), find_preset, _plan_of_fields)


def _plan_of_fields(data: dict[str, Any]) -> Any:
    kind = data.get("kind") or _kind_by_fields(data)
    if not isinstance(kind, str) or kind not in STUDY_KINDS:
        raise PlanError(f"kind: unknown study kind {kind!r}; kinds: {', '.join(STUDY_KINDS)}")
    return STUDY_KINDS[kind].plan.from_dict(data)


def _kind_by_fields(data: Mapping[str, Any]) -> str:
    fits = [
        k.name
        for k in STUDY_KINDS.values()
        if set(data) <= set(getattr(k.plan, "model_fields", ()))
    ]
    return fits[0] if len(fits) == 1 else DEFAULT_KIND


def kind_of(plan: Any) -> StudyKind:
    """The registered kind of a plan object."""
    name = getattr(plan, "kind", None)
    if not isinstance(name, str):
        raise TypeError(
            f"{type(plan).__name__} is not a study plan (no 'kind'); plans are made by a "
            f"registered study kind, e.g. mawdo.experiments.ExperimentPlan"
        )
    return STUDY_KINDS[name]


def plan_from_json(text: str, stored: bool = False) -> Any:
    """The plan stored in a results store, whichever registered kind it is.

    ``stored=True``: the text comes from a store's meta row; the plan is validated with the
    context ``{"stored": True}`` (see :meth:`StudyPlanBase.from_dict`).

    A plan without a ``kind`` field is a benchmark plan (stores written before kinds existed).
    """
    try:
        data = json.loads(text)
    except json.JSONDecodeError as exc:
        raise PlanError(f"stored plan is not valid JSON: {exc}") from None
    if not isinstance(data, dict):
        raise PlanError("stored plan is not a table of fields")
    name = data.get("kind", DEFAULT_KIND)
    try:
        kind = STUDY_KINDS[name]
    except KeyError as exc:
        raise PlanError(
            f"{exc}; import the module that registers it before reading this store"
        ) from None
    if stored:
        return kind.plan.from_dict(data, stored=True)
    return kind.plan.from_dict(data)
