"""The WDO family's fused Numba iteration (:func:`wind_step`) and its inlined helpers.

:mod:`mawdo.optimizers.wind` holds the same equations as readable NumPy functions;
``tests/optimizers/test_kernels.py`` checks the kernel against them, and
``tests/optimizers/test_value_shuffles.py`` checks the in-place shuffle against the permutation
and gather it replaced.
"""

from __future__ import annotations

import numpy as np
from numba import njit

from mawdo.optimizers.kernels import SHIFT11, U53, xoshiro_step
from mawdo.util.shuffle import SHUFFLE_BATCH, bounded_draw


@njit(cache=True, nogil=True, error_model="numpy")
def wind_step(  # noqa: PLR0913 - one fused iteration needs every input
    p,
    u,
    pbest,
    pbest_f,
    rank,
    perm,
    rng,
    use_rng,
    coef_draw,
    coef,
    gstarts,
    guidance,
    w,
    gate,
    d_max,
    gravity,
    pressure,
    vmax,
    reflect,
    eta,
    lb,
    width,
    X,
):  # pragma: no cover - compiled
    """One WDO-family move of every parcel of every run, in place on ``p`` and ``u``.

    Long by design: one fused Numba iteration of the WDO family (the leaders and the shuffle
    are inlined helpers); separate kernels per component would add passes over the arrays.

    Parameters (shapes with ``R`` runs, ``N`` parcels, ``G`` groups, ``D`` dimensions)
    ----------
    p, u : (R, N, D) positions and velocities, updated in place.
    pbest : (R, N, D), pbest_f : (R, N)
        Personal bests; the group bests and the global best are located here.
    rank : (R, N) float
        Rank ``r_i`` of each parcel (population or group scope), 1 = best.
    perm : (R, N, D) int
        Permutation of the dimensions per parcel (Coriolis term ``u[perm]``); read only when
        ``use_rng`` is false.
    rng : (R, 4) uint64, use_rng : bool
        Per-run xoshiro256** states (:func:`seed_xoshiro`); when used, each parcel's permutation
        is the one :func:`shuffle_from_words` draws from the next
        ``words_per_permutation(D)`` outputs of its run's generator, applied to the velocities
        by :func:`shuffle_values` (no permutation is stored).
    coef_draw : int
        0: coefficients from ``coef``. 1: AWDO's ``a_t, g_t, RT_t, c_t ~ U[0, 1)`` drawn here,
        four outputs of the run's generator per iteration (53-bit uniforms), before any
        permutation; 2: four per parcel, before the parcel's permutation.
    coef : (R or 1, N or 1, 4)
        ``alpha, g, RT, c`` per parcel (or shared by the run's parcels) when ``coef_draw == 0``.
    gstarts : (G + 1,) int
        Group boundaries (contiguous groups).
    guidance : int
        0 ``B = tbest``, 1 ``B = gbest_g``, 2 hierarchical (Eq. 5) with weights ``w = (w1, w2,
        w3)`` and, when ``gate``, ``w3`` scaled by the distance gate of Eq. 10 (``d_max``).
    gravity : int
        Target of the gravity term ``-g (p - centre)``: 0 the origin (WDO, AWDO), 1 the
        parcel's group centroid (low-D stabilisation, Eqs. 22-23), 2 the mean position of the
        run's population, 3 the run's best-so-far ``tbest``, 4 no gravity term (``g = 0``; the
        coefficient draws are still made).
    pressure : int
        Rank weights of the pressure and Coriolis terms: 0 WDO's ``|1 - 1/r| RT`` and ``c/r``
        (Bayraktar 2013 Eq. 1), 1 AWDO's ``RT/r`` and ``c/r`` (Eq. 4), 2 rank-free ``RT`` and
        ``c``.
    vmax : float
        Velocity clamp (``inf``: none).
    reflect : bool, eta : float
        Reflect-damp boundary (Eqs. 15-16) or clip (Eq. 3).
    lb, width : (D,)
        Problem box: ``X = lb + (p + 1)/2 width`` is written to ``X[:, :N]``.
    """
    R, N, D = p.shape
    G = gstarts.size - 1
    gbest = np.empty(G, np.intp)
    w3e = np.empty(G)
    centre = np.zeros((G, D))
    up = np.empty(D)  # u[r, i][perm]: the Coriolis term's permuted velocity
    Bv = np.empty(D)  # guidance B of the parcel
    cw = np.empty(4)  # alpha, g, RT, c of the parcel
    for r in range(R):
        tb = run_leaders(p, pbest, pbest_f, r, gstarts, guidance, w, gate, d_max, gravity,
                         gbest, w3e, centre)  # fmt: skip
        # the run's generator lives in locals (registers) while its parcels move
        rr = r if use_rng else 0  # rng is a (1, 4) placeholder without use_rng
        s0, s1, s2, s3 = rng[rr, 0], rng[rr, 1], rng[rr, 2], rng[rr, 3]
        rc = r if coef.shape[0] > 1 else 0
        per_parcel = coef.shape[1] > 1
        if coef_draw == 1:
            for k in range(4):
                wd, s0, s1, s2, s3 = xoshiro_step(s0, s1, s2, s3)
                cw[k] = np.float64(wd >> SHIFT11) * U53
        for g in range(G):
            gb = gbest[g]  # a local: the compiler cannot tell that Bv's stores leave gbest alone
            lead = tb if guidance == 0 else gb
            denom = w[0] + w[1] + w3e[g]
            b1, b2, b3 = w[0] / denom, w[1] / denom, w3e[g] / denom
            for i in range(gstarts[g], gstarts[g + 1]):
                rk = rank[r, i]
                if coef_draw == 2:
                    for k in range(4):
                        wd, s0, s1, s2, s3 = xoshiro_step(s0, s1, s2, s3)
                        cw[k] = np.float64(wd >> SHIFT11) * U53
                if coef_draw == 0:
                    ci = i if per_parcel else 0
                    for k in range(4):
                        cw[k] = coef[rc, ci, k]
                a1 = 1.0 - cw[0]
                grav = cw[1] if gravity != 4 else 0.0
                RT = cw[2]
                if pressure == 2:  # rank-free
                    wp, wc = RT, cw[3]
                else:  # pressure and Coriolis weights
                    wp = RT / rk if pressure == 1 else abs(1.0 - 1.0 / rk) * RT
                    wc = cw[3] / rk
                # shuffling a copy of the velocities with the swaps that would build the
                # permutation gives u[perm] with no index array and no gather
                if use_rng:
                    for d in range(D):
                        up[d] = u[r, i, d]
                    s0, s1, s2, s3 = shuffle_values(up, s0, s1, s2, s3)
                else:
                    for d in range(D):
                        up[d] = u[r, i, perm[r, i, d]]
                if guidance == 2:  # Eq. 5 renormalised, the division folded into the weights
                    for d in range(D):
                        Bv[d] = b1 * pbest[r, i, d] + b2 * pbest[r, gb, d] + b3 * pbest[r, tb, d]
                else:
                    for d in range(D):
                        Bv[d] = pbest[r, lead, d]
                # one loop per boundary policy: no branch on the policy inside the hot loop
                if reflect:
                    for d in range(D):
                        q = p[r, i, d]
                        v = a1 * u[r, i, d] - grav * (q - centre[g, d]) + wp * (Bv[d] - q)
                        v = min(max(v + wc * up[d], -vmax), vmax)
                        q = q + v
                        over = q > 1.0
                        under = q < -1.0
                        q = 2.0 - q if over else (-2.0 - q if under else q)
                        v = -eta * v if (over or under) else v
                        p[r, i, d] = min(max(q, -1.0), 1.0)
                        u[r, i, d] = v
                else:
                    for d in range(D):
                        q = p[r, i, d]
                        v = a1 * u[r, i, d] - grav * (q - centre[g, d]) + wp * (Bv[d] - q)
                        v = min(max(v + wc * up[d], -vmax), vmax)
                        p[r, i, d] = min(max(q + v, -1.0), 1.0)
                        u[r, i, d] = v
                for d in range(D):
                    X[r, i, d] = lb[d] + (p[r, i, d] + 1.0) * 0.5 * width[d]
        if use_rng:
            rng[r, 0], rng[r, 1], rng[r, 2], rng[r, 3] = s0, s1, s2, s3


