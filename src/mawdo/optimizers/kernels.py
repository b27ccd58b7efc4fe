"""Numba kernels for the optimizers' inner loops: one pass over the batch per iteration.

The equations live as readable NumPy array functions in :mod:`mawdo.optimizers.wind`,
:mod:`mawdo.optimizers.boundary` and :mod:`mawdo.optimizers.gwo`; these kernels compute the same
numbers in one sweep with no ``(R, N, D)`` temporaries (a third of the NumPy time went
to fresh temporaries and their page faults). ``tests/optimizers/test_kernels.py`` checks each
kernel against the NumPy functions. Every random number comes from the run's own generator
(:class:`mawdo.streams.RunStreams`), drawn before the call or through a xoshiro256** state seeded
once from it (:func:`seed_xoshiro`). The WDO family's kernel is in
:mod:`mawdo.optimizers.wind_kernel`.
"""

from __future__ import annotations

import numpy as np
from numba import njit

from mawdo.util.shuffle import (  # noqa: F401  (re-exported)
    SHUFFLE_BATCH,
    fisher_yates_batch,
    shuffle_from_words,
    shuffle_values_from_words,
    words_per_permutation,
)
from mawdo.util.stablesort import stable_argsort

_LOW32 = np.uint64(0xFFFFFFFF)
_SHIFT32 = np.uint64(32)
SHIFT11 = np.uint64(11)
U53 = 1.0 / 9007199254740992.0


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
            else:  # (not np.argsort(kind="mergesort"): the same order, compiles 2 s faster)
                keys = np.empty(n)
                for k in range(n):
                    keys[k] = F[r, a + k]
                order = stable_argsort(keys)
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


# A 32-bit word ``x`` as a double without a uint64 -> double conversion (this CPU family has no
# SIMD one; the scalar conversion cost more than the xoshiro step): the double whose bits are
# ``0x4330000000000000 | x`` is ``2**52 + x`` exactly, so ``(it - 2**52) * 2**-32`` equals
# ``float(x) * 2**-32`` bit for bit for every ``x < 2**52``.
_MAGIC = np.uint64(0x4330000000000000)
_TWO52 = 4503599627370496.0


@njit(cache=True, nogil=True, inline="always")
def magic_bits(x):  # pragma: no cover - compiled
    """The bits of the double ``2**52 + x`` for a uint64 ``x < 2**52`` (view them as float64)."""
    return x | _MAGIC


@njit(cache=True, nogil=True, inline="always")
def magic_unit(bits_as_double):  # pragma: no cover - compiled
    """``x 2**-32`` from the double :func:`magic_bits` made of ``x``, bit for bit."""
    return (bits_as_double - _TWO52) * _U32


@njit(cache=True, nogil=True)
def halves_to_unit(words, r1, r2):  # pragma: no cover - compiled
    """``r1 = (w & 0xFFFFFFFF) 2**-32`` and ``r2 = (w >> 32) 2**-32`` of each uint64 word of
    ``words`` (1-D), through the magic-number conversion :func:`gwo_step` uses; ``r1, r2`` in
    ``[0, 1)``, same length, overwritten. Exposed so the tests can check the conversion."""
    lo = np.empty(words.size, np.uint64)
    hi = np.empty(words.size, np.uint64)
    for m in range(words.size):
        lo[m] = magic_bits(words[m] & _LOW32)
        hi[m] = magic_bits(words[m] >> _SHIFT32)
    lof, hif = lo.view(np.float64), hi.view(np.float64)
    for m in range(words.size):
        r1[m] = magic_unit(lof[m])
        r2[m] = magic_unit(hif[m])


@njit(cache=True, nogil=True, inline="always")
def _gwo_wolf(X, lead_x, q, i, a, r1, r2, lb, ub, out):  # pragma: no cover - compiled
    """Wolf ``i`` of run ``q``: Eqs. 3.3-3.7 and the clip, with ``r1[3 d + k]``, ``r2[3 d + k]``
    the uniforms of dimension ``d`` and leader ``k``."""
    two_a = 2.0 * a
    for d in range(X.shape[2]):
        x = X[q, i, d]
        acc = 0.0
        for k in range(3):
            L = lead_x[q, k, d]
            A = r1[3 * d + k] * two_a - a
            dist = abs(r2[3 * d + k] * (2.0 * L) - x) * A
            acc += L
            acc -= dist
        v = acc / 3.0
        if v > ub[d]:
            v = ub[d]
        elif v < lb[d]:
            v = lb[d]
        out[q, i, d] = v


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
    M = 3 * D
    # a wolf's words first (the xoshiro loop stores bits only), then its arithmetic
    lo, hi = np.empty(M, np.uint64), np.empty(M, np.uint64)
    lof, hif = lo.view(np.float64), hi.view(np.float64)
    r1, r2 = np.empty(M), np.empty(M)
    for q in range(R):
        # the run's generator state lives in locals (registers) for the whole run
        qq = q if use_rng else 0  # rng is a (1, 4) placeholder without use_rng
        s0, s1, s2, s3 = rng[qq, 0], rng[qq, 1], rng[qq, 2], rng[qq, 3]
        for i in range(N):
            if use_rng:
                for m in range(M):
                    wd, s0, s1, s2, s3 = xoshiro_step(s0, s1, s2, s3)
                    lo[m] = magic_bits(wd & _LOW32)
                    hi[m] = magic_bits(wd >> _SHIFT32)
                for m in range(M):
                    r1[m] = magic_unit(lof[m])
                    r2[m] = magic_unit(hif[m])
            else:
                for d in range(D):
                    for k in range(3):
                        r1[3 * d + k] = r[q, 0, k, i, d]
                        r2[3 * d + k] = r[q, 1, k, i, d]
            _gwo_wolf(X, lead_x, q, i, a, r1, r2, lb, ub, out)
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
