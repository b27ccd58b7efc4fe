"""L-SHADE (Tanabe & Fukunaga, CEC 2014) and jSO (Brest, Maucec & Boskovic, CEC 2017).

One implementation of the authors' C++ codes (Tanabe's ``lshade.cc`` 1.1; Brest's jSO, which
edits it), batched over runs and individuals; ``rules="jso"`` switches on jSO's changes. A
generation, per individual ``i`` of ``N`` (0-based, ``nfes`` counted at the generation's start,
``M`` the evaluation budget):

    r ~ U{0..H-1};  (mu_F, mu_CR) = (M_F[r], M_CR[r])   (jSO: (0.9, 0.9) when r = H - 1)
    CR_i = 0 if mu_CR is terminal (L-SHADE: -1; jSO: < 0) else clip(N(mu_CR, 0.1), 0, 1)
    F_i ~ Cauchy(mu_F, 0.1) redrawn until > 0, capped at 1
    jSO: CR_i >= 0.7 while nfes < M/4, >= 0.6 while nfes < M/2; F_i <= 0.7 while nfes < 0.6 M
    v_i = x_i + Fw_i (x_pbest - x_i) + F_i (x_r1 - x~_r2)     (current-to-pbest/1)
      Fw_i = F_i (L-SHADE); jSO: 0.7 F_i, 0.8 F_i, 1.2 F_i for nfes < 0.2 M, < 0.4 M, after
      pbest uniform among the p_num best (jSO: not i while nfes < M/2); r1 != i in the
      population; r2 != i, r1 in the population and archive together
    u_ij = v_ij if U_ij < CR_i or j = j_rand, else x_ij; outside the box: (bound + x_ij) / 2

then selection (``u_i`` replaces ``x_i`` when not worse; a strictly better ``u_i`` sends ``x_i``
to the archive and ``(F_i, CR_i, |f(x_i) - f(u_i)|)`` to the success lists), the memory update
at position ``k`` (weighted Lehmer means; L-SHADE's ``M_CR = -1`` when every
successful ``CR`` is 0; jSO averages the new and the old value), ``k = (k + 1) mod H`` after a
generation with successes, and the linear population size reduction with the archive
cut to ``int(N * arc_rate)`` members (the first ones) and ``p_num = max(2, round(N p))`` (jSO:
``p = p_max (1 - nfes / 2M)``).

The population size changes with ``nfes`` alone, and every run of a batch counts the same
evaluations, so the runs shrink in lock-step and the arrays stay ``(R, N, D)``.
See docs/algorithms.md#lshade and docs/deviations.md#d-shade.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass

import numpy as np

from mawdo.optimizers import shade_ops as ops
from mawdo.optimizers.base import Optimizer, Params, Space, initial_population, option
from mawdo.streams import RunStreams

N_MIN = 4  # the codes' min_pop_size


@dataclass(frozen=True)
class ShrinkingParams(Params):
    """The initial population size of a shrinking DE.

    Parameters
    ----------
    pop_size : int
        Initial population size ``N_0``, >= 4, used when ``auto_pop_size`` is false (passing
        ``pop_size`` alone turns it off).
    auto_pop_size : bool
        Size the initial population from the dimension ``D`` by the authors' rule.
    """

    pop_size: int = option(50, lo=4)
    auto_pop_size: bool = True


@dataclass(frozen=True)
class LShadeParams(ShrinkingParams):
    """L-SHADE / jSO coefficients (defaults: Tanabe's L-SHADE; the ``jso`` entry presets jSO's);
    ``pop_size`` and ``auto_pop_size``: :class:`ShrinkingParams`.

    Parameters
    ----------
    size_rule : {"18D", "25sqrtDlnD"}
        L-SHADE's ``round(18 D)`` or jSO's ``round(25 sqrt(D) ln(D))`` (at least 4).
    memory_size : int
        Entries H of the success-history memories, >= 1 (L-SHADE 6, jSO 5).
    arc_rate : float
        Archive size as a multiple of the population size, >= 0 (2.6; jSO 1).
    p_best : float
        Share p of the population that ``pbest`` is drawn from, in (0, 1] (0.11; jSO's
        ``p_max`` 0.25, falling to 0.125).
    memory_f, memory_cr : float
        Initial memory entries (0.5, 0.5; jSO 0.3, 0.8).
    rules : {"lshade", "jso"}
        ``"jso"``: the fixed (0.9, 0.9) last memory entry, the phase limits on CR and F, the
        weighted pbest step, pbest != i in the first half, the falling p, and the memory
        averaged with its old value.
    """

    size_rule: str = option("18D", choices=("18D", "25sqrtDlnD"))
    memory_size: int = option(6, lo=1)
    arc_rate: float = option(2.6, lo=0)
    p_best: float = option(0.11, lo=0, hi=1, lo_open=True)
    memory_f: float = option(0.5, lo=0, hi=1, lo_open=True)
    memory_cr: float = option(0.5, lo=0, hi=1)
    rules: str = option("lshade", choices=("lshade", "jso"))


def initial_size(rule: str, dim: int) -> int:
    """The authors' initial population size for dimension ``dim``."""
    if rule == "18D":
        return max(N_MIN, ops.c_round(dim * 18.0))
    return max(N_MIN, ops.c_round(math.sqrt(dim) * math.log(dim) * 25)) if dim > 1 else N_MIN


