"""EA4eig's four algorithms, one generation each, on the runs (``rows``) whose roulette picked it.

``<name>_ask(opt, state, rows, sub)`` draws the generation's numbers from the runs' streams
``sub`` and returns the trials ``(n, N, D)`` and the draws (kept in ``state.gen`` for the
literal port's test); ``<name>_tell(opt, state, rows, trial, F)`` takes their values. IDE and
CMA-ES rank the population first, as the code's ``sortrows`` does, carrying each member's CoBiDE
``F`` and ``CR`` along. Line references are to the authors' MATLAB (``alg_EA4eig.m``).
"""

from __future__ import annotations

import math

import numpy as np

from mawdo.optimizers import ea4eig_ops as ops
from mawdo.optimizers.shade_ops import (
    archive_insert,
    gather,
    index_excluding,
    lehmer_weights,
    truncated_cauchy,
)
from mawdo.util import libm

P_MAX, P_MIN = 0.25, 0.125  # jSO's pbest share, falling with the evaluations


def _me(n: int, N: int) -> np.ndarray:
    return np.broadcast_to(np.arange(N), (n, N))


def _sort_rows(state, rows) -> None:
    """``[P, I] = sortrows(P, DIM + 1); CBF = CBF(I); CBCR = CBCR(I)`` on the runs ``rows``."""
    order = np.argsort(state.F[rows], axis=1, kind="stable")
    state.X[rows] = np.take_along_axis(state.X[rows], order[..., None], 1)
    for name in ("F", "CBF", "CBCR"):
        arr = getattr(state, name)
        arr[rows] = np.take_along_axis(arr[rows], order, 1)


def _eigen(opt, X, F, y, v, mask, eig):
    """The eigen crossover of ``y`` with ``v`` on the runs ``eig`` (bool), in place in ``y``."""
    if eig.any():
        E = ops.eigen_basis(X[eig], F[eig], opt.params.eig_share)
        y[eig] = ops.eigen_crossover(X[eig], v[eig], E, mask[eig])
    return y


def _select(state, rows, trial, Fq, ok) -> None:
    state.X[rows] = np.where(ok[..., None], trial, state.X[rows])
    state.F[rows] = np.where(ok, Fq, state.F[rows])


# -- 1. CoBiDE ------------------------------------------------------------------------------------


def cobide_ask(opt, state, rows, sub):
    """rand/1 with each member's ``(CBF_i, CBCR_i)``; ``v`` and the trial reflected into the box
    (lines of ``case 1``)."""
    N, D = state.X.shape[1:]
    lb, ub = state.space.lb, state.space.ub
    u_eig, u_r, u_cr, u_j, u_fc, u_fv, u_cc, u_cv = sub.random_parts(
        (1,), (N, 3), (N, D), (N,), (N,), (N,), (N,), (N,)
    )
    d = {"u_eig": u_eig[:, 0], "u_r": u_r, "u_cr": u_cr, "u_j": u_j,
         "u_fc": u_fc, "u_fv": u_fv, "u_cc": u_cc, "u_cv": u_cv}  # fmt: skip
    X, F = state.X[rows], state.F[rows]
    r1, r2, r3 = ops.distinct_excluding(u_r, N, _me(len(rows), N))
    v = gather(X, r1) + state.CBF[rows][..., None] * (gather(X, r2) - gather(X, r3))
    v = ops.mirror(v, lb, ub)
    mask = ops.crossover_mask(u_cr, state.CBCR[rows], u_j)
    y = _eigen(opt, X, F, np.where(mask, v, X), v, mask, d["u_eig"] < opt.params.p_eig)
    return ops.mirror(y, lb, ub), d


def cobide_tell(opt, state, rows, trial, Fq) -> None:
    """A trial not worse than its parent replaces it (a success); a failed member draws a new
    ``F`` and ``CR``."""
    d = state.gen["cobide"]
    ok = Fq <= state.F[rows]
    _select(state, rows, trial, Fq, ok)
    state.ni[rows, 0] += ok.sum(axis=1)
    state.CBF[rows] = np.where(ok, state.CBF[rows], ops.cobide_f(d["u_fc"], d["u_fv"]))
    state.CBCR[rows] = np.where(ok, state.CBCR[rows], ops.cobide_cr(d["u_cc"], d["u_cv"]))


# -- 2. IDE ---------------------------------------------------------------------------------------


