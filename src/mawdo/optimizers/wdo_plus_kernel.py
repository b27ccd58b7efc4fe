"""WDO+'s fused Numba move (:func:`plus_step`): one pass over every parcel of every run.

The equations are those of :mod:`mawdo.optimizers.wdo_plus` (its module docstring);
``tests/optimizers/test_wdo_plus.py`` checks this kernel against a step computed by hand on a
fixed population with fixed draws, and the in-kernel draws against the explicit-draw path.
The Coriolis shuffle is the WDO kernel's (:func:`mawdo.optimizers.wind_kernel.shuffle_values`),
so a run's permutations come from its own xoshiro256** state as in ``wdo``.
"""

from __future__ import annotations

import numpy as np
from numba import njit

from mawdo.optimizers.kernels import xoshiro_step
from mawdo.optimizers.wind_kernel import shuffle_values

CENTRES = ("origin", "mean", "best")
"""Gravity references: WDO's box centre, the mean of the personal bests, the global best."""
BOUNDS = ("clip", "midpoint")
"""Boundary handling: WDO's clip, or halfway from the old position to the crossed bound."""

SQRT3 = np.sqrt(3.0)  # (2U - 1) sqrt(3) has unit variance
LOW32 = np.uint64(0xFFFFFFFF)
SHIFT32 = np.uint64(32)
U32 = 1.0 / 4294967296.0


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
    a1 = 1.0 - coef[0]
    grav, RT, cor = coef[1], coef[2], coef[3]
    for r in range(R):
        if not hold[r]:
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
                        # one word, two 32-bit uniforms: the noise's (low half) and the
                        # pressure weight's (high half); int64 -> double converts in one
                        # instruction where uint64 -> double does not
                        wd, s0, s1, s2, s3 = xoshiro_step(s0, s1, s2, s3)
                        xi[d] = (2.0 * (np.float64(np.int64(wd & LOW32)) * U32) - 1.0) * SQRT3
                        if random_pressure:
                            wr[d] = np.float64(np.int64(wd >> SHIFT32)) * U32
                else:
                    for d in range(D):
                        up[d] = u[r, i, perm[r, i, d]]
                        xi[d] = noise[r, i, d]
                        if random_pressure:
                            wr[d] = press[r, i, d]
                for d in range(D):
                    q = p[r, i, d]
                    v = a1 * u[r, i, d] - grav * (q - ref[d]) + wp * wr[d] * (pbest[r, tb, d] - q)
                    v = min(max(v + wc * up[d] + sg * xi[d], -vmax), vmax)
                    qn = q + v
                    if midpoint:
                        if qn > 1.0:
                            qn = 0.5 * (q + 1.0)
                        elif qn < -1.0:
                            qn = 0.5 * (q - 1.0)
                        v = qn - q
                    else:
                        qn = min(max(qn, -1.0), 1.0)
                    p[r, i, d] = qn
                    u[r, i, d] = v
            if use_rng:
                rng[r, 0], rng[r, 1], rng[r, 2], rng[r, 3] = s0, s1, s2, s3
        for i in range(N):
            for d in range(D):
                X[r, i, d] = lb[d] + (p[r, i, d] + 1.0) * 0.5 * width[d]
