"""Suite-study runs read back from a results store, and COCO's measures computed on them.

Everything a report or an export shows comes from here: the store's best-so-far records, read
through :func:`load_runs`, turned into runtimes to targets (:func:`runtime_table`) and values at
budgets (:func:`precision_at`) with :mod:`mawdo.experiments.kinds.suite.metrics`.
"""

from __future__ import annotations

import functools
import os
from dataclasses import dataclass, field

import numpy as np

from mawdo.experiments.kinds.suite.metrics import fixed_budget, runtimes
from mawdo.experiments.kinds.suite.plan import KIND
from mawdo.experiments.store import Store


@dataclass(frozen=True)
class StoredRun:
    """One successful run of the store (failed runs are counted, not loaded).

    Attributes
    ----------
    algorithm : str
    function_id, instance, dim, run : int
    function_name : str
    f_star : float
        Optimum value.
    evals : numpy.ndarray of int64
        Improvement evaluations (1-based).
    best_y : numpy.ndarray
        Best raw value from each improvement on.
    nfev, max_evals : int
        Evaluations spent and the budget.
    best_x : numpy.ndarray
    """

    algorithm: str
    function_id: int
    instance: int
    dim: int
    run: int
    function_name: str
    f_star: float
    evals: np.ndarray
    best_y: np.ndarray
    nfev: int
    max_evals: int
    best_x: np.ndarray

    @property
    def precision(self) -> np.ndarray:
        """``best_y - f_star`` at each improvement."""
        return self.best_y - self.f_star


@dataclass(frozen=True)
class StudyRuns:
    """The runs of a store and its plan's axes; ``setups`` says what runs under each
    algorithm's name (``{"mawdo-r10": "mawdo (restart_every=10)"}``); ``versions``: the mawdo
    versions that made the store(s), which a report names (a report reads a store of any
    version of this schema)."""

    suite: str
    algorithms: tuple[str, ...]
    functions: tuple[int, ...]
    dims: tuple[int, ...]
    budget: float
    runs: list[StoredRun]
    failed: int
    setups: dict[str, str] = field(default_factory=dict)
    versions: tuple[str, ...] = ()
    numbering: str = ""  # how the function ids map to the official ones ("" if they are them)

    @functools.cached_property
    def _index(self) -> dict[tuple[str, int, int], list[StoredRun]]:
        # reports select (algorithm, function, D) cells thousands of times: one pass, not many
        out: dict[tuple[str, int, int], list[StoredRun]] = {}
        for r in self.runs:
            out.setdefault((r.algorithm, r.function_id, r.dim), []).append(r)
        return out

    def select(self, algorithm=None, function_id=None, dim=None) -> list[StoredRun]:
        """Runs matching every given filter, in store order."""
        if None not in (algorithm, function_id, dim):
            return list(self._index.get((algorithm, function_id, dim), []))
        return [
            r
            for r in self.runs
            if (algorithm is None or r.algorithm == algorithm)
            and (function_id is None or r.function_id == function_id)
            and (dim is None or r.dim == dim)
        ]


def load_runs(store_paths) -> StudyRuns:
    """Every stored run of one suite-study store, or of several merged (read-only).

    Several stores are one study when they hold the same suite at the same budget per
    dimension (e.g. ``bbob-full`` run once per dimension into its own file): their algorithms,
    functions and dimensions are united, in the order first seen.

    Parameters
    ----------
    store_paths : str, Path or sequence of them
        One store, or several.

    Raises
    ------
    StoreError
        Not a results store, a store of another study kind, or stores that are not one study
        (another suite or budget, or the same run stored twice).
    """
    if isinstance(store_paths, (str, os.PathLike)):
        return _load_one(store_paths)
    paths = list(store_paths)
    if not paths:
        raise ValueError("no results store given; name one or more suite-study stores")
    parts = [_load_one(p) for p in paths]
    return parts[0] if len(parts) == 1 else _merge(parts, paths)


