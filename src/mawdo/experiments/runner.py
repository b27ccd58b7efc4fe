"""Run a plan into a store: resume, local process pool or Dask, one writer, clean Ctrl-C.

The parent process is the only writer to SQLite; workers (processes of a local pool, or Dask
workers) compute tasks and send their rows back. Every task is a pure function of its spec
(the plan's ``task_spec``), and every kind makes run ``k`` identical whether it is computed alone
or in any batch, so the stored values do not depend on the worker count, the
backend, the order of completion or on where a sweep was interrupted.
"""

from __future__ import annotations

import multiprocessing as mp
import os
import socket
import sys
import time
from collections.abc import Callable, Iterator, Sequence
from concurrent.futures import ProcessPoolExecutor, as_completed
from contextlib import closing
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from threadpoolctl import threadpool_limits

from mawdo.experiments.machine import platform_summary
from mawdo.experiments.progress import RunBar
from mawdo.experiments.protocol import STUDY_KINDS, Study, kind_of
from mawdo.experiments.store import Store, library_version
from mawdo.experiments.workers import worker_init
from mawdo.util.interrupts import SigintWatch, is_interrupt

TASK_KEYS = ("algorithm", "problem", "first_run", "n_runs")


@dataclass
class RunSummary:
    """What :func:`run_plan` did.

    Attributes
    ----------
    store : Path
        The results store.
    total : int
        Runs in the plan.
    skipped : int
        Runs already stored when the sweep started (resume).
    done : int
        Runs computed and stored by this call (failed ones included).
    failed : int
        Of ``done``, runs whose algorithm or objective raised (stored with their error text).
    lost : int
        Runs of tasks that never came back (worker crash, lost Dask worker); not stored, so a
        re-run computes them.
    interrupted : bool
        Stopped by Ctrl-C (KeyboardInterrupt); finished tasks are stored.
    tasks : int
        Tasks stored by this call.
    reused : int
        Runs copied from other stores by this call (``reuse`` of :func:`run_plan`), not
        computed; counted in neither ``skipped`` nor ``done``.
    wall_time : float
        Seconds.
    """

    store: Path
    total: int
    skipped: int = 0
    done: int = 0
    failed: int = 0
    lost: int = 0
    interrupted: bool = False
    tasks: int = 0
    reused: int = 0
    wall_time: float = 0.0

    @property
    def complete(self) -> bool:
        """Every run of the plan is stored."""
        return self.skipped + self.reused + self.done == self.total

    def __str__(self) -> str:
        rate = self.done / self.wall_time if self.wall_time > 0 else 0.0
        parts = [f"{self.done} runs computed ({rate:.1f} runs/s)", f"{self.skipped} already stored"]
        if self.reused:
            parts.append(f"{self.reused} reused from other stores")
        if self.failed:
            parts.append(f"{self.failed} failed")
        if self.lost:
            parts.append(f"{self.lost} lost")
        state = "interrupted" if self.interrupted else ("complete" if self.complete else "partial")
        return (
            f"{state}: {', '.join(parts)}; {self.skipped + self.reused + self.done}/{self.total} "
            f"runs in {self.store} ({self.wall_time:.1f} s)"
        )


# ---------------------------------------------------------------------- the unit of work
def execute_task(spec: dict[str, Any], execute: Callable | None = None) -> dict[str, Any]:
    """Compute one task (a spec from the plan's ``task_spec``) and return its outcome.

    Runs on a worker; must stay a module-level function (pickled by reference). The kind's
    ``execute`` computes the rows; it is looked up in the registry by ``spec["kind"]`` unless
    given (the runner passes it, so a worker process imports the kind's module when it
    unpickles the function, which registers the kind there too).

    Returns
    -------
    dict
        ``task`` (the task key), ``rows`` (the kind's row objects), ``wall`` (s), ``worker``
        (host:pid), ``platform`` (:func:`~mawdo.experiments.machine.platform_summary`) and
        ``library_version``.
    """
    if execute is None:
        execute = STUDY_KINDS[spec["kind"]].execute
    t0 = time.perf_counter()
    # A Ctrl-C is never a result: whatever the kind made of it (an error row, a SystemError
    # from compiled code), the task's rows are dropped and the sweep stops.
    # A task is one core's work: BLAS threads on its small matrices only wait for each other
    # and for the other workers (CMA-ES's 30 x 30 eigh on a busy 2-core machine: 15.6 ms on two
    # threads, 0.11 ms on one; the same numbers, benchmarks/log/optimizers.md).
    with SigintWatch() as watch, threadpool_limits(limits=1, user_api="blas"):
        try:
            rows = execute(spec)
        except BaseException as exc:
            if watch.fired or is_interrupt(exc):
                raise KeyboardInterrupt from exc
            raise
    if watch.fired:
        raise KeyboardInterrupt
    out = {
        "task": {k: spec[k] for k in TASK_KEYS},
        "rows": rows,
        "wall": time.perf_counter() - t0,
        "worker": f"{socket.gethostname()}:{os.getpid()}",
        "platform": platform_summary(),
        "library_version": library_version(),
    }
    if "plan_hash" in spec:  # the runner's specs name their plan; the store checks it
        out["plan_hash"] = spec["plan_hash"]
    return out