def ide_ask(opt, state, rows, sub):
    """Individual-dependent mutation on the ranked population, then the eigen crossover or the
    rank-dependent binomial one with out-of-box coordinates redrawn (``case 2``)."""
    _sort_rows(state, rows)
    N, D = state.X.shape[1:]
    lb, ub = state.space.lb, state.space.ub
    parts = sub.random_parts(
        (1,), (N, 4), (N, D), (N, D), (N,), (N,), (N,), (N, D), (N,), (N,), (N, D)
    )
    names = ("u_eig", "u_r", "u_pd", "u_pt", "u_fo", "u_sup", "u_half", "u_cr", "u_j", "u_crv",
             "u_box")  # fmt: skip
    d = dict(zip(names, parts, strict=True))
    d["u_eig"] = d["u_eig"][:, 0]
    X, F = state.X[rows], state.F[rows]
    g, gt = state.g[rows][:, None], state.gt[rows][:, None]
    share = 0.1 + 0.9 * libm.power(10.0, 5.0 * (g / state.gmax - 1.0))  # IDEps
    me = _me(len(rows), N)
    picks = ops.distinct_excluding(d["u_r"], N, me)
    o = np.where(g <= gt, me, picks[0])
    xr3 = np.where(d["u_pd"] < 0.1 * share[..., None], lb + d["u_pt"] * (ub - lb),
                   gather(X, picks[3]))  # fmt: skip
    Fo = ops.truncated_normal((o + 1) / N, d["u_fo"], 0.0, 1.0, closed=False)
    superior = np.trunc(share * N).astype(np.int64)  # high_ind_S
    inferior = (o + 1 > superior) & (picks[1] + 1 > superior)
    # setdiff(1:high_ind_S, [vyb, i]) has high_ind_S minus those of vyb and i below it; the
    # code then takes ``1 + fix(rand * length)``: a rank among the first ``length``
    left = superior - sum((p < superior).astype(np.int64) for p in (*picks, me))
    r1 = np.where(inferior, ops.index_in(d["u_sup"], left), picks[1])
    xo = gather(X, o)
    base = np.where(((g > gt) & (d["u_half"] < 0.5))[..., None], X, xo)
    Q = base + Fo[..., None] * (gather(X, r1) - xo) + Fo[..., None] * (gather(X, picks[2]) - xr3)
    CR = ops.truncated_normal((me + 1) / N, d["u_crv"], 0.0, 1.0, closed=True)
    j = ops.index_in(d["u_j"], D)
    take = (d["u_cr"] <= CR[..., None]) | (np.arange(D) == j[..., None])
    y = np.where(take, Q, X)
    y = np.where((y < lb) | (y > ub), lb + d["u_box"] * (ub - lb), y)
    eig = d["u_eig"] < opt.params.p_eig
    if eig.any():
        mask = ops.crossover_mask(d["u_cr"], state.CBCR[rows], d["u_j"])
        y[eig] = ops.mirror(_eigen(opt, X, F, y.copy(), Q, mask, eig)[eig], lb, ub)
    return y, d


def ide_tell(opt, state, rows, trial, Fq) -> None:
    """Not-worse trials replace their parents; the success rate drives the switch to the
    second stage (``gt``); the population is ranked again."""
    ok = Fq <= state.F[rows]
    wins = ok.sum(axis=1)
    state.ni[rows, 1] += wins
    g, gt = state.g[rows], state.gt[rows]
    early = g < gt
    streak = np.where(wins / ok.shape[1] <= 0.0, state.t_fail[rows] + 1, 0)  # SRT = 0 then
    state.t_fail[rows] = np.where(early, streak, state.t_fail[rows])
    state.gt[rows] = np.where(early & (state.t_fail[rows] >= state.t_limit), g, gt)
    _select(state, rows, trial, Fq, ok)
    _sort_rows(state, rows)
    state.g[rows] += 1


# -- 3. CMA-ES ------------------------------------------------------------------------------------


def cmaes_ask(opt, state, rows, sub):
    """``N`` samples ``xmean + sigma B (D z)`` around the weighted mean of the ranked best
    ``mu``; a coordinate out of the box goes halfway from its last sample to the bound
    (``case 3``)."""
    _sort_rows(state, rows)
    N, D = state.X.shape[1:]
    lb, ub = state.space.lb, state.space.ub
    z = sub.normal((N, D))
    xmean = np.einsum("k,rkd->rd", state.weights, state.X[rows, : state.mu])
    scaled = state.sigma[rows][:, None, None] * state.B[rows]  # (sigma * B) * (D .* z)
    pop = xmean[:, None, :] + np.einsum("rde,rne->rnd", scaled, state.Dd[rows][:, None, :] * z)
    old = state.old_pop[rows][:, :N]
    pop = np.where(pop < lb, (old + lb) / 2.0, pop)
    pop = np.where(pop > ub, (old + ub) / 2.0, pop)
    return pop, {"z": z, "xmean": xmean}


