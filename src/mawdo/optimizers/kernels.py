"""Numba kernels for the optimizers' inner loops: one pass over the batch per iteration.

The equations live as readable NumPy array functions in :mod:`mawdo.optimizers.wind`,
:mod:`mawdo.optimizers.boundary` and :mod:`mawdo.optimizers.gwo`; these kernels compute the same
numbers in one sweep with no ``(R, N, D)`` temporaries (issue 15: a third of the NumPy time went
to fresh temporaries and their page faults). ``tests/optimizers/test_kernels.py`` checks each
kernel against the NumPy functions. Every random number comes from the run's own generator
(:class:`mawdo.streams.RunStreams`), drawn before the call or through a xoshiro256** state seeded
once from it (:func:`seed_xoshiro`). The WDO family's kernel is in
:mod:`mawdo.optimizers.wind_kernel`.
"""

from __future__ import annotations

import numpy as np
from numba import njit

from mawdo.shuffle import (  # noqa: F401  (re-exported)
    _BATCH,
    fisher_yates_batch,
    shuffle_from_words,
    shuffle_values_from_words,
    words_per_permutation,
)

_LOW32 = np.uint64(0xFFFFFFFF)
_SHIFT32 = np.uint64(32)
_SHIFT11 = np.uint64(11)
_U53 = 1.0 / 9007199254740992.0


@njit(cache=True, nogil=True)
def segment_ranks(F, starts, out):  # pragma: no cover - compiled
    """1-based rank of each entry of ``F`` ``(R, N)`` within its segment ``starts[s]:starts[s+1]``,
    ties broken by index (a stable sort), written to ``out`` ``(R, N)`` as float."""
    R = F.shape[0]
    S = starts.size - 1
    idx = np.empty(F.shape[1], np.intp)
    for r in range(R):
        for s in range(S):
            a, b = starts[s], starts[s + 1]
            n = b - a
            if n <= 64:  # insertion sort: stable, no allocation, fast for small groups
                for k in range(n):
                    j = k
                    v = F[r, a + k]
                    while j > 0 and F[r, a + idx[j - 1]] > v:
                        idx[j] = idx[j - 1]
                        j -= 1
                    idx[j] = k
                for k in range(n):
                    out[r, a + idx[k]] = k + 1.0
            else:
                order = np.argsort(F[r, a:b], kind="mergesort")
                for k in range(n):
                    out[r, a + order[k]] = k + 1.0


_U32 = 1.0 / 4294967296.0


@njit(cache=True, nogil=True, inline="always")
def _rotl(x, k):  # pragma: no cover - compiled
    return (x << np.uint64(k)) | (x >> np.uint64(64 - k))


@njit(cache=True, nogil=True, inline="always")
def xoshiro_step(s0, s1, s2, s3):  # pragma: no cover - compiled
    """One xoshiro256** step (Blackman & Vigna 2018) on a state held in locals:
    returns ``(output, s0, s1, s2, s3)``."""
    result = _rotl(s1 * np.uint64(5), 7) * np.uint64(9)
    t = s1 << np.uint64(17)
    s2 ^= s0
    s3 ^= s1
    s1 ^= s2
    s0 ^= s3
    s2 ^= t
    s3 = _rotl(s3, 45)
    return result, s0, s1, s2, s3


@njit(cache=True, nogil=True, error_model="numpy")
def gwo_step(X, lead_x, a, rng, use_rng, r, lb, ub, out):  # pragma: no cover - compiled
    """GWO's move (Eqs. 3.3-3.7) of every wolf, clipped to ``[lb, ub]``, written to ``out``.

    ``X`` ``(R, N, D)``, ``lead_x`` ``(R, 3, D)`` (alpha, beta, delta), ``a`` scalar. When
    ``use_rng``, the six uniforms of wolf ``i``, dimension ``d`` (``r1, r2`` for alpha, beta,
    delta) are the 32-bit halves of three outputs of the run's xoshiro256** (``rng (R, 4)``,
    seeded from the run's own generator), scaled by ``2**-32``, drawn in the order wolf,
    dimension, leader; else they are ``r[:, 0, k, i, d]`` and ``r[:, 1, k, i, d]``
    (``r`` of shape ``(R, 2, 3, N, D)``).
    """
    R, N, D = X.shape
    two_a = 2.0 * a
    for q in range(R):
        # the run's generator state lives in locals (registers) for the whole run
        qq = q if use_rng else 0  # rng is a (1, 4) placeholder without use_rng
        s0, s1, s2, s3 = rng[qq, 0], rng[qq, 1], rng[qq, 2], rng[qq, 3]
        for i in range(N):
            for d in range(D):
                x = X[q, i, d]
                acc = 0.0
                for k in range(3):
                    if use_rng:
                        wd, s0, s1, s2, s3 = xoshiro_step(s0, s1, s2, s3)
                        r1 = np.float64(wd & _LOW32) * _U32
                        r2 = np.float64(wd >> _SHIFT32) * _U32
                    else:
                        r1 = r[q, 0, k, i, d]
                        r2 = r[q, 1, k, i, d]
                    L = lead_x[q, k, d]
                    A = r1 * two_a - a
                    dist = abs(r2 * (2.0 * L) - x) * A
                    acc += L
                    acc -= dist
                v = acc / 3.0
                if v > ub[d]:
                    v = ub[d]
                elif v < lb[d]:
                    v = lb[d]
                out[q, i, d] = v
        if use_rng:
            rng[q, 0], rng[q, 1], rng[q, 2], rng[q, 3] = s0, s1, s2, s3


