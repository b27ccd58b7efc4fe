"""The cost kernel over a population on several threads: rows in chunks, one kernel call each.

A candidate's cost, length, count and turning depend on that candidate alone (the filters in
front of the exact tests only skip work whose outcome is certain), so chunks of rows can run at
once and give the very numbers of one call. The chunks run in a Numba ``prange`` loop, on
Numba's threading layer (a pool of Python threads took about 0.1 ms to hand a chunk over, as
long as a whole call of 240 candidates). The parallel function is compiled on the first call
with ``threads > 1``; with ``threads = 1`` the kernel is called directly.

OpenMP's threads, left to themselves, wait spinning after a call (libgomp: 300,000 spins) so
that the next one starts at once. On a machine whose cores are busy that spinning takes the
cores from the thread with work and from everyone else: the realtime planner's replans became
3-8x slower (median) with ``threads=2`` than with one thread (``python -m benchmarks
threads``). So this module asks the OpenMP runtime to sleep at once (``OMP_WAIT_POLICY=passive``)
unless the user chose a policy (``OMP_WAIT_POLICY``, ``GOMP_SPINCOUNT`` or ``KMP_BLOCKTIME`` set)
or Numba's threads are already running (the runtime reads the variable when it starts).

Numba's threading layers differ in safety (its documentation, "The Threading Layers"): the
``workqueue`` layer, the fallback where neither TBB nor OpenMP is installed, must not be
entered from two threads at once, so calls go through a process-wide lock; and the OpenMP layer
must not be used on both sides of a ``fork()`` (mawdo's study runner starts its workers with
``forkserver`` or ``spawn``).
"""

from __future__ import annotations

import os
import threading
import time
from dataclasses import dataclass

import numpy as np
from numba import njit, prange

from mawdo.planning.refine.kernel.constants import INDEX_MOVERS, INDEX_STANDING
from mawdo.planning.refine.kernel.population import fused_population_cost, scratch_size
from mawdo.util.validate import check_int

# Fewer rows than this per chunk do not repay the hand-over.
MIN_ROWS = 16
# A call is split into chunks only when the same call on one thread took at least this much CPU
# (seconds): each chunk repeats the call's set-up (the obstacles' bounds, the movers' position
# grids) and waking a sleeping thread costs tens of microseconds, so on the paper scenario's
# 0.3-0.5 ms population calls two threads made replans slower (median 18 ms against 15-19 ms),
# while the crowd's 1.3-1.7 ms calls ran 35-40 % faster (benchmarks/log/latency.md).
PARALLEL_SECONDS = 1e-3

_lock = threading.Lock()

# environment variables through which a user picks how OpenMP threads wait
WAIT_VARIABLES = ("OMP_WAIT_POLICY", "GOMP_SPINCOUNT", "KMP_BLOCKTIME")


def passive_wait() -> bool:
    """Make Numba's OpenMP threads sleep, not spin, between calls, unless told otherwise.

    Sets ``OMP_WAIT_POLICY=passive`` in this process's environment when none of
    :data:`WAIT_VARIABLES` is set and Numba has not started its threads yet (the runtime reads
    it when it starts; child processes inherit it). Called at import of this module.

    Returns
    -------
    bool
        Whether the variable was set.
    """
    from numba.np.ufunc import parallel

    if any(v in os.environ for v in WAIT_VARIABLES) or getattr(parallel, "_is_initialized", True):
        return False
    os.environ["OMP_WAIT_POLICY"] = "passive"
    return True


passive_wait()


@njit(cache=True, parallel=True, nogil=True)
def _chunked(
    bounds, X, start, goal, t0, speed, spacetime, obs, snap, motion, horizon, weights, box, out,
    buf, min_movers, by_cells,
):  # fmt: skip
    """:func:`~mawdo.planning.refine.kernel.population.fused_population_cost` on rows
    ``bounds[j]:bounds[j + 1]`` for every ``j`` at once, chunk ``j`` working in row ``j`` of
    ``buf``."""
    cost, length, ncol, turn = out
    for j in prange(bounds.shape[0] - 1):
        lo = bounds[j]
        hi = bounds[j + 1]
        part = (cost[lo:hi], length[lo:hi], ncol[lo:hi], turn[lo:hi])
        fused_population_cost(
            X[lo:hi], start, goal, t0, speed, spacetime, obs, snap, motion, horizon, weights, box,
            part, buf[j], min_movers, by_cells,
        )  # fmt: skip