def _lost(spec: dict[str, Any], exc: BaseException) -> dict[str, Any]:
    return {
        "task": {k: spec[k] for k in TASK_KEYS},
        "lost": f"{type(exc).__name__}: {exc}",
    }


# ---------------------------------------------------------------------- backends
def _in_process(specs: list[dict], execute: Callable) -> Iterator[dict]:
    for spec in specs:
        yield execute_task(spec, execute)


def _pool(specs: list[dict], workers: int, execute: Callable) -> Iterator[dict]:
    # forkserver/spawn rather than fork: the parent may hold threads (rich's refresh thread,
    # Dask, BLAS pools), and forking a threaded process can deadlock.
    method = "forkserver" if "forkserver" in mp.get_all_start_methods() else "spawn"
    pool = ProcessPoolExecutor(
        max_workers=workers,
        mp_context=mp.get_context(method),
        initializer=worker_init,
        initargs=(os.getpid(),),
    )
    futures = {pool.submit(execute_task, s, execute): s for s in specs}
    finished = False
    try:
        for fut in as_completed(futures):
            try:
                yield fut.result()
            except Exception as exc:  # noqa: BLE001 - a broken pool loses tasks, not the sweep
                yield _lost(futures[fut], exc)
        finished = True
    finally:
        # The executor forgets its processes on shutdown; keep them to stop them ourselves.
        procs = list((getattr(pool, "_processes", None) or {}).values())
        pool.shutdown(wait=finished, cancel_futures=True)
        if not finished:
            # Interrupted: running tasks would otherwise finish (minutes) before exit.
            for proc in procs:
                proc.terminate()
            for proc in procs:
                proc.join(timeout=5)


def _connect(dask, scheduler_file):
    """A Dask client for an address or a scheduler file, and whether this sweep owns it."""
    from distributed import Client

    if scheduler_file is None and not isinstance(dask, str):
        return dask, False  # the caller's connected client, left open
    where = dask if scheduler_file is None else f"of scheduler file {scheduler_file}"
    try:
        if scheduler_file is not None:
            return Client(scheduler_file=str(scheduler_file), timeout="20s"), True
        return Client(dask, timeout="20s"), True
    except (OSError, TimeoutError, ValueError) as exc:
        raise ConnectionError(f"cannot connect to the Dask scheduler {where}: {exc}") from None


def _dask(specs: list[dict], dask, execute: Callable, scheduler_file=None) -> Iterator[dict]:
    from distributed import as_completed as dask_as_completed

    client, own = _connect(dask, scheduler_file)
    futures = {}
    for s in specs:
        f = client.submit(execute_task, s, execute, pure=False)
        futures[f] = s
    finished = False
    try:
        for fut in dask_as_completed(list(futures)):
            try:
                out = fut.result()
            except Exception as exc:  # noqa: BLE001 - e.g. KilledWorker: lost, retried on re-run
                out = _lost(futures[fut], exc)
            fut.release()
            yield out
        finished = True
    finally:
        if not finished:
            client.cancel(list(futures))
        if own:
            client.close()


def _say(msg: str) -> None:
    print(msg, file=sys.stderr, flush=True)


