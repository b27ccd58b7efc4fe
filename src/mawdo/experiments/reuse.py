"""Runs another store already holds, taken into a plan's store instead of computed again.

A run is the same computation in two plans when the work its worker is handed is the same: the
kind's task spec of that one run (:meth:`Study.task_spec` of a one-run task: algorithm,
problem, seeds, settings) is equal in both, and both stores were written by this library
version. A bigger study can then grow from smaller ones (``crowdnav`` from ``crowdnav-50`` and
``crowdnav-10``, a CEC study from one store per algorithm) without recomputing what they hold;
a run is computed from its spec alone, whatever else shares its task (tested for the
benchmark, suite and crowd kinds), so the copied row is the row the plan would compute.
"""

from __future__ import annotations

from collections.abc import Iterable
from pathlib import Path
from typing import Any

from mawdo.experiments.protocol import Task, missing_run_tasks
from mawdo.experiments.sqlitefile import library_version

__all__ = ["ReuseError", "reuse_runs", "same_run"]


class ReuseError(ValueError):
    """A store given to reuse runs from cannot be used (not a store of this kind or version)."""


def same_run(plan: Any, other: Any, algorithm: str, problem: str, run: int) -> bool:
    """Whether run ``run`` of ``algorithm`` on ``problem`` is the same computation in both
    plans: equal one-run task specs (names of the plans apart, which specs do not carry)."""
    task = Task(algorithm, problem, run, 1)
    try:
        return plan.task_spec(task) == other.task_spec(task)
    except (KeyError, ValueError, IndexError):  # a problem or run one of the plans lacks
        return False


def _plan_keys(plan: Any) -> set[tuple[str, str, int]]:
    return {(t.algorithm, t.problem, k) for t in plan.tasks(set()) for k in t.runs}


def _check_source(src: Any, path: Path, plan: Any) -> None:
    from mawdo.experiments.protocol import kind_of

    if kind_of(src.plan) is not kind_of(plan):
        raise ReuseError(
            f"cannot reuse runs from {path}: it holds a {src.plan.kind!r} study, this plan is "
            f"{plan.kind!r}; give a store of the same kind"
        )
    if src.meta["library_version"] != library_version():
        raise ReuseError(
            f"cannot reuse runs from {path}: written by mawdo {src.meta['library_version']}, "
            f"this is mawdo {library_version()} (results of different versions may differ); "
            f"compute them again instead"
        )


def reuse_runs(plan: Any, store: Any, sources: Iterable[str | Path], say=None) -> int:
    """Copy into ``store`` (open for ``plan``) every run of ``plan`` it lacks that a source
    store holds as the same computation (:func:`same_run`), without error.

    Parameters
    ----------
    plan : Study
        The plan ``store`` belongs to.
    store : Store
        Open for writing.
    sources : iterable of str or Path
        Results stores of the same study kind written by this library version; read only.
    say : callable, optional
        ``say(text)`` before each source is read and with what it gave (progress lines).

    Returns
    -------
    int
        Runs copied. Each consecutive block of them is one entry of the store's task log,
        its worker ``reused from <file>`` and its wall time the source runs' own.

    Raises
    ------
    ReuseError
        A source of another kind or library version.
    StoreError
        A source that is no results store, or is damaged.
    """
    from mawdo.experiments.store import Store

    wanted = _plan_keys(plan) - store.done_keys(failed=True)
    copied = 0
    for path in map(Path, sources):
        if say is not None:
            say(f"reading {path} for runs this plan computes the same way ...")
        before = copied
        with Store.read(path) as src:
            _check_source(src, path, plan)
            have = src.done_keys(failed=False) & wanted
            blocks: dict[tuple[str, str], list[int]] = {}
            for a, p, k in sorted(have):
                if same_run(plan, src.plan, a, p, k):
                    blocks.setdefault((a, p), []).append(k)
            for (a, p), runs in blocks.items():
                rows = {r.run: r for _, _, r in src.rows(algorithm=a, problem=p)}
                # the copied runs' consecutive stretches, as the plans cut missing runs
                others = {(a, p, k) for k in range(runs[-1] + 1)} - {(a, p, k) for k in runs}
                for task in missing_run_tasks(a, p, runs[-1] + 1, others, len(runs)):
                    picked = [rows[k] for k in task.runs]
                    store.write_task({
                        "task": task.key(),
                        "rows": picked,
                        "wall": sum(r.wall_time or 0.0 for r in picked),
                        "worker": f"reused from {path.name}",
                    })  # fmt: skip
                    wanted -= {(a, p, k) for k in task.runs}
                    copied += task.n_runs
        if say is not None:
            say(f"{copied - before} runs copied from {path}")
    return copied
