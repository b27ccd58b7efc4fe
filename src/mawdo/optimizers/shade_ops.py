"""The success-history DE family's building blocks (L-SHADE, jSO, NL-SHADE-RSP) as array functions.

Every function works on a batch of ``R`` runs at once (leading run axis) and draws nothing
itself: the uniforms it turns into indices or parameters are handed in, so a literal
per-individual port can be driven by the same numbers (``tests/optimizers/shade_literal.py``).
The authors' C++ codes draw indices by rejection loops (``do r1 = rand() % NP while (r1 ==
i)``); here each such draw is one uniform mapped through the inverse distribution function of
the same law (docs/deviations.md#d-shade-draws).
"""

from __future__ import annotations

import math

import numpy as np

from mawdo.util import libm


def c_round(x: float) -> int:
    """C's ``round()``: to the nearest integer, halves away from zero (NumPy rounds to even)."""
    t = math.trunc(x)
    return int(t + math.copysign(1.0, x)) if abs(x - t) >= 0.5 else int(t)


def lpsr_size(nfes: int, max_nfes: int, n_init: int, n_min: int) -> int:
    """Linear population size reduction (Tanabe & Fukunaga 2014): the size planned
    after ``nfes`` of ``max_nfes`` evaluations, ``round((n_min - n_init)/max_nfes * nfes +
    n_init)`` in the code's operation order, never below ``n_min``."""
    plan = c_round(((n_min - n_init) / float(max_nfes)) * nfes + n_init)
    return max(plan, n_min)


def nonlinear_size(nfes: int, max_nfes: int, n_init: int, n_min: int) -> tuple[int, int]:
    """NL-SHADE-RSP's non-linear reduction: ``round((n_min - n_init) x^(1 - x) + n_init)`` with
    ``x = nfes / max_nfes``, clamped to ``[n_min, n_init]``; also the unclamped rounded value,
    which the code's archive size is computed from."""
    x = nfes / float(max_nfes)
    raw = c_round((n_min - n_init) * math.pow(x, 1.0 - x) + n_init)
    return min(max(raw, n_min), n_init), raw


def lehmer_weights(delta: np.ndarray, success: np.ndarray) -> np.ndarray:
    """Weights ``w_k = delta_k / sum(delta)`` over each run's successes (``(R, N)``, 0 elsewhere).

    The authors' arithmetic (``dif / sum``) where the sum is finite. An infinite improvement
    (a parent with a non-finite value, +inf to the algorithm) never occurs on their benchmarks;
    there the weights are shared equally by the infinite improvements (the limit of letting them
    grow together), and a sum that overflows is taken after dividing by the largest delta
    (docs/deviations.md#d-shade-nonfinite).
    """
    d = np.where(success, delta, 0.0)
    with np.errstate(over="ignore", invalid="ignore"):
        tot = seqsum(d)[:, None]
        w = d / np.where(tot > 0, tot, 1.0)
    bad = ~np.isfinite(tot[:, 0])
    if bad.any():
        db = d[bad]
        inf = np.isinf(db)
        some_inf = inf.any(axis=1, keepdims=True)
        with np.errstate(invalid="ignore"):
            scaled = db / np.maximum(db.max(axis=1, keepdims=True), np.finfo(float).tiny)
        scaled = np.where(some_inf, inf.astype(float), scaled)
        w[bad] = scaled / scaled.sum(axis=1, keepdims=True)
    return w


def lehmer_terms(values: np.ndarray, w: np.ndarray, square_first: bool = False):
    """``(sum w v^2, sum w v)`` per run (each ``(R,)``), as the codes accumulate them: L-SHADE
    ``weight * v * v``, NL-SHADE-RSP (``square_first``) ``weight * pow(v, 2)``. The weighted
    Lehmer mean is their ratio."""
    sq = w * (values * values) if square_first else (w * values) * values
    return seqsum(sq), seqsum(w * values)


def seqsum(a: np.ndarray) -> np.ndarray:
    """Sums along the last axis added one by one, in order, as the codes' loops add (NumPy's
    ``sum`` adds pairwise: the last bits could differ from the authors')."""
    return np.cumsum(a, axis=-1)[..., -1]


def truncated_cauchy(mu: np.ndarray, u: np.ndarray, scale: float = 0.1) -> np.ndarray:
    """``F ~ Cauchy(mu, scale)`` conditioned on ``F > 0``, by inverting its distribution
    function at ``u`` in ``[0, 1)``: the law of the codes' ``do F = cauchy(mu, 0.1) while (F <=
    0)``, from one uniform. ``u = 0`` maps to the upper tail (a huge ``F``, which the callers
    cap at 1), never to ``F = 0``."""
    u0 = 0.5 + libm.arctan(-mu / scale) / np.pi  # P(F <= 0)
    w = u0 + (1.0 - u0) * (1.0 - u)
    with np.errstate(over="ignore"):
        F = mu + scale * libm.tan(np.pi * (w - 0.5))
    return np.where(F > 0, F, np.nextafter(0.0, 1.0))