@njit(cache=True, nogil=True, inline="always")
def run_leaders(p, pbest, pbest_f, r, gstarts, guidance, w, gate, d_max, gravity, gbest, w3e,
                centre):  # fmt: skip  # pragma: no cover - compiled
    """Run ``r``'s leaders for :func:`wind_step`: each group's best parcel ``gbest (G,)``, the
    gated ``w3`` of each group ``w3e (G,)`` (Eq. 10), and each group's gravity target
    ``centre (G, D)`` for ``gravity`` 1-3 (group centroid, Eqs. 22-23; population mean; tbest),
    left as it is otherwise (zeros: the origin); returns ``tbest``'s index (first minima, as
    argmin)."""
    G = gstarts.size - 1
    D = p.shape[2]
    tb = 0
    for g in range(G):
        best = gstarts[g]
        for k in range(gstarts[g] + 1, gstarts[g + 1]):
            if pbest_f[r, k] < pbest_f[r, best]:
                best = k
        gbest[g] = best
        if pbest_f[r, best] < pbest_f[r, tb] or g == 0:
            tb = best
    for g in range(G):
        w3e[g] = w[2]
        if guidance == 2 and gate:
            acc = 0.0
            for d in range(D):
                diff = pbest[r, gbest[g], d] - pbest[r, tb, d]
                acc += diff * diff
            w3e[g] = w[2] * min(1.0, np.sqrt(acc) / d_max)
        if gravity == 1 or (gravity == 2 and g == 0):
            # the population mean is the centroid of the one segment [0, N), shared by the groups
            a, b = (gstarts[g], gstarts[g + 1]) if gravity == 1 else (0, p.shape[1])
            for d in range(D):
                acc = 0.0
                for k in range(a, b):
                    acc += p[r, k, d]
                centre[g, d] = acc / (b - a)
        elif gravity == 2:
            for d in range(D):
                centre[g, d] = centre[0, d]
        elif gravity == 3:
            for d in range(D):
                centre[g, d] = pbest[r, tb, d]
    return tb