@njit(cache=True, nogil=True)
def update_personal_best(p, f, pbest, pbest_f):  # pragma: no cover - compiled
    """``pbest``/``pbest_f`` take ``p``/``f`` where ``f < pbest_f`` (strict), in place."""
    R, N, D = p.shape
    for r in range(R):
        for i in range(N):
            if f[r, i] < pbest_f[r, i]:
                pbest_f[r, i] = f[r, i]
                for d in range(D):
                    pbest[r, i, d] = p[r, i, d]


def seed_xoshiro(streams) -> np.ndarray:
    """xoshiro256** states ``(R, 4)`` uint64, four raw words of each run's own generator.

    GWO draws six uniforms per wolf and dimension; the Numba generator supplies them inside the
    kernel (no per-run Python call, no buffer), and run ``r``'s numbers still depend only on run
    ``r``'s seed. An all-zero state (probability ``2**-256``) is the one xoshiro cannot leave.
    """
    state = streams.raw_words(np.empty((streams.runs, 4), np.uint64))
    state[~state.any(axis=1), 0] = 1
    return state


@njit(cache=True, nogil=True, error_model="numpy")
def mewdo_step(
    p,
    u,
    pbest,
    rank,
    tb,
    guide,
    centre,
    strat,
    draws,
    perm,
    words,
    use_words,
    coef,
    vmax,
    lb,
    width,
    X,
):  # pragma: no cover - compiled
    """MEWDO (reconstructed)'s move: each parcel applies only the strategy it drew.

    ``strat (R, N)``: 0 classic WDO toward ``pbest[tb]``; 1 AWDO with the parcel's coefficients
    ``draws[r, i, 1:5]``; 2 toward ``pbest[guide]`` with unit pressure and rank, gravity toward
    ``centre (R, D)``. ``coef = (alpha, g, RT, c)`` of strategies 0 and 2. The Coriolis
    permutations: with ``use_words``, parcel ``i``'s is
    ``shuffle_from_words(words[r], i W, .)`` (``W = words_per_permutation(D)``, applied to the
    velocities by :func:`shuffle_values_from_words`) from ``words (R, N W)`` uint64, else
    ``perm (R, N, D)``. Velocity clamped to ``vmax``, position clipped to ``[-1, 1]``,
    ``X = lb + (p + 1)/2 width``. Same equations as ``wind.wdo_velocity``/``awdo_velocity``.
    """
    R, N, D = p.shape
    u_old = np.empty(D)
    up = np.empty(D)  # u_old[perm]
    v = np.empty(D)
    alpha, g, RT, c = coef[0], coef[1], coef[2], coef[3]
    W = words.shape[1] // N if use_words else 0
    for r in range(R):
        for i in range(N):
            for d in range(D):  # the gathers first, one loop per strategy: the loops vectorise
                u_old[d] = u[r, i, d]
            if use_words:
                for d in range(D):
                    up[d] = u_old[d]
                shuffle_values_from_words(words[r], i * W, up)
            else:
                for d in range(D):
                    up[d] = u_old[perm[r, i, d]]
            s = strat[r, i]
            rk = rank[r, i]
            if s == 0:
                for d in range(D):
                    q = p[r, i, d]
                    v[d] = (
                        (1.0 - alpha) * u_old[d]
                        - g * q
                        + abs(1.0 - 1.0 / rk) * RT * (pbest[r, tb[r], d] - q)
                        + c * up[d] / rk
                    )
            elif s == 1:
                a1, g1 = draws[r, i, 1], draws[r, i, 2]
                RT1, c1 = draws[r, i, 3], draws[r, i, 4]
                for d in range(D):
                    q = p[r, i, d]
                    v[d] = (
                        (1.0 - a1) * u_old[d]
                        - g1 * q
                        + RT1 * (pbest[r, tb[r], d] - q) / rk
                        + c1 * up[d] / rk
                    )
            else:
                gi = guide[r, i]
                for d in range(D):
                    q = p[r, i, d]
                    v[d] = (
                        (1.0 - alpha) * u_old[d]
                        - g * (q - centre[r, d])
                        + (pbest[r, gi, d] - q)
                        + c * up[d]
                    )
            for d in range(D):
                vd = min(max(v[d], -vmax), vmax)
                q = min(max(p[r, i, d] + vd, -1.0), 1.0)
                u[r, i, d] = vd
                p[r, i, d] = q
                X[r, i, d] = lb[d] + (q + 1.0) * 0.5 * width[d]