def cmaes_tell(opt, state, rows, pop, Fpop) -> None:
    """Each sample in turn replaces the current worst member if better (a success); then the
    code's CMA-ES update of the mean, paths, covariance and step size."""
    N, D = state.X.shape[1:]
    X, F = state.X[rows], state.F[rows]
    idx = np.arange(len(rows))
    for kk in range(N):
        worst = np.argmax(F, axis=1)
        better = Fpop[:, kk] < F[idx, worst]
        X[idx[better], worst[better]] = pop[better, kk]
        F[idx[better], worst[better]] = Fpop[better, kk]
        state.ni[rows[better], 2] += 1
    state.X[rows], state.F[rows] = X, F
    sel = np.take_along_axis(pop, np.argsort(Fpop, axis=1, kind="stable")[:, : state.mu, None], 1)
    xold = state.gen["cmaes"]["xmean"]
    xmean = np.einsum("k,rkd->rd", state.weights, sel)
    state.old_pop[rows, :N] = pop
    _cma_update(state, rows, xold, xmean, sel, state.nfes + N)


def _cma_update(state, rows, xold, xmean, sel, fes: int) -> None:
    """The code's cumulation, rank-one and rank-mu updates, step size and (every
    ``N / (c1 + cmu) / D / 10`` evaluations) eigendecomposition, at ``FES = fes``."""
    c, mueff, w = state.cma, state.mueff, state.weights
    N, D = state.X.shape[1:]
    sigma = state.sigma[rows][:, None]
    dx = xmean - xold
    ps = (1 - c["cs"]) * state.ps[rows] + np.einsum(
        "rde,re->rd", math.sqrt(c["cs"] * (2 - c["cs"]) * mueff) * state.inv_sqrt_c[rows], dx
    ) / sigma
    hsig = (ps**2).sum(axis=1) / (1 - (1 - c["cs"]) ** (2 * fes / N)) / D < 2 + 4 / (D + 1)
    h = hsig.astype(float)[:, None]
    pc_rate = math.sqrt(c["cc"] * (2 - c["cc"]) * mueff)
    pc = (1 - c["cc"]) * state.pc[rows] + h * pc_rate * dx / sigma
    art = (1 / sigma[..., None]) * (sel - xold[:, None, :])
    rank_one = (
        np.einsum("rd,re->rde", pc, pc)
        + ((1 - h) * c["cc"] * (2 - c["cc"]))[..., None] * state.C[rows]
    )
    rank_mu = np.einsum("rkd,k,rke->rde", art, w, art)
    C = (1 - c["c1"] - c["cmu"]) * state.C[rows] + c["c1"] * rank_one + c["cmu"] * rank_mu
    new_sigma = state.sigma[rows] * libm.exp(
        (c["cs"] / c["damps"]) * (np.linalg.norm(ps, axis=1) / c["chiN"] - 1)
    )
    bad = ~((new_sigma <= 1e300) & (new_sigma >= 1e-300))  # (NaN included)
    new_sigma[bad] = (state.space.ub[0] - state.space.lb[0]) / 2.0
    state.ps[rows], state.pc[rows], state.C[rows], state.sigma[rows] = ps, pc, C, new_sigma
    due = rows[fes - state.eigeneval[rows] > N / (c["c1"] + c["cmu"]) / D / 10]
    if due.size:
        state.eigeneval[due] = fes
        up = np.triu(state.C[due])
        C = up + np.swapaxes(np.triu(state.C[due], 1), 1, 2)  # triu(CC) + triu(CC, 1)'
        vals, B = np.linalg.eigh(C)
        Dd = np.sqrt(np.maximum(vals, np.finfo(float).tiny))
        state.C[due], state.B[due], state.Dd[due] = C, B, Dd
        state.inv_sqrt_c[due] = np.einsum("rdk,rk,rek->rde", B, 1.0 / Dd, B)


# -- 4. jSO ---------------------------------------------------------------------------------------


