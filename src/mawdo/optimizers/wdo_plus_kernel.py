"""WDO+'s fused Numba move (:func:`plus_step`): one pass over every parcel of every run, and
its bookkeeping after each evaluation (:func:`plus_tell`), one more.

The equations are those of :mod:`mawdo.optimizers.wdo_plus` (its module docstring);
``tests/optimizers/test_wdo_plus.py`` checks this kernel against a step computed by hand on a
fixed population with fixed draws, and the in-kernel draws against the explicit-draw path.
The Coriolis shuffle is the WDO kernel's (:func:`mawdo.optimizers.wind_kernel.shuffle_values`),
so a run's permutations come from its own xoshiro256** state as in ``wdo``.
"""

from __future__ import annotations

import numpy as np
from numba import njit

from mawdo.optimizers.kernels import magic_bits, magic_unit, xoshiro_step
from mawdo.optimizers.wind_kernel import shuffle_values

CENTRES = ("origin", "mean", "best")
"""Gravity references: WDO's box centre, the mean of the personal bests, the global best."""
BOUNDS = ("clip", "midpoint")
"""Boundary handling: WDO's clip, or halfway from the old position to the crossed bound."""

SQRT3 = np.sqrt(3.0)  # (2U - 1) sqrt(3) has unit variance
LOW32 = np.uint64(0xFFFFFFFF)
SHIFT32 = np.uint64(32)


@njit(cache=True, nogil=True, error_model="numpy")
def plus_step(  # noqa: PLR0913 - one fused iteration needs every input
    p,
    u,
    pbest,
    pbest_f,
    rank,
    sigma,
    hold,
    coef,
    centre_mode,
    vmax,
    midpoint,
    random_pressure,
    perm,
    noise,
    press,
    rng,
    use_rng,
    lb,
    width,
    X,
):  # pragma: no cover - compiled
    """One WDO+ move of every parcel of every run, in place on ``p`` and ``u``.

    Long by design, like :func:`~mawdo.optimizers.wind_kernel.wind_step`: one fused pass;
    separate kernels per component would add passes over the arrays.

    Parameters (``R`` runs, ``N`` parcels, ``D`` dimensions; positions in ``[-1, 1]^D``)
    ----------
    p, u : (R, N, D) positions and velocities, updated in place.
    pbest : (R, N, D), pbest_f : (R, N)
        Personal bests: the global best ``tbest`` (first least ``pbest_f``) and the gravity
        reference are taken here.
    rank : (R, N) float
        1-based rank of each parcel's current value (1 = best).
    sigma : (R,)
        Each run's success-adapted step of the velocity noise, normalised units.
    hold : (R,) bool
        Runs whose population was just (re)drawn: positions are returned unmoved, no draws.
    coef : (4,)
        ``alpha, g, RT, c`` (friction, gravity, pressure, Coriolis).
    centre_mode : int
        Gravity reference: 0 the origin (WDO), 1 the mean of the run's ``pbest``, 2 ``tbest``.
    vmax : float
        Velocity clamp.
    midpoint : bool
        A coordinate that leaves ``[-1, 1]`` lands halfway between its old value and the bound
        (velocity set to the step taken); otherwise it is clipped (WDO, Eq. 3).
    random_pressure : bool
        Weigh the pressure term of each coordinate by its own ``U[0, 1)`` draw ``w``.
    perm : (R, N, D) int, noise, press : (R, N, D) float
        Explicit Coriolis permutations, noise ``xi`` (unit variance) and pressure weights ``w``,
        read when ``use_rng`` is false (tests).
    rng : (R, 4) uint64, use_rng : bool
        Per-run xoshiro256** states. Each parcel draws its permutation
        (:func:`shuffle_values`), then one word per coordinate: its low 32 bits give ``U`` for
        ``xi = (2U - 1) sqrt 3``, its high 32 bits ``w`` (``k 2**-32`` for a half ``k``).
    lb, width : (D,)
        Problem box: ``X = lb + (p + 1)/2 width``.
    X : (R, N, D)
        Output: the new positions in problem coordinates.
    """
    R, N, D = p.shape
    up = np.empty(D)
    xi = np.empty(D)
    ref = np.empty(D)
    wr = np.ones(D)  # the pressure weights (all 1 without random_pressure)
    # a parcel's words first (the xoshiro loop stores bits only), then the conversions in a
    # loop that vectorises, as in gwo_step: 0.79 -> 0.68 ms per 30 x 50 x 30 iteration
    lo = np.empty(D, np.uint64)
    hi = np.empty(D, np.uint64)
    lof, hif = lo.view(np.float64), hi.view(np.float64)
    a1 = 1.0 - coef[0]
    grav, RT, cor = coef[1], coef[2], coef[3]
    for r in range(R):
        if hold[r]:
            for i in range(N):
                for d in range(D):
                    X[r, i, d] = lb[d] + (p[r, i, d] + 1.0) * 0.5 * width[d]
            continue
        tb = 0
        for k in range(1, N):
            if pbest_f[r, k] < pbest_f[r, tb]:
                tb = k
        for d in range(D):
            ref[d] = 0.0
            if centre_mode == 2:
                ref[d] = pbest[r, tb, d]
        if centre_mode == 1:
            for k in range(N):
                for d in range(D):
                    ref[d] += pbest[r, k, d]
            for d in range(D):
                ref[d] /= N
        rr = r if use_rng else 0
        s0, s1, s2, s3 = rng[rr, 0], rng[rr, 1], rng[rr, 2], rng[rr, 3]
        sg = sigma[r]
        for i in range(N):
            rk = rank[r, i]
            wp = abs(1.0 - 1.0 / rk) * RT
            wc = cor / rk
            if use_rng:
                for d in range(D):
                    up[d] = u[r, i, d]
                s0, s1, s2, s3 = shuffle_values(up, s0, s1, s2, s3)
                for d in range(D):
                    # one word, two 32-bit uniforms: the noise's (low half) and the pressure
                    # weight's (high half), as doubles 2**52 + half (magic_bits)
                    wd, s0, s1, s2, s3 = xoshiro_step(s0, s1, s2, s3)
                    lo[d] = magic_bits(wd & LOW32)
                    hi[d] = magic_bits(wd >> SHIFT32)
                for d in range(D):
                    xi[d] = (2.0 * magic_unit(lof[d]) - 1.0) * SQRT3
                if random_pressure:
                    for d in range(D):
                        wr[d] = magic_unit(hif[d])
            else:
                for d in range(D):
                    up[d] = u[r, i, perm[r, i, d]]
                    xi[d] = noise[r, i, d]
                    if random_pressure:
                        wr[d] = press[r, i, d]
            # one loop per boundary rule, each with selects only: no branch in the hot loop
            if midpoint:
                for d in range(D):
                    q = p[r, i, d]
                    v = a1 * u[r, i, d] - grav * (q - ref[d]) + wp * wr[d] * (pbest[r, tb, d] - q)
                    v = min(max(v + wc * up[d] + sg * xi[d], -vmax), vmax)
                    qn = q + v
                    qn = 0.5 * (q + 1.0) if qn > 1.0 else (0.5 * (q - 1.0) if qn < -1.0 else qn)
                    p[r, i, d] = qn
                    u[r, i, d] = qn - q
                    X[r, i, d] = lb[d] + (qn + 1.0) * 0.5 * width[d]
            else:
                for d in range(D):
                    q = p[r, i, d]
                    v = a1 * u[r, i, d] - grav * (q - ref[d]) + wp * wr[d] * (pbest[r, tb, d] - q)
                    v = min(max(v + wc * up[d] + sg * xi[d], -vmax), vmax)
                    qn = min(max(q + v, -1.0), 1.0)
                    p[r, i, d] = qn
                    u[r, i, d] = v
                    X[r, i, d] = lb[d] + (qn + 1.0) * 0.5 * width[d]
        if use_rng:
            rng[r, 0], rng[r, 1], rng[r, 2], rng[r, 3] = s0, s1, s2, s3


