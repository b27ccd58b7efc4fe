"""NL-SHADE-RSP (Stanovov, Akhmedova & Semenkin, CEC 2021), as the authors' C++ code runs it.

Batched over runs and individuals. A generation (``N`` members ranked by value, ``nfes``
counted at its start, ``M`` the evaluation budget, ``x_(k)`` the member of rank ``k``):

    ps = int(max(2, N (0.2 nfes / M + 0.2)))                (pbest share 0.2 -> 0.4)
    exponential crossover for the whole generation with probability 1/2, else binomial
    r ~ U{0..H-1};  CR ~ clip(N(M_CR[r], 0.1), 0, 1);  F_i ~ Cauchy(M_F[r], 0.1) until > 0,
      capped at 1; the N CRs sorted ascending, the member of rank k takes the k-th
    pbest uniform among the ps best, r1 uniform in the population (each redrawn up to 25
      times while it repeats i, resp. pbest); r2 from the archive with probability p_A (when
      it is not empty), else by rank with weights exp(-k / N) (redrawn up to 25 times while
      it repeats i, pbest or r1)
    v_i = x_i + F_i (x_pbest - x_i) + F_i (x_r1 - x_r2)
    binomial: u_ij = v_ij if U < CR_b or j = j_rand, CR_b = 0 before M/2, then 2 (nfes_i / M
      - 1/2) with nfes_i the evaluations made before u_i; exponential: from a random start, a
      run of coordinates while U < CR_i (no wrap-around)
    a coordinate outside the box is redrawn uniformly in the box

Selection keeps ``u_i`` when ``f(u_i) <= f(x_i)`` and archives ``x_i``; strict improvements
feed the memories (weighted Lehmer means; no success: the entry is reset to 0.5, the position
kept). ``p_A`` follows the mean relative improvement ``(f(x) - f(u)) / f(x)`` of the archive
users against the others (clipped to [0.1, 0.9]; 0.5 when undefined). The population shrinks
non-linearly, ``N = round((4 - N_0) x^(1 - x) + N_0)``, ``x = nfes / M``, the archive to
``2.1 N``. Two details of the code are kept by default and switchable: every success stores
the last generated ``F`` of the generation (``success_f="last"``), and the removal of the worst
members scans a stale copy of the last one (``removal="code"``). See
docs/algorithms.md#nlshade-rsp and docs/deviations.md#d-shade.
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass

import numpy as np

from mawdo.optimizers import shade_ops as ops
from mawdo.optimizers.base import Space, option
from mawdo.optimizers.lshade import ShadeState, ShrinkingDE, ShrinkingParams
from mawdo.streams import RunStreams
from mawdo.util import libm

N_MIN = 4  # NIndsMin
TRIES = 25  # the code's retry limit


@dataclass(frozen=True)
class NLShadeRSPParams(ShrinkingParams):
    """NL-SHADE-RSP coefficients (the authors' CEC 2021 settings); ``pop_size`` and
    ``auto_pop_size`` (the authors' ``30 D``): :class:`~mawdo.optimizers.lshade.ShrinkingParams`.

    Parameters
    ----------
    memory_size : int
        Memory entries H, >= 0; 0 (default) means the authors' ``20 D``.
    arc_rate : float
        Archive size as a multiple of the population size, >= 0 (2.1).
    memory_init : float
        Initial ``M_F`` and ``M_CR`` entries (0.2).
    success_f : {"last", "own"}
        The ``F`` a success stores: ``"last"`` (the code) the generation's last generated ``F``
        for every success, ``"own"`` the member's own ``F_i`` (as the paper describes).
    removal : {"code", "worst"}
        ``"code"``: the code's removal loop (it rescans the population with a stale copy of the
        last member); ``"worst"``: the worst members are removed.
    """

    memory_size: int = option(0, lo=0)
    arc_rate: float = option(2.1, lo=0)
    memory_init: float = option(0.2, lo=0, hi=1, lo_open=True)
    success_f: str = option("last", choices=("last", "own"))
    removal: str = option("code", choices=("code", "worst"))


def next_size(nfes: int, max_nfes: int, n: int, n_init: int) -> int:
    """The population size after a generation that ended at ``nfes`` (sizes only fall)."""
    return min(n, ops.nonlinear_size(nfes, max_nfes, n_init, N_MIN)[0])


def remove_worst_as_coded(X: np.ndarray, F: np.ndarray, n_new: int):
    """The code's ``RemoveWorst(NInds, NewNInds)``: ``NInds - NewNInds`` times, find the first
    largest of all ``NInds`` values and shift the later members down one place, the last
    place keeping its old (now duplicated) member; then keep the first ``n_new``."""
    N = F.shape[1]
    j = np.arange(N)
    for _ in range(N - n_new):
        w = np.argmax(F, axis=1)[:, None]
        idx = np.where((j >= w) & (j < N - 1), j + 1, j)
        F = np.take_along_axis(F, idx, 1)
        X = ops.gather(X, idx)
    return X[:, :n_new], F[:, :n_new]


@dataclass
class NLShadeRSPState(ShadeState):
    p_arc: np.ndarray | None = None  # (R,) probability of taking r2 from the archive
    gen: dict = dataclasses.field(default_factory=dict)  # this generation's trial and draws


class NLShadeRSP(ShrinkingDE):
    """NL-SHADE-RSP, vectorised over runs and individuals; see the module docstring."""

    name = "nlshade_rsp"
    params_class = NLShadeRSPParams
    next_size = staticmethod(next_size)

    def auto_size(self, dim: int) -> int:
        return max(N_MIN, 30 * dim)

    def init(self, space: Space, streams: RunStreams, max_iter: int, x0=None) -> NLShadeRSPState:
        """``max_iter`` is the evaluation budget ``M`` from :meth:`horizon`."""
        p, R, D = self.params, streams.runs, space.dim
        X = self.start(space, streams, x0)
        n0 = X.shape[1]
        H = p.memory_size or 20 * D
        arc = int(n0 * p.arc_rate)
        return NLShadeRSPState(
            X=X,
            F=np.full((R, n0), np.inf),
            archive=np.zeros((R, max(arc, N_MIN), D)),
            n_arc=np.zeros(R, np.int64),
            arc_size=arc,
            MF=np.full((R, H), p.memory_init),
            MCR=np.full((R, H), p.memory_init),
            k=np.zeros(R, np.int64),
            p_arc=np.full(R, 0.5),
            nfes=0,
            max_nfes=max(int(max_iter), 1),
            n_init=n0,
            space=space,
            streams=streams,
        )

    def ask(self, state: NLShadeRSPState) -> np.ndarray:
        """The initial population, then one generation of trial vectors ``(R, N, D)``."""
        if state.nfes == 0:
            return state.X
        N, D = state.X.shape[1:]
        parts = state.streams.random_parts(
            (1,), (N,), (N,), (N,), (N,), (N,), (N,), (N,), (N,), (N, D), (N, D), (N,)
        )
        u_exp, u_mem, u_f, u_pb, u_r1, u_arc, u_r2, u_j, u_start, u_cr, u_box, u_slot = parts
        z = state.streams.normal((N,))
        order = np.argsort(state.F, axis=1, kind="stable")
        rank = np.argsort(order, axis=1)
        F_i, CR_i, F_last = self._parameters(state, rank, u_mem, u_f, z)
        x_pb, x_r1, x_r2, used = self._donors(state, order, rank, u_pb, u_r1, u_arc, u_r2)
        X = state.X
        v = X + F_i[..., None] * (x_pb - X)
        v += F_i[..., None] * (x_r1 - x_r2)
        cross = self._crossover(state, CR_i, u_exp[:, 0] < 0.5, u_j, u_start, u_cr)
        trial = np.where(cross, v, X)
        lb, ub = state.space.lb, state.space.ub
        out = (trial < lb) | (trial > ub)
        trial = np.where(out, u_box * (ub - lb) + lb, trial)  # FindLimits: Random(Left, Right)
        F_store = F_i if self.params.success_f == "own" else np.broadcast_to(F_last, F_i.shape)
        state.gen = {"trial": trial, "CR": CR_i, "F": F_store, "used": used, "u_slot": u_slot}
        return trial

    def _parameters(self, state, rank, u_mem, u_f, z):
        """``F_i``, the rank-sorted ``CR_i`` and the generation's last raw ``F``."""
        H = state.MF.shape[1]
        r = np.minimum((u_mem * H).astype(np.int64), H - 1)
        CR = np.clip(np.take_along_axis(state.MCR, r, 1) + 0.1 * z, 0.0, 1.0)
        F_raw = ops.truncated_cauchy(np.take_along_axis(state.MF, r, 1), u_f)
        CR_sorted = np.sort(CR, axis=1)  # qSort1(CrGenerated): the best member gets the least
        return np.minimum(F_raw, 1.0), np.take_along_axis(CR_sorted, rank, 1), F_raw[:, -1:]

    def _donors(self, state, order, rank, u_pb, u_r1, u_arc, u_r2):
        """``x_pbest, x_r1, x_r2`` and whether ``r2`` came from the archive, with the code's
        capped retries (:func:`~mawdo.optimizers.shade_ops.weighted_capped`'s law)."""
        N = state.F.shape[1]
        ps = int(max(2.0, N * (0.2 / float(state.max_nfes) * float(state.nfes) + 0.2)))
        pb_rank = uniform_capped(u_pb, ps, np.where(rank < ps, rank, -1), TRIES + 1)
        pbest = np.take_along_axis(order, pb_rank, 1)
        r1 = uniform_capped(u_r1, N, pbest, TRIES)
        use_arc = (u_arc <= state.p_arc[:, None]) & (state.n_arc[:, None] > 0)
        excluded = [rank, np.take_along_axis(rank, pbest, 1), np.take_along_axis(rank, r1, 1)]
        r2 = np.take_along_axis(order, rank_capped(u_r2, N, excluded, TRIES + 1), 1)
        a2 = np.minimum((u_r2 * state.n_arc[:, None]).astype(np.int64), state.n_arc[:, None] - 1)
        from_arc = ops.gather(state.archive, np.maximum(a2, 0))
        x_r2 = np.where(use_arc[..., None], from_arc, ops.gather(state.X, r2))
        return ops.gather(state.X, pbest), ops.gather(state.X, r1), x_r2, use_arc

    def _crossover(self, state, CR_i, exponential, u_j, u_start, u_cr) -> np.ndarray:
        """The generation's crossover masks ``(R, N, D)`` (binomial or exponential per run)."""
        R, N = CR_i.shape
        D = u_cr.shape[2]
        j = np.arange(D)
        # binomial: CR rises from 0 after half the budget, counted before each evaluation
        at = state.nfes + np.arange(N)
        cr_b = np.where(at > 0.5 * state.max_nfes, (at / float(state.max_nfes) - 0.5) * 2, 0.0)
        j_rand = np.minimum((u_j * D).astype(np.int64), D - 1)
        binomial = (u_cr < cr_b[:, None]) | (j == j_rand[..., None])
        # exponential: L grows while a fresh U < CR_i, up to the last coordinate
        start = np.minimum((u_start * D).astype(np.int64), D - 1)
        run = np.cumprod(u_cr[..., : D - 1] < CR_i[..., None], axis=2).sum(axis=2)
        stop = start + 1 + np.minimum(run, D - 1 - start)
        expo = (j >= start[..., None]) & (j < stop[..., None])
        return np.where(exponential[:, None, None], expo, binomial)

    def tell(self, state: NLShadeRSPState, X: np.ndarray, F: np.ndarray) -> NLShadeRSPState:
        if self.told_initial(state, F):
            return state
        N = state.X.shape[1]
        g, Fp = state.gen, state.F
        success = F < Fp  # SaveSuccessCrF: strict
        accepted = F <= Fp  # replacement and archive: not worse
        with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
            delta = np.abs(Fp - F)
            gain = (Fp - F) / Fp
        state.p_arc = archive_probability(gain, accepted, g["used"])
        size = state.arc_size if state.arc_size > 0 else 0
        state.n_arc = ops.archive_insert(state.archive, state.n_arc, size, state.X, accepted,
                                         g["u_slot"])  # fmt: skip
        state.X = np.where(accepted[..., None], g["trial"], state.X)
        state.F = np.where(accepted, F, Fp)
        state.nfes += N
        self._reduce(state)
        self._update_memory(state, success, delta, g["CR"], g["F"])
        state.gen = {}
        return state

    def _reduce(self, state: NLShadeRSPState) -> None:
        N = state.X.shape[1]
        new, raw = ops.nonlinear_size(state.nfes, state.max_nfes, state.n_init, N_MIN)
        new = min(new, N)  # past the planned budget the code's size would grow again
        arc = max(int(raw * self.params.arc_rate), N_MIN)
        state.arc_size = min(arc, state.archive.shape[1])
        state.n_arc = np.minimum(state.n_arc, state.arc_size)
        if new == N:
            return
        if self.params.removal == "code":
            state.X, state.F = remove_worst_as_coded(state.X, state.F, new)
        else:
            keep = ops.keep_best(state.F, new)
            state.X, state.F = ops.gather(state.X, keep), np.take_along_axis(state.F, keep, 1)

    def _update_memory(self, state, success, delta, CR, F) -> None:
        """``MeanWL_general``: weighted Lehmer means (0.5 where ``|sum w v| <= 1e-6``) into
        entry ``k`` of each run with a success; a run without one resets entry ``k`` to 0.5."""
        rows = success.any(axis=1)
        idx = np.flatnonzero(rows)
        k = state.k[idx]
        if idx.size:
            w = ops.lehmer_weights(delta[rows], success[rows])
            for M, values in ((state.MCR, CR), (state.MF, F)):
                v2, v1 = ops.lehmer_terms(np.asarray(values)[rows], w, square_first=True)
                with np.errstate(invalid="ignore", divide="ignore"):
                    M[idx, k] = np.where(np.abs(v1) > 0.000001, v2 / v1, 0.5)
            state.k[idx] = (k + 1) % state.MF.shape[1]
        none = np.flatnonzero(~rows)
        state.MF[none, state.k[none]] = 0.5
        state.MCR[none, state.k[none]] = 0.5


def archive_probability(gain, accepted, used) -> np.ndarray:
    """The code's ``ArchProbs`` update per run from the relative gains ``(f(x) - f(u)) / f(x)``
    of the accepted trials, split by whether ``r2`` came from the archive (``used``).

    ``NArchUsages`` counts the accepted archive users only, and the other mean divides by
    ``N - NArchUsages``; C++'s ``min``/``max`` return their first argument on NaN.
    """
    N = gain.shape[1]
    arc, rest = accepted & used, accepted & ~used
    n_arc = arc.sum(axis=1)
    with np.errstate(invalid="ignore", divide="ignore"):
        a = ops.seqsum(np.where(arc, gain, 0.0)) / np.where(n_arc > 0, n_arc, 1)
        b = ops.seqsum(np.where(rest, gain, 0.0)) / (N - n_arc)
        p = a / (a + b)
    p = np.where(p < 0.9, p, 0.9)  # std::min(0.9, p)
    p = np.where(0.1 < p, p, 0.1)  # std::max(0.1, p)
    p = np.where(a == 0, 0.5, p)
    return np.where(n_arc > 0, p, 0.5)


def uniform_capped(u, n: int, excluded, draws: int) -> np.ndarray:
    """An index uniform on ``0..n-1`` redrawn while it equals ``excluded`` (``-1``: nothing is
    excluded), ``draws`` draws at most: :func:`~mawdo.optimizers.shade_ops.weighted_capped`'s
    law for equal weights, in closed form."""
    has = excluded >= 0
    c = np.where(has, (1.0 / n) ** draws, 0.0)
    inside = u < c
    v = (u - c) / (1.0 - c)
    free = np.minimum((v * n).astype(np.int64), n - 1)
    k = np.where(has, ops.index_excluding(v, n, np.maximum(excluded, 0)), free)
    return np.where(inside, excluded, k)


def rank_capped(u, N: int, excluded: list, draws: int) -> np.ndarray:
    """A rank drawn with weights ``exp(-k / N)`` (``std::discrete_distribution``), redrawn
    while it is one of the ``excluded`` ranks (three ``(R, N)`` arrays, repeats allowed),
    ``draws`` draws at most: :func:`~mawdo.optimizers.shade_ops.weighted_capped`'s law, with
    the excluded set's weights skipped instead of an ``(R, N, N)`` mask."""
    w = libm.exp(-np.arange(N) / float(N))
    cum = np.cumsum(w)
    e = np.sort(np.stack(excluded, axis=-1), axis=-1)
    dup = np.zeros(e.shape, bool)
    dup[..., 1:] = e[..., 1:] == e[..., :-1]
    we = np.where(dup, 0.0, w[e])
    wE = we.sum(axis=-1)
    c = libm.power(wE / cum[-1], draws)
    inside = u < c
    # inside: one of the excluded ranks, by their weights
    pick = ops.inverse_cdf(np.where(inside, u / np.where(c > 0, c, 1.0), 0.0), we)
    e_in = np.take_along_axis(e, pick[..., None], -1)[..., 0]
    # outside: invert the distribution function with the excluded weights skipped
    x = (u - c) / np.where(c < 1, 1.0 - c, 1.0) * (cum[-1] - wE)
    for m in range(3):
        em = e[..., m]
        x = np.where(~dup[..., m] & (cum[em] - w[em] <= x), x + w[em], x)
    k = np.minimum(np.searchsorted(cum, x, side="right"), N - 1)
    return np.where(inside, e_in, k)
