"""Compiled generation step of :mod:`mawdo.optimizers.purecmaes`: one loop over runs.

The array form costs ~35 small NumPy calls a generation (AWDO-CMA at 0.34 us per
evaluation, the CMA-ES half of it); the same statements over one run's 4-vectors and 4 x 4
matrices cost next to nothing compiled. The eigen decomposition stays in NumPy (every few
generations).
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit


@njit(cache=True, fastmath=False, error_model="numpy")
def update(arx, fitness, w, consts, counteval, xmean, sigma, pc, ps, C, invsqrtC, sigma_max):
    """One ``purecmaes_wdo`` update per run, in place (mean, paths, covariance, step size).

    Long by design: one fused Numba pass; splitting it adds calls in the hot loop.

    Parameters
    ----------
    arx : float64[:, :, :], shape (R, lam, n)
        The samples just scored.
    fitness : float64[:, :], shape (R, lam)
        Their fitness, minimised (finite).
    w : float64[:], shape (mu,)
        Recombination weights, summing to 1.
    consts : float64[:]
        ``(mueff, cc, cs, c1, cmu, damps, chin)`` of :class:`~.purecmaes.Settings`.
    counteval : int
        The source's iteration number (2 at the first call).
    xmean, sigma, pc, ps, C, invsqrtC : arrays
        The state, shapes (R, n), (R,), (R, n), (R, n), (R, n, n), (R, n, n); updated in place.
    sigma_max : float
        Cap of the step size.
    """
    R, lam, n = arx.shape
    mu = w.shape[0]
    mueff, cc, cs, c1, cmu, damps, chin = (
        consts[0], consts[1], consts[2], consts[3], consts[4], consts[5], consts[6],
    )  # fmt: skip
    path_s = math.sqrt(cs * (2 - cs) * mueff)
    path_c = math.sqrt(cc * (2 - cc) * mueff)
    norm_h = 1 - (1 - cs) ** (2 * counteval / lam)
    xold = np.empty(n)
    step = np.empty(n)
    artmp = np.empty((mu, n))
    for r in range(R):
        order = np.argsort(fitness[r], kind="mergesort")  # stable, as MATLAB's sort
        for i in range(n):
            xold[i] = xmean[r, i]
            s = 0.0
            for m in range(mu):
                s += w[m] * arx[r, order[m], i]
            xmean[r, i] = s
            step[i] = (s - xold[i]) / sigma[r]
        norm2 = 0.0
        for i in range(n):
            s = 0.0
            for j in range(n):
                s += invsqrtC[r, i, j] * step[j]
            ps[r, i] = (1 - cs) * ps[r, i] + path_s * s
            norm2 += ps[r, i] * ps[r, i]
        hsig = 1.0 if norm2 / norm_h / n < 2 + 4 / (n + 1) else 0.0
        for i in range(n):
            pc[r, i] = (1 - cc) * pc[r, i] + hsig * path_c * step[i]
        for m in range(mu):
            for i in range(n):
                artmp[m, i] = (arx[r, order[m], i] - xold[i]) / sigma[r]
        for i in range(n):
            for j in range(n):
                rank_mu = 0.0
                for m in range(mu):
                    rank_mu += artmp[m, i] * w[m] * artmp[m, j]
                rank_one = pc[r, i] * pc[r, j] + (1 - hsig) * cc * (2 - cc) * C[r, i, j]
                C[r, i, j] = (1 - c1 - cmu) * C[r, i, j] + c1 * rank_one + cmu * rank_mu
        sigma[r] = min(sigma[r] * math.exp((cs / damps) * (math.sqrt(norm2) / chin - 1)), sigma_max)


@njit(cache=True, fastmath=False, error_model="numpy")
def sample(xmean, sigma, B, D, z):
    """``xmean + sigma B (D z)`` per run: new samples, shape (R, lam, n).

    Parameters
    ----------
    xmean : float64[:, :], shape (R, n)
    sigma : float64[:], shape (R,)
    B : float64[:, :, :], shape (R, n, n)
        Eigenvectors of the covariance, in columns.
    D : float64[:, :], shape (R, n)
        Standard deviations along them.
    z : float64[:, :, :], shape (R, lam, n)
        Standard normal draws.
    """
    R, lam, n = z.shape
    out = np.empty_like(z)
    for r in range(R):
        for k in range(lam):
            for i in range(n):
                s = 0.0
                for j in range(n):
                    s += B[r, i, j] * (D[r, j] * z[r, k, j])
                out[r, k, i] = xmean[r, i] + sigma[r] * s
    return out
