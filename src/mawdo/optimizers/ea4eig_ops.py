"""EA4eig's building blocks as array functions over a batch of runs (leading run axis).

Each function draws nothing itself: the uniforms and normals it turns into indices, parameters
and masks are handed in (one generation's arrays), so the literal per-individual port of the
authors' MATLAB code (``tests/optimizers/ea4eig_literal.py``) can be driven by the same numbers.
A rejection loop of the code (``while F < 0, draw again``) is one uniform mapped through the
inverse distribution function of the same law, as in the SHADE family
(docs/deviations.md#d-shade-draws). Indices are 0-based; the code's 1-based ranks appear as
``rank + 1`` where they enter a formula.
"""

from __future__ import annotations

import math

import numpy as np
from scipy.special import ndtr, ndtri

from mawdo.optimizers.shade_ops import c_round, truncated_cauchy
from mawdo.util import libm

#: The CoBiDE F's two Cauchy centres and CR's two, each picked with probability 1/2.
F_CENTRES, CR_CENTRES = (0.65, 1.0), (0.1, 0.95)
# P(Cauchy(c, 0.1) > 0) for the F centres: the code redraws the coin and the value while F < 0,
# so the centre of an accepted F is picked with these odds
_F_POSITIVE = tuple(0.5 + math.atan(c / 0.1) / math.pi for c in F_CENTRES)
F_FIRST = _F_POSITIVE[0] / (_F_POSITIVE[0] + _F_POSITIVE[1])


def mirror(y: np.ndarray, lb, ub) -> np.ndarray:
    """The code's ``zrcad``: a coordinate outside ``[lb, ub]`` is reflected at the bound it
    crossed, again until it lies inside (``2 ub - y``, ``2 lb - y``).

    Past eight reflections (a value several box widths out) the fold's closed form
    ``lb + w - |((y - lb) mod 2w) - w|`` gives the same point in one step (the loop would take
    ``|y| / 2w`` steps); non-finite values become NaN, which the evaluator counts as +inf.
    """
    y = np.array(y, dtype=float)
    for _ in range(8):
        hi, lo = y > ub, y < lb
        if not (hi.any() or lo.any()):
            return y
        y = np.where(hi, 2.0 * ub - y, np.where(lo, 2.0 * lb - y, y))
    out = (y > ub) | (y < lb) | ~np.isfinite(y)
    if out.any():
        w = np.broadcast_to(np.asarray(ub, float) - lb, y.shape)
        base = np.broadcast_to(np.asarray(lb, float), y.shape)
        with np.errstate(invalid="ignore"):
            folded = base + w - np.abs(np.mod(y - base, 2.0 * w) - w)
        y = np.where(out, folded, y)
    return y


def cobide_f(u_coin: np.ndarray, u_value: np.ndarray) -> np.ndarray:
    """CoBiDE's ``F``: Cauchy(0.65, 0.1) or Cauchy(1, 0.1) with probability 1/2 each, drawn
    again (coin and value) while negative, then capped at 1."""
    mu = np.where(u_coin < F_FIRST, F_CENTRES[0], F_CENTRES[1])
    return np.minimum(truncated_cauchy(mu, u_value), 1.0)


def cobide_cr(u_coin: np.ndarray, u_value: np.ndarray) -> np.ndarray:
    """CoBiDE's ``CR``: Cauchy(0.1, 0.1) or Cauchy(0.95, 0.1) with probability 1/2 each
    (``x0 + 0.1 tan(pi (u - 1/2))``), clipped to ``[0, 1]``."""
    mu = np.where(u_coin < 0.5, CR_CENTRES[0], CR_CENTRES[1])
    return np.clip(mu + 0.1 * libm.tan(np.pi * (u_value - 0.5)), 0.0, 1.0)