def generations(max_nfes: int, n_init: int, reduce) -> int:
    """Iterations (the initial population is the first) that a run of ``max_nfes`` evaluations
    takes under the size schedule ``reduce(nfes, max_nfes, n)`` -> next size."""
    nfes, n, g = n_init, n_init, 1
    while nfes < max_nfes:
        nfes += n
        n = reduce(nfes, max_nfes, n)
        g += 1
    return g


def plan_evaluations(budget, n_init: int, reduce) -> int:
    """The evaluation budget a run plans its schedules over: ``max_evals`` when set, else the
    least budget whose schedule lasts ``max_iter`` iterations (the smaller when both are set)."""
    planned = None
    if budget.max_iter is not None:
        lo, hi = 1, budget.max_iter * n_init  # hi lasts at least max_iter iterations
        while lo < hi:
            mid = (lo + hi) // 2
            if generations(mid, n_init, reduce) >= budget.max_iter:
                hi = mid
            else:
                lo = mid + 1
        planned = hi
    if budget.max_evals is not None:
        planned = budget.max_evals if planned is None else min(planned, budget.max_evals)
    return planned


def next_size(nfes: int, max_nfes: int, n: int, n_init: int) -> int:
    """The population size after a generation that ended at ``nfes`` (sizes only fall)."""
    return min(n, ops.lpsr_size(nfes, max_nfes, n_init, N_MIN))


@dataclass
class ShadeState:
    """The arrays every member of the family keeps (``R`` runs, ``N`` members, ``D``)."""

    X: np.ndarray  # (R, N, D) population
    F: np.ndarray  # (R, N) its values
    archive: np.ndarray  # (R, cap, D)
    n_arc: np.ndarray  # (R,) members in each run's archive
    arc_size: int  # the archive's size limit, the same for every run
    MF: np.ndarray  # (R, H) success-history memories
    MCR: np.ndarray
    k: np.ndarray  # (R,) memory position
    nfes: int  # evaluations so far, the same for every run
    max_nfes: int
    n_init: int
    space: Space
    streams: RunStreams


@dataclass
class LShadeState(ShadeState):
    p_num: int = 2
    trial: np.ndarray | None = None  # the generation's trial vectors, F_i, CR_i, slot draws
    Fi: np.ndarray | None = None
    CRi: np.ndarray | None = None
    u_slot: np.ndarray | None = None


class ShrinkingDE(Optimizer):
    """What the success-history DE family shares around its generations: the initial size from
    ``D`` (or an explicit ``pop_size``), the evaluation budget its schedules plan over
    (:meth:`horizon`), the size schedule ``next_size`` and the initial population's ``tell``."""

    shrinking = True
    next_size = staticmethod(next_size)

    def __init__(self, params: Params | None = None, name: str | None = None, **options) -> None:
        if params is None and "pop_size" in options and "auto_pop_size" not in options:
            options["auto_pop_size"] = False  # an explicit population size means that size
        super().__init__(params, name, **options)

    def auto_size(self, dim: int) -> int:  # pragma: no cover - every subclass defines it
        raise NotImplementedError

    def initial_size(self, dim: int) -> int:
        """``N_0`` in dimension ``dim``: the authors' rule, or ``pop_size`` when it was given."""
        return self.auto_size(dim) if self.params.auto_pop_size else self.params.pop_size

    def horizon(self, budget, dim: int) -> int:
        """The evaluation budget ``M`` the schedules run over (see :func:`plan_evaluations`)."""
        n0 = self.initial_size(dim)
        return plan_evaluations(budget, n0, lambda nfes, m, n: self.next_size(nfes, m, n, n0))

    def start(self, space: Space, streams: RunStreams, x0) -> np.ndarray:
        """The initial population ``(R, N_0, D)``; ``params.pop_size`` becomes ``N_0``."""
        n0 = self.initial_size(space.dim)
        if self.params.auto_pop_size:  # reported in the result's params
            self.params = dataclasses.replace(self.params, pop_size=n0)
        return initial_population(streams, n0, space.lb, space.ub, x0)

    @staticmethod
    def told_initial(state, F: np.ndarray) -> bool:
        """Take the initial population's values (True) unless a generation was told."""
        if state.nfes:
            return False
        state.F = F.copy()
        state.nfes = F.shape[1]
        return True