def _load_one(store_path) -> StudyRuns:
    from mawdo.experiments.store import StoreError

    with Store.read(store_path) as store:
        plan = store.plan
        if getattr(plan, "kind", None) != KIND:
            raise StoreError(
                f"{store_path} holds a {getattr(plan, 'kind', '?')!r} study, not a suite study "
                f"(mawdo bench run --suite ...)"
            )
        out, failed = [], 0
        for algo, _problem, r in store.rows(skip=("params", "seed_entropy")):
            if r.failed:
                failed += 1
                continue
            out.append(
                StoredRun(
                    algo,
                    r.function_id,
                    r.instance,
                    r.dim,
                    r.run,
                    r.function_name,
                    r.f_star,
                    r.evals,
                    r.best_so_far,
                    r.nfev,
                    r.max_evals,
                    r.best_x,
                )
            )
    return StudyRuns(
        plan.suite,
        tuple(plan.algorithms),
        tuple(plan.functions),
        tuple(sorted(plan.dims)),
        plan.budget,
        out,
        failed,
        {a: plan.setup(a) for a in plan.algorithms},
        (str(store.meta.get("library_version", "unknown")),),
        plan.numbering_note(),
    )


def _merge(parts: list[StudyRuns], paths: list) -> StudyRuns:
    """One study from the studies of several stores; refuses what would mix two studies."""
    from mawdo.experiments.store import StoreError

    first = parts[0]
    seen: dict[tuple, object] = {}
    for part, path in zip(parts, paths, strict=True):
        if (part.suite, part.budget) != (first.suite, first.budget):
            raise StoreError(
                f"{path} holds suite {part.suite} at {part.budget:g} x D evaluations, but "
                f"{paths[0]} holds {first.suite} at {first.budget:g} x D: report them separately"
            )
        if part.numbering != first.numbering:
            raise StoreError(
                f"{path} and {paths[0]} hold {first.suite} functions of different sources (one "
                f"store was made when {first.suite} meant opfunu's functions): report them "
                "separately"
            )
        for r in part.runs:
            key = (r.algorithm, r.function_id, r.instance, r.dim, r.run)
            if key in seen:
                raise StoreError(
                    f"{path} and {seen[key]} both hold run {r.run} of {r.algorithm} on "
                    f"f{r.function_id} instance {r.instance} at D = {r.dim}: they are not parts "
                    f"of one study; report them separately"
                )
            seen[key] = path
        for name, setup in part.setups.items():
            others = {q.setups[name] for q in parts if name in q.setups} - {setup}
            if others:
                other = others.pop()
                raise StoreError(
                    f"{path} runs {name!r} as {setup}, another store as {other}: they are not "
                    f"one study; report them separately (or give the variants their own labels)"
                )

    def union(field: str) -> tuple:
        return tuple(dict.fromkeys(v for p in parts for v in getattr(p, field)))

    return StudyRuns(
        first.suite,
        union("algorithms"),
        union("functions"),
        tuple(sorted(union("dims"))),
        first.budget,
        [r for p in parts for r in p.runs],
        sum(p.failed for p in parts),
        {k: v for p in parts for k, v in p.setups.items()},
        union("versions"),
        first.numbering,
    )


def runtime_table(runs: list[StoredRun], targets) -> tuple[np.ndarray, np.ndarray]:
    """Runtimes of ``runs`` to each precision target, and their evaluations spent.

    Returns
    -------
    rt : numpy.ndarray
        ``(len(runs), T)`` evaluations to reach each target (``inf``: not reached).
    spent : numpy.ndarray
        ``(len(runs),)`` evaluations each run spent.
    """
    t = np.asarray(targets, dtype=float)
    rt = np.array([runtimes(r.evals, r.best_y, r.f_star, t) for r in runs]).reshape(-1, t.size)
    return rt, np.array([r.nfev for r in runs], dtype=float)


def precision_at(runs: list[StoredRun], budgets) -> np.ndarray:
    """``(len(runs), B)`` precision ``f - f_star`` of the best-so-far after each budget
    (evaluations; ``inf`` before the first evaluation). A run that stopped at the final target
    keeps its last value."""
    b = np.asarray(budgets, dtype=float)
    out = [fixed_budget(r.evals, r.best_y, b) - r.f_star for r in runs]
    return np.array(out).reshape(-1, b.size)