def chunk_bounds(n: int, threads: int) -> np.ndarray:
    """Row boundaries ``[0, ..., n]`` of the chunks: as even as rows allow, at most
    ``threads`` chunks and at least :data:`MIN_ROWS` rows in each (one chunk below that)."""
    k = max(1, min(threads, n // MIN_ROWS))
    return np.array([(j * n) // k for j in range(k + 1)], dtype=np.int64)


def index_choice(nk: np.ndarray, spacetime: bool) -> tuple:
    """The indexes the kernel uses in a world whose obstacles have ``nk`` motion knots each
    (``> 1``: moving in spacetime mode), as the ``(min_movers, by_cells)`` arguments of
    :func:`~mawdo.planning.refine.kernel.population.fused_population_cost`: neither below
    :data:`INDEX_MOVERS` moving and :data:`INDEX_STANDING` standing obstacles, the moving index
    from :data:`INDEX_MOVERS` movers on, and the standing obstacles' grid too from
    :data:`INDEX_STANDING` standing ones on.

    All give the same numbers, bit for bit; a world below both thresholds compiles neither
    index (about a fifth of the kernel's compile)."""
    moving = int(np.count_nonzero(nk > 1)) if spacetime else 0
    if len(nk) - moving >= INDEX_STANDING:
        return INDEX_MOVERS, True
    return (INDEX_MOVERS, None) if moving >= INDEX_MOVERS else (None, None)


@dataclass(slots=True)
class _Plan:
    """How :class:`ThreadedKernel` calls one population size under one motion table: the
    table's knot counts (its identity), the chunk bounds, the scratch floats a chunk and the
    whole call need, the indexes (:func:`index_choice`), and whether to split (None: not yet
    timed)."""

    nk: np.ndarray
    bounds: np.ndarray
    part: int
    whole: int
    indexes: tuple
    split: bool | None


class ThreadedKernel:
    """Calls the population cost (:func:`~mawdo.planning.refine.kernel.population
    .fused_population_cost` with the indexes the world needs, :func:`index_choice`) on chunks
    of rows in parallel, keeping the scratch space from call to call.

    Parameters
    ----------
    threads : int
        Chunks a call is split into, >= 1; they run on up to that many of Numba's threads
        (``numba.get_num_threads()``, the number of cores unless set lower).
    """

    def __init__(self, threads: int = 1, clock=time.thread_time) -> None:
        self.threads = check_int(
            "threads", threads, 1, what="an integer >= 1 (1: the calling thread only)"
        )
        self._clock = clock
        self._buf = np.empty((0, 0))
        # a _Plan per population size (a new motion table brings a new one); a planner
        # alternates a few sizes (populations, one-candidate guard checks), so all are kept
        self._plans: dict = {}

    def _scratch(self, rows: int, need: int) -> np.ndarray:
        if self._buf.shape[0] < rows or self._buf.shape[1] < need:
            # a whole number of 4 KiB pages per row (the kernel lays its arrays out within a
            # page), and a quarter more, so that slightly larger populations do not reallocate
            cols = (need + need // 4 + 511) // 512 * 512
            self._buf = np.empty((rows, cols))
        return self._buf

    def _plan(self, n: int, npts: int, spacetime: bool, nk: np.ndarray) -> _Plan:
        key = (n, npts, spacetime)
        plan = self._plans.get(key)
        if plan is None or plan.nk is not nk:
            if len(self._plans) >= 16:  # (sizes seen long ago)
                self._plans.clear()
            bounds = chunk_bounds(n, self.threads)
            k = bounds.size - 1
            whole = scratch_size(n, npts, nk, spacetime)
            part = scratch_size(-(-n // k), npts, nk, spacetime) if k > 1 else whole
            split = None if k > 1 else False  # a call that cannot be split is never timed
            plan = _Plan(nk, bounds, part, whole, index_choice(nk, spacetime), split)
            self._plans[key] = plan
        return plan

    def __call__(
        self, X, start, goal, t0, speed, spacetime, obs, snap, motion, horizon, weights, box, out
    ):
        """Fill ``out = (cost, length, n_collisions, turning)`` for the rows of ``X``; the
        arguments are those of :func:`population_cost` without the scratch buffer.

        With ``threads > 1`` the first call of each population size under a motion table runs
        on the calling thread and is timed (the thread's CPU time, which other processes do not
        inflate); the rest of that size and table run in chunks when it took
        :data:`PARALLEL_SECONDS` or more. The numbers are the same either way."""
        plan = self._plan(X.shape[0], X.shape[1] // 2 + 2, spacetime, motion[3])
        args = (X, start, goal, t0, speed, spacetime, obs, snap, motion, horizon, weights, box, out)
        if not plan.split:
            timed = plan.split is None
            t = self._clock() if timed else 0.0
            fused_population_cost(*args, self._scratch(1, plan.whole)[0], *plan.indexes)
            if timed:
                plan.split = self._clock() - t >= PARALLEL_SECONDS
            return
        buf = self._scratch(plan.bounds.size - 1, plan.part)
        with _lock:
            _chunked(plan.bounds, *args, buf, *plan.indexes)