def index_excluding(u: np.ndarray, n, *excluded: np.ndarray) -> np.ndarray:
    """An index uniform on ``{0..n-1}`` minus the distinct ``excluded`` indices, from ``u`` in
    ``[0, 1)``: the law of ``do r = rand() % n while (r in excluded)``.

    ``n`` is an int or an array broadcasting with ``u``; each array of ``excluded`` has ``u``'s
    shape, holds indices below ``n``, and differs from the others entry by entry.
    """
    m = len(excluded)
    k = np.minimum((u * (np.asarray(n) - m)).astype(np.int64), np.asarray(n) - m - 1)
    for e in sorted_columns(excluded):
        k = k + (k >= e)
    return k


def sorted_columns(arrays) -> list[np.ndarray]:
    """The arrays' entries sorted across the arrays, entry by entry (for 0, 1 or 2 arrays)."""
    if len(arrays) < 2:
        return list(arrays)
    a, b = arrays
    return [np.minimum(a, b), np.maximum(a, b)]


def weighted_capped(u: np.ndarray, w: np.ndarray, excluded: np.ndarray, draws: int) -> np.ndarray:
    """Index ``k`` drawn with weights ``w`` ``(..., M)`` and redrawn while it is ``excluded``,
    at most ``draws`` draws in all, the last kept even if excluded: NL-SHADE-RSP's ``for (i = 0;
    i != 25 && !CheckGenerated(...); i++)`` retry loops, by inverting the exact law at ``u``.

    With ``q`` the excluded weight share, the draw lands in the excluded set with probability
    ``c = q^draws`` (by the excluded weights) and otherwise in the rest (by its weights);
    ``u < c`` picks the first case, ``u / c`` or ``(u - c) / (1 - c)`` then inverts its
    distribution function. ``u`` has shape ``(...)``.
    """
    tot = w.sum(axis=-1)
    q = (w * excluded).sum(axis=-1) / tot
    c = libm.power(q, draws)
    inside = u < c
    v = np.where(inside, u / np.where(c > 0, c, 1.0), (u - c) / np.where(c < 1, 1.0 - c, 1.0))
    pool = np.where(inside[..., None], excluded, ~excluded)
    return inverse_cdf(v, w * pool)


def inverse_cdf(v: np.ndarray, w: np.ndarray) -> np.ndarray:
    """The first index whose cumulative weight exceeds ``v`` times the total (``w`` ``(..., M)``
    non-negative with a positive sum, ``v`` in ``[0, 1)``); never an index of zero weight."""
    cum = np.cumsum(w, axis=-1)
    k = (cum <= v[..., None] * cum[..., -1:]).sum(axis=-1)
    last = w.shape[-1] - 1 - np.argmax((w > 0)[..., ::-1], axis=-1)
    return np.minimum(k, last)


def archive_insert(archive, count, size: int, parents, inserted, u) -> np.ndarray:
    """Put the ``inserted`` parents into each run's archive, in individual order, in place.

    ``archive (R, cap, D)`` holds ``count (R,)`` members; the size limit ``size`` is the same
    for every run. While a run's archive has room a parent is appended, afterwards it replaces
    the member at ``floor(u_i * size)`` (the codes' ``rand() % size``; a later parent overwrites
    an earlier one in the same slot). ``parents (R, N, D)``, ``inserted (R, N)`` bool, ``u (R,
    N)``. Returns the new counts. ``size < 1`` inserts nothing.
    """
    R, N = inserted.shape
    if size < 1:
        return count
    rank = np.cumsum(inserted, axis=1) - 1  # the parent's place among this generation's
    pos = count[:, None] + rank
    slot = np.where(pos < size, pos, np.minimum((u * size).astype(np.int64), size - 1))
    writer = np.full((R, archive.shape[1]), -1, np.int64)
    rows = np.broadcast_to(np.arange(R)[:, None], (R, N))
    who = np.broadcast_to(np.arange(N), (R, N))
    np.maximum.at(writer, (rows[inserted], slot[inserted]), who[inserted])
    r, s = np.nonzero(writer >= 0)
    archive[r, s] = parents[r, writer[r, s]]
    return np.minimum(count + inserted.sum(axis=1), size)


def keep_best(F: np.ndarray, n_keep: int) -> np.ndarray:
    """Indices ``(R, n_keep)`` of the members that survive removing the worst one at a time
    (the first of equal worst values first, as the codes' scans with ``>``), in their order."""
    order = np.argsort(-F, axis=1, kind="stable")
    return np.sort(order[:, F.shape[1] - n_keep :], axis=1)


def gather(X: np.ndarray, idx: np.ndarray) -> np.ndarray:
    """``X[r, idx[r, ...]]`` for ``X (R, M, D)`` and integer ``idx (R, ...)``."""
    return X[np.arange(X.shape[0]).reshape(-1, *([1] * (idx.ndim - 1))), idx]


def midpoint_bounds(trial: np.ndarray, parent: np.ndarray, lb, ub) -> np.ndarray:
    """JADE's repair used by L-SHADE and jSO: a coordinate below ``lb`` becomes ``(lb +
    parent)/2``, one above ``ub`` becomes ``(ub + parent)/2``
    (``modifySolutionWithParentMedium``)."""
    low = trial < lb
    high = trial > ub
    out = np.where(low, (lb + parent) / 2.0, trial)
    return np.where(high & ~low, (ub + parent) / 2.0, out)