@njit(cache=True, nogil=True, error_model="numpy")
def plus_tell(F, p, f, pbest, pbest_f, sigma, hold, gain, vmax, best, stall, limit, sigma_min,
              restart, mask):  # fmt: skip  # pragma: no cover - compiled
    """WDO+'s bookkeeping after an evaluation, every run in one pass, in place; returns the
    number of runs to restart.

    The same numbers as the NumPy reference ``success_sigma`` (on moved runs, when ``gain`` is
    given), then ``f = F`` and the personal bests (:func:`update_personal_best`), then
    ``stalled`` (when ``restart``), with no ``(R,)`` temporaries (twelve NumPy calls per
    iteration before); ``tests/optimizers/test_wdo_plus.py`` checks it against them.

    Parameters (``R`` runs, ``N`` parcels, ``D`` dimensions)
    ----------
    F : (R, N) float
        The values of the positions ``p`` (R, N, D).
    f, pbest, pbest_f
        Current values ``(R, N)`` and personal bests, updated.
    sigma : (R,)
        Noise steps: a moved run with ``k`` of ``N`` parcels better than their personal best
        takes ``min(sigma gain[k], vmax)``. ``gain (N + 1,)`` is the success rule's factor
        ``exp((k/N - target) / ((1 - target) damp))`` computed by NumPy (the same ``exp``
        as the reference); an empty ``gain`` leaves ``sigma`` alone (no adaptation).
    hold : (R,) bool
        Runs evaluated unmoved (their success is not counted); all cleared.
    best, stall : (R,)
        Best value since the last restart and iterations without improvement, updated when
        ``restart``.
    limit : int, sigma_min : float
        A run restarts when ``stall >= limit`` or ``sigma < sigma_min``.
    mask : (R,) bool
        Output: the runs to restart (all false without ``restart``).
    """
    R, N, D = p.shape
    adapt = gain.size > 0
    n = 0
    for r in range(R):
        k = 0
        run_best = np.inf
        for i in range(N):
            fi = F[r, i]
            f[r, i] = fi
            if fi < pbest_f[r, i]:  # a success is exactly a personal-best update
                k += 1
                pbest_f[r, i] = fi
                for d in range(D):
                    pbest[r, i, d] = p[r, i, d]
            run_best = min(run_best, pbest_f[r, i])
        if adapt and not hold[r]:
            s = sigma[r] * gain[k]
            sigma[r] = vmax if s > vmax else s  # np.minimum: a nan stays nan
        hold[r] = False
        mask[r] = False
        if restart:
            b = best[r]
            tol = 1e-12 * abs(b) if np.isfinite(b) else 0.0
            stall[r] = 0 if run_best < b - tol else stall[r] + 1
            best[r] = min(b, run_best)
            mask[r] = stall[r] >= limit or sigma[r] < sigma_min
            n += mask[r]
    return n