def roulette(ni: np.ndarray, u: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The code's ``roulete``: heuristic ``k`` (0-based) with probability ``ni_k / sum(ni)``
    (``u (R,)``), and each run's smallest share ``min(ni) / sum(ni)``."""
    total = ni.sum(axis=1, keepdims=True)
    cp = np.cumsum(ni, axis=1) / total
    return (cp < u[:, None]).sum(axis=1), ni.min(axis=1) / total[:, 0]


def distinct_excluding(u: np.ndarray, n: int, me: np.ndarray) -> list[np.ndarray]:
    """The code's ``nahvyb_expt(n, k, i)``: ``k`` distinct indices of ``0..n-1`` other than
    ``me``, each uniform on what is left (``u (..., k)``, one uniform per pick)."""
    picks: list[np.ndarray] = []
    for j in range(u.shape[-1]):
        excluded = np.sort(np.stack([me, *picks]), axis=0)
        m = excluded.shape[0]
        k = np.minimum((u[..., j] * (n - m)).astype(np.int64), n - m - 1)
        for e in excluded:  # the k-th allowed value: step over the excluded ones below it
            k = k + (k >= e)
        picks.append(k)
    return picks


def truncated_normal(mean: np.ndarray, u: np.ndarray, lo: float, hi: float, closed: bool):
    """``mean + 0.1 z`` redrawn until it lies in ``(lo, hi]`` (``closed``: ``[lo, hi]``), from
    one uniform by inverting the distribution function (the two intervals differ by a point)."""
    a, b = ndtr((lo - mean) / 0.1), ndtr((hi - mean) / 0.1)
    x = mean + 0.1 * ndtri(a + u * (b - a))
    x = np.clip(x, lo, hi)
    return x if closed else np.where(x > lo, x, np.nextafter(lo, hi))


def crossover_mask(u_cr: np.ndarray, CR: np.ndarray, u_j: np.ndarray) -> np.ndarray:
    """``change = find(rand(1, D) < CR)``, and one coordinate ``1 + fix(D rand)`` when that
    finds none (``u_cr (R, N, D)``, ``CR (R, N)``, ``u_j (R, N)``)."""
    D = u_cr.shape[-1]
    mask = u_cr < CR[..., None]
    j = np.minimum((u_j * D).astype(np.int64), D - 1)
    none = ~mask.any(axis=-1)
    return mask | (none[..., None] & (np.arange(D) == j[..., None]))


#: Largest spread whose squares, summed over a population, stay far from overflow.
_SQUARE_SAFE = 1e150


def eigen_basis(X: np.ndarray, F: np.ndarray, share: float) -> np.ndarray:
    """Eigenvectors ``(R, D, D)`` (columns) of the covariance of each run's best members:
    ``round(N share + 1) - 1`` of them after a stable sort by value (the code's
    ``Popeig(round(N * CBps + 1):N, :) = []``), sample covariance with ``n - 1``."""
    N = X.shape[1]
    keep = c_round(N * share + 1.0) - 1
    order = np.argsort(F, axis=1, kind="stable")[:, :keep]
    top = np.take_along_axis(X, order[..., None], 1)
    centred = top - top.mean(axis=1, keepdims=True)
    # the eigenvectors do not change with the covariance's scale: a run whose spread would
    # overflow its squares (a box near the float range) is divided by a power of two (exact),
    # every other run is left as it is (bit for bit)
    big = np.abs(centred).max(axis=(1, 2))
    huge = big > _SQUARE_SAFE
    if np.any(huge):
        scale = np.ones_like(big)
        scale[huge] = np.exp2(np.ceil(np.log2(big[huge])))
        centred = centred / scale[:, None, None]
    cov = np.einsum("rkd,rke->rde", centred, centred) / (keep - 1)
    return np.linalg.eigh(cov)[1]


def eigen_crossover(y: np.ndarray, v: np.ndarray, E: np.ndarray, mask: np.ndarray) -> np.ndarray:
    """Crossover in the eigenvector basis: ``y`` and ``v`` in ``E``'s coordinates
    (``E' y``), the masked coordinates taken from ``v``, back (``E y_eig``)."""
    y_eig = np.einsum("rdk,rnd->rnk", E, y)
    v_eig = np.einsum("rdk,rnd->rnk", E, v)
    return np.einsum("rdk,rnk->rnd", E, np.where(mask, v_eig, y_eig))


def cma_weights(mu_raw: float) -> tuple[int, np.ndarray, float]:
    """``(mu, weights, mueff)``: ``log(mu_raw + 1/2) - log(1..floor(mu_raw))`` normalised."""
    mu = int(math.floor(mu_raw))
    w = math.log(mu_raw + 0.5) - libm.log(np.arange(1.0, mu + 1))
    w = w / w.sum()
    return mu, w, float(w.sum() ** 2 / (w**2).sum())


def cma_constants(mueff: float, D: int) -> dict:
    """The CMA-ES learning rates, set once from the initial ``mueff`` (the code does not set
    them again when the population shrinks)."""
    cc = (4 + mueff / D) / (D + 4 + 2 * mueff / D)
    cs = (mueff + 2) / (D + mueff + 5)
    c1 = 2 / ((D + 1.3) ** 2 + mueff)
    cmu = min(1 - c1, 2 * (mueff - 2 + 1 / mueff) / ((D + 2) ** 2 + mueff))
    damps = 1 + 2 * max(0.0, math.sqrt((mueff - 1) / (D + 1)) - 1) + cs
    chiN = D**0.5 * (1 - 1 / (4 * D) + 1 / (21 * D**2))
    return {"cc": cc, "cs": cs, "c1": c1, "cmu": cmu, "damps": damps, "chiN": chiN}


def lehmer(values: np.ndarray, w: np.ndarray) -> np.ndarray:
    """``sum(w v v) / sum(w v)`` per run (``values``, ``w`` ``(R, N)``, zero weight off the
    successes), summed in order as the code's vectors."""
    jm = w * values
    with np.errstate(invalid="ignore", divide="ignore"):
        return np.cumsum(jm * values, axis=1)[:, -1] / np.cumsum(jm, axis=1)[:, -1]


def index_in(u: np.ndarray, n) -> np.ndarray:
    """``1 + fix(rand n)`` as a 0-based index: ``floor(u n)``, at most ``n - 1``."""
    n = np.asarray(n)
    return np.minimum((u * n).astype(np.int64), np.maximum(n - 1, 0))


__all__ = [
    "F_FIRST",
    "cma_constants",
    "cma_weights",
    "cobide_cr",
    "cobide_f",
    "crossover_mask",
    "distinct_excluding",
    "eigen_basis",
    "eigen_crossover",
    "index_in",
    "lehmer",
    "mirror",
    "roulette",
    "truncated_normal",
]