# ---------------------------------------------------------------------- driver
def run_plan(
    plan: Study,
    store_path: str | Path,
    workers: int = 1,
    dask=None,
    progress: bool = True,
    force: bool = False,
    retry_failed: bool = False,
    scheduler_file: str | Path | None = None,
    reuse: Sequence[str | Path] = (),
) -> RunSummary:
    """Compute every run of ``plan`` that ``store_path`` does not hold yet, and store it.

    Long only by its numpydoc docstring; the loop over outcomes is :func:`_store_outcomes`.

    Parameters
    ----------
    plan : Study
        The study: a plan of a registered kind (:data:`~mawdo.experiments.protocol.STUDY_KINDS`).
    store_path : str or Path
        SQLite results store; created if absent, resumed if it holds part of this plan.
    workers : int
        1: compute in this process. >1: a local process pool of that many workers.
    dask : str or distributed.Client, optional
        Send tasks to a Dask cluster instead (scheduler address such as
        ``"tcp://10.0.0.1:8786"``, or a connected client, left open). Excludes ``workers > 1``.
    progress : bool
        Show a progress bar over runs with an ETA (stderr).
    force : bool
        Reuse a store made by another plan or library version by discarding its runs.
    retry_failed : bool
        Compute again the stored runs that failed with an error (``error_text`` set); each
        one's new row replaces it in the transaction that stores its task. A run that ended
        without error but without success (a planner that did not reach its goal) is a result
        and is kept.
    scheduler_file : str or Path, optional
        Send tasks to the Dask cluster whose scheduler wrote this file (``dask scheduler
        --scheduler-file FILE``). Excludes ``dask`` and ``workers > 1``.
    reuse : sequence of str or Path
        Other results stores of the same kind and library version: a run they hold as the same
        computation (:func:`~mawdo.experiments.reuse.same_run`) is copied, not computed.

    Returns
    -------
    RunSummary
        Counts and wall time. A Ctrl-C does not raise: it stops the workers, keeps every
        finished task, stores nothing of the interrupted ones, prints how to resume and
        returns with ``interrupted=True``.

    Raises
    ------
    StoreError
        The store cannot be used (another plan, read-only, corrupt ...).
    ValueError
        Bad ``workers`` / ``dask`` / ``scheduler_file`` combination, or no scheduler file.
    ConnectionError
        The Dask scheduler cannot be reached.
    """
    _check_backend(workers, dask, scheduler_file)
    execute = kind_of(plan).execute
    t0 = time.perf_counter()
    store_path = Path(store_path)
    summary = RunSummary(store=store_path, total=plan.total_runs)
    with Store.open(store_path, plan, force=force) as store:
        bar = RunBar(False, 0, "")
        try:
            if reuse:
                from mawdo.experiments.reuse import reuse_runs

                summary.reused = reuse_runs(plan, store, reuse, say=_say if progress else None)
            tasks = plan.tasks(store.done_keys(failed=not retry_failed))
            summary.skipped = plan.total_runs - sum(t.n_runs for t in tasks) - summary.reused
            # each spec names the plan it is computed for; the store checks it on write
            specs = [{**plan.task_spec(t), "plan_hash": plan.plan_hash} for t in tasks]
            if dask is not None or scheduler_file is not None:
                outcomes = _dask(specs, dask, execute, scheduler_file)
            elif workers > 1 and len(specs) > 1:
                outcomes = _pool(specs, min(workers, len(specs)), execute)
            else:
                outcomes = _in_process(specs, execute)
            bar = RunBar(progress, sum(t.n_runs for t in tasks), plan.name)
            _store_outcomes(outcomes, store, summary, bar)
        except BaseException as exc:
            # Ctrl-C, also where compiled code (scene generation, a kernel) turned it into a
            # SystemError: the finished tasks are stored, the rest is left for the resume.
            if not is_interrupt(exc):
                raise
            summary.interrupted = True
        finally:
            bar.close()
    summary.wall_time = time.perf_counter() - t0
    if summary.interrupted:
        _say(
            f"Interrupted. {summary.skipped + summary.done}/{summary.total} runs are stored in "
            f"{store_path}; run the same command again to resume (stored runs are skipped)."
        )
    elif summary.lost:
        _say(
            f"{summary.lost} runs were lost to worker failures; run the same command again to "
            f"compute them."
        )
    return summary


def _check_backend(workers, dask, scheduler_file) -> None:
    if isinstance(workers, bool) or not isinstance(workers, int) or workers < 1:
        raise ValueError(f"workers={workers!r} must be an integer >= 1")
    if dask is not None and scheduler_file is not None:
        raise ValueError("give either a Dask scheduler address or its scheduler file, not both")
    if (dask is not None or scheduler_file is not None) and workers > 1:
        raise ValueError("give either workers > 1 (local pool) or dask (cluster), not both")
    if scheduler_file is not None and not Path(scheduler_file).is_file():
        raise ValueError(
            f"no Dask scheduler file at {scheduler_file}: start the scheduler with "
            f"`dask scheduler --scheduler-file {scheduler_file}` (and its workers with "
            f"`dask worker --scheduler-file {scheduler_file} --nworkers N --nthreads 1`)"
        )


def _store_outcomes(outcomes, store: Store, summary: RunSummary, bar: RunBar) -> None:
    """Store each outcome as it arrives; count lost tasks (worker failure, other version)."""
    version = library_version()
    with closing(outcomes):
        for out in outcomes:
            n = out["task"]["n_runs"]
            if "lost" not in out and out["library_version"] != version:
                out = {
                    "task": out["task"],
                    "lost": (
                        f"worker {out['worker']} runs mawdo {out['library_version']}, "
                        f"this process {version}"
                    ),
                }
            if "lost" in out:
                summary.lost += n
                _say(f"task lost ({_task_name(out['task'])}): {out['lost']}")
            else:
                store.write_task(out)
                summary.tasks += 1
                summary.done += n
                summary.failed += sum(r.failed for r in out["rows"])
            bar.advance(n, f"{summary.failed} failed" if summary.failed else "")


def _task_name(t: dict[str, Any]) -> str:
    last = t["first_run"] + t["n_runs"] - 1
    return f"{t['algorithm']} on {t['problem']}, runs {t['first_run']}-{last}"