@njit(cache=True, nogil=True, inline="always")
def shuffle_values(vals, s0, s1, s2, s3):  # pragma: no cover - compiled
    """Permute ``vals`` ``(d,)`` in place as ``vals[perm]``, ``perm`` being the permutation
    :func:`shuffle_from_words` builds from the next ``words_per_permutation(d)`` outputs of the
    xoshiro256** state ``(s0, s1, s2, s3)``; returns the advanced state.

    The same Fisher-Yates swaps applied to the values instead of to ``range(d)``: swap ``k``
    exchanges the entries at ``k`` and ``j``, so entry ``k`` ends up holding ``vals[perm[k]]``.
    Words are drawn when :func:`shuffle_from_words` moves to its next one, so the state advances
    by exactly the words it would read.
    """
    d = vals.shape[0]
    if d < 2:
        return s0, s1, s2, s3
    x, s0, s1, s2, s3 = xoshiro_step(s0, s1, s2, s3)
    prod = 1
    for k in range(d - 1, 0, -1):
        n = k + 1
        if prod * n > SHUFFLE_BATCH:
            x, s0, s1, s2, s3 = xoshiro_step(s0, s1, s2, s3)
            prod = 1
        prod *= n
        j, x = bounded_draw(x, n)
        tmp = vals[k]
        vals[k] = vals[j]
        vals[j] = tmp
    return s0, s1, s2, s3