class LShade(ShrinkingDE):
    """L-SHADE and jSO (``rules``), vectorised over runs and individuals; see the module."""

    name = "lshade"
    params_class = LShadeParams

    def auto_size(self, dim: int) -> int:
        return initial_size(self.params.size_rule, dim)

    def init(self, space: Space, streams: RunStreams, max_iter: int, x0=None) -> LShadeState:
        """``max_iter`` is the evaluation budget ``M`` from :meth:`horizon`."""
        p, R, D = self.params, streams.runs, space.dim
        X = self.start(space, streams, x0)
        n0 = X.shape[1]
        arc = ops.c_round(n0 * p.arc_rate)
        H = p.memory_size
        return LShadeState(
            X=X,
            F=np.full((R, n0), np.inf),
            archive=np.zeros((R, max(arc, 1), D)),
            n_arc=np.zeros(R, np.int64),
            arc_size=arc,
            MF=np.full((R, H), p.memory_f),
            MCR=np.full((R, H), p.memory_cr),
            k=np.zeros(R, np.int64),
            nfes=0,
            max_nfes=max(int(max_iter), 1),
            n_init=n0,
            p_num=max(1, ops.c_round(n0 * p.p_best)),
            space=space,
            streams=streams,
        )

    def ask(self, state: LShadeState) -> np.ndarray:
        """The initial population, then one generation of trial vectors ``(R, N, D)``."""
        if state.nfes == 0:
            return state.X
        N, D = state.X.shape[1:]
        # one call per run for every uniform of the generation, then the CR normals
        u_mem, u_f, u_pb, u_r1, u_r2, u_j, u_cr, state.u_slot = state.streams.random_parts(
            (N,), (N,), (N,), (N,), (N,), (N,), (N, D), (N,)
        )
        z = state.streams.normal((N,))
        state.Fi, state.CRi = self._parameters(state, u_mem, u_f, z)
        x_pb, x_r1, x_r2 = self._donors(state, u_pb, u_r1, u_r2)
        X = state.X
        v = X + self._pbest_weight(state)[..., None] * (x_pb - X)  # the codes' order of operations
        v += state.Fi[..., None] * (x_r1 - x_r2)
        j_rand = np.minimum((u_j * D).astype(np.int64), D - 1)
        cross = (u_cr < state.CRi[..., None]) | (np.arange(D) == j_rand[..., None])
        trial = np.where(cross, v, X)
        state.trial = ops.midpoint_bounds(trial, X, state.space.lb, state.space.ub)
        return state.trial

    def _parameters(self, state: LShadeState, u_mem, u_f, z) -> tuple[np.ndarray, np.ndarray]:
        """Each individual's ``(F_i, CR_i)`` from a random memory entry (and jSO's rules)."""
        H, jso = self.params.memory_size, self.params.rules == "jso"
        r = np.minimum((u_mem * H).astype(np.int64), H - 1)
        mu_f = np.take_along_axis(state.MF, r, 1)
        mu_cr = np.take_along_axis(state.MCR, r, 1)
        if jso:  # the last entry stands for (0.9, 0.9); it is still updated, never read
            mu_f = np.where(r == H - 1, 0.9, mu_f)
            mu_cr = np.where(r == H - 1, 0.9, mu_cr)
        terminal = mu_cr < 0 if jso else mu_cr == -1
        CR = np.where(terminal, 0.0, np.clip(mu_cr + 0.1 * z, 0.0, 1.0))
        F = np.minimum(ops.truncated_cauchy(mu_f, u_f), 1.0)
        if jso:
            nfes, M = state.nfes, state.max_nfes
            if nfes < 0.25 * M:
                CR = np.maximum(CR, 0.7)
            if nfes < 0.5 * M:
                CR = np.maximum(CR, 0.6)
            if nfes < 0.6 * M:
                F = np.minimum(F, 0.7)
        return F, CR

    def _pbest_weight(self, state: LShadeState) -> np.ndarray:
        """``F_i`` (L-SHADE) or jSO's ``F_w``: 0.7, 0.8 or 1.2 times ``F_i`` by phase."""
        if self.params.rules != "jso":
            return state.Fi
        nfes, M = state.nfes, state.max_nfes
        return state.Fi * (0.7 if nfes < 0.2 * M else 0.8 if nfes < 0.4 * M else 1.2)

    def _donors(self, state: LShadeState, u_pb, u_r1, u_r2):
        """``x_pbest``, ``x_r1`` and ``x~_r2`` (population or archive) of every individual."""
        X, F, A = state.X, state.F, state.archive
        R, N = F.shape
        order = np.argsort(F, axis=1, kind="stable")  # the codes' quicksort, ties aside
        p = state.p_num
        k = np.minimum((u_pb * p).astype(np.int64), p - 1)
        if self.params.rules == "jso" and state.nfes < 0.5 * state.max_nfes and p >= 2:
            rank = np.argsort(order, axis=1)  # do pbest = ... while (pbest == i)
            k = np.where(rank < p, ops.index_excluding(u_pb, p, np.minimum(rank, p - 1)), k)
        pbest = np.take_along_axis(order, k, 1)
        me = np.broadcast_to(np.arange(N), (R, N))
        r1 = ops.index_excluding(u_r1, N, me)
        r2 = ops.index_excluding(u_r2, N + state.n_arc[:, None], me, r1)
        from_pop = ops.gather(X, np.minimum(r2, N - 1))
        from_arc = ops.gather(A, np.clip(r2 - N, 0, A.shape[1] - 1))
        x_r2 = np.where((r2 < N)[..., None], from_pop, from_arc)
        return ops.gather(X, pbest), ops.gather(X, r1), x_r2

    def tell(self, state: LShadeState, X: np.ndarray, F: np.ndarray) -> LShadeState:
        if self.told_initial(state, F):
            return state
        N = state.X.shape[1]
        better, delta = self._select(state, F)
        state.nfes += N
        self._update_memory(state, better, delta)
        self._reduce(state)
        return state

    def _select(self, state: LShadeState, Fc: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Generation alternation: archive the parents that a strictly better trial replaces,
        keep every trial that is not worse. Returns the strict successes ``(R, N)`` and the
        improvements ``|f(x_i) - f(u_i)|``."""
        better = Fc < state.F
        replace = better | (Fc == state.F)
        size = state.arc_size if state.arc_size > 1 else 0  # the codes' "if (arc_size > 1)"
        state.n_arc = ops.archive_insert(
            state.archive, state.n_arc, size, state.X, better, state.u_slot
        )
        with np.errstate(invalid="ignore"):
            delta = np.abs(state.F - Fc)
        state.X = np.where(replace[..., None], state.trial, state.X)
        state.F = np.where(replace, Fc, state.F)
        return better, delta

    def _update_memory(self, state: LShadeState, better, delta) -> None:
        """Weighted Lehmer means of the successful ``F_i`` and ``CR_i`` into entry ``k`` of
        each run with a success (jSO: averaged with the old entry)."""
        rows = better.any(axis=1)
        if not rows.any():
            return
        w = ops.lehmer_weights(delta[rows], better[rows])
        f2, f1 = ops.lehmer_terms(state.Fi[rows], w)
        c2, c1 = ops.lehmer_terms(state.CRi[rows], w)
        with np.errstate(invalid="ignore", divide="ignore"):
            mf = f2 / f1
            mcr = np.where(c1 == 0, -1.0, c2 / c1)
        k = state.k[rows]
        idx = np.flatnonzero(rows)
        if self.params.rules == "jso":
            mf = (mf + state.MF[idx, k]) / 2.0
            mcr = (mcr + state.MCR[idx, k]) / 2.0
        state.MF[idx, k] = mf
        state.MCR[idx, k] = mcr
        state.k[idx] = (k + 1) % self.params.memory_size

    def _reduce(self, state: LShadeState) -> None:
        """Linear population size reduction, with the archive and ``p_num`` resized."""
        p, N = self.params, state.X.shape[1]
        plan = ops.c_round(
            ((N_MIN - state.n_init) / float(state.max_nfes)) * state.nfes + state.n_init
        )
        if N <= plan:
            return
        new = max(plan, N_MIN)
        if new < N:
            keep = ops.keep_best(state.F, new)
            state.X = ops.gather(state.X, keep)
            state.F = np.take_along_axis(state.F, keep, 1)
        state.arc_size = int(new * p.arc_rate)
        state.n_arc = np.minimum(state.n_arc, state.arc_size)
        rate = p.p_best
        if p.rules == "jso":
            rate = p.p_best * (1.0 - 0.5 * state.nfes / float(state.max_nfes))
        state.p_num = max(2, ops.c_round(new * rate))