def jso_ask(opt, state, rows, sub):
    """current-to-pBest-w/1 with the memories' ``(F, CR)`` (``CR`` with spread sqrt(0.1), as
    coded), the archive, and the eigen crossover (which uses the member's CoBiDE ``CR`` and no
    boundary handling, as coded) or the binomial one with reflection (``case 4``)."""
    N, D = state.X.shape[1:]
    lb, ub = state.space.lb, state.space.ub
    parts = sub.random_parts((1,), (N,), (N,), (N,), (N,), (N,), (N, D), (N,), (N,))
    names = ("u_eig", "u_mem", "u_f", "u_pb", "u_r1", "u_r2", "u_cr", "u_j", "u_slot")
    d = dict(zip(names, parts, strict=True))
    d["u_eig"], d["z"] = d["u_eig"][:, 0], sub.normal((N,))
    X, F = state.X[rows], state.F[rows]
    fes, M = state.nfes, state.max_nfes
    r = ops.index_in(d["u_mem"], state.MF.shape[1])
    CR = np.clip(np.take_along_axis(state.MCR[rows], r, 1) + math.sqrt(0.1) * d["z"], 0.0, 1.0)
    if fes < 0.25 * M:
        CR = np.maximum(CR, 0.7)
    elif fes < 0.5 * M:
        CR = np.maximum(CR, 0.6)
    Fi = np.minimum(truncated_cauchy(np.take_along_axis(state.MF[rows], r, 1), d["u_f"]), 1.0)
    if fes < 0.6 * M:
        Fi = np.where(Fi > 0.7, 0.7, Fi)
    p = max(2, math.ceil((P_MAX - (P_MAX - P_MIN) * (fes / M)) * N))
    pbest = np.take_along_axis(np.argsort(F, axis=1, kind="stable"), ops.index_in(d["u_pb"], p), 1)
    me = _me(len(rows), N)
    r1 = index_excluding(d["u_r1"], N, me)
    n_arc = state.n_arc[rows][:, None]
    r2 = index_excluding(d["u_r2"], N + n_arc, me, r1)
    A = state.archive[rows]
    x_r2 = np.where((r2 < N)[..., None], gather(X, np.minimum(r2, N - 1)),
                    gather(A, np.clip(r2 - N, 0, A.shape[1] - 1)))  # fmt: skip
    Fw = Fi * (0.7 if fes < 0.2 * M else 0.8 if fes < 0.4 * M else 1.2)
    v = X + Fw[..., None] * (gather(X, pbest) - X) + Fi[..., None] * (gather(X, r1) - x_r2)
    y = ops.mirror(np.where(ops.crossover_mask(d["u_cr"], CR, d["u_j"]), v, X), lb, ub)
    eig = d["u_eig"] < opt.params.p_eig
    if eig.any():
        mask = ops.crossover_mask(d["u_cr"], state.CBCR[rows], d["u_j"])
        y = _eigen(opt, X, F, y, v, mask, eig)
    d["F"], d["CR"] = Fi, CR
    return y, d


def jso_tell(opt, state, rows, trial, Fq) -> None:
    """Strictly better trials archive their parents and feed the memory entry ``k`` (weighted
    Lehmer means, averaged with the old entry; ``k`` cycles over all but the last entry);
    not-worse trials replace their parents."""
    d, H = state.gen["jso"], state.MF.shape[1]
    F = state.F[rows]
    better = Fq < F
    with np.errstate(invalid="ignore"):
        delta = np.where(better, F - Fq, 0.0)
    A, n_arc = state.archive[rows], state.n_arc[rows]
    state.n_arc[rows] = archive_insert(A, n_arc, state.arc_size, state.X[rows], better, d["u_slot"])
    state.archive[rows] = A
    _select(state, rows, trial, Fq, Fq <= F)
    wins = better.sum(axis=1)
    state.ni[rows, 3] += wins
    upd = rows[wins > 0]
    if not upd.size:
        return
    sub = wins > 0
    total = np.cumsum(delta[sub], axis=1)[:, -1:]
    with np.errstate(invalid="ignore"):
        w = (1.0 / total) * delta[sub]  # the code's 1 / sum_delta * delty
    odd = ~np.isfinite(total[:, 0])  # an infinite improvement: shares as in the SHADE family
    if odd.any():
        w[odd] = lehmer_weights(delta[sub][odd], better[sub][odd])
    k = state.k[upd]
    old_cr, old_f = state.MCR[upd, k], state.MF[upd, k]
    m_scr = np.where(better[sub], d["CR"][sub], -np.inf).max(axis=1)
    cr = np.where((old_cr == -1) | (m_scr == 0), -1.0, ops.lehmer(d["CR"][sub], w))
    state.MCR[upd, k] = (cr + old_cr) / 2
    state.MF[upd, k] = (ops.lehmer(d["F"][sub], w) + old_f) / 2
    state.k[upd] = np.where(k + 2 >= H, 0, k + 1)
