"""The C code's shared steps on a block of points, as Numba loops in its order: the shift and
rotation (``sr_func``, ``rotatefunc``), the Lunacek bi-Rastrigin (``bi_rastrigin_func``, which
does its own shifting), the composition's weighting (``cf_cal``) and the choice of a basic
function by its code.

Points of a block are held transposed, ``(D, B)``: the rotation then runs over the block's
points innermost, which vectorises without reordering any sum (each ``z_i`` still adds its
terms ``y_j M_ij`` in the C code's order ``j = 1..D``). A BLAS product (``y @ M.T``) would
round a row differently by batch size (gemv for one row, gemm blocks for many), so a point's
value would depend on the other points of its batch.
"""

from __future__ import annotations

import math

import numpy as np

from mawdo.suites import cec_basic as B
from mawdo.suites.cec_basic import PI, kernel

INF = 1.0e99


@kernel
def transpose(x, r0, m, xt):
    """``xt[j, r] = x[r0 + r, j]``: the block's ``m`` points as columns."""
    for r in range(m):
        xr = x[r0 + r]
        for j in range(xt.shape[0]):
            xt[j, r] = xr[j]


@kernel
def shift_t(xt, m, shift, rate, yt):
    """``yt[j, r] = (xt[j, r] - shift[j]) * rate`` for the block's first ``m`` points."""
    for j in range(xt.shape[0]):
        xj, yj, sj = xt[j], yt[j], shift[j]
        for r in range(m):
            yj[r] = (xj[r] - sj) * rate


@kernel
def rotate_t(yt, m, matrix, zt):
    """``rotatefunc`` on the first ``m`` columns: ``zt[i, r] = sum_j M_ij yt[j, r]``, summed
    over j in order (four terms per pass over the block, added one after the other)."""
    d = yt.shape[0]
    if m < 8:  # a few points: one sum at a time (the vector loop would not fill)
        for i in range(d):
            for r in range(m):
                acc = 0.0
                for j in range(d):
                    acc += yt[j, r] * matrix[i, j]
                zt[i, r] = acc
        return
    for i in range(d):
        zi, mi = zt[i], matrix[i]
        for r in range(m):
            zi[r] = 0.0
        j4 = d - d % 4
        for j in range(0, j4, 4):
            m0, m1, m2, m3 = mi[j], mi[j + 1], mi[j + 2], mi[j + 3]
            y0, y1, y2, y3 = yt[j], yt[j + 1], yt[j + 2], yt[j + 3]
            for r in range(m):
                acc = zi[r] + y0[r] * m0
                acc += y1[r] * m1
                acc += y2[r] * m2
                zi[r] = acc + y3[r] * m3
        for j in range(j4, d):
            mij, yj = mi[j], yt[j]
            for r in range(m):
                zi[r] += yj[r] * mij


@kernel
def bi_rastrigin(x, k, m, shift, t, z, out):
    """``bi_rastrigin_func`` without its rotation, on ``x`` (>= k, B): the points already
    shifted (or, inside a hybrid, not), before its own scaling by 1/10. Writes the smaller of
    the two spheres to ``out`` and leaves the mirrored point ``2 sign(o) y`` in ``z``, for
    :func:`bi_rastrigin_tail` after the rotation; ``shift`` gives the mirror's signs even where
    the point is not shifted, as in the C code's hybrids; ``t`` is
    :func:`~mawdo.suites.cec_basic.constants`' row."""
    mu0, d = 2.5, 1.0
    s, mu1 = t[0], t[1]
    t2 = np.zeros(m)
    out[:m] = 0.0
    for i in range(k):
        xi, zi = x[i], z[i]
        sign = -1.0 if shift[i] < 0.0 else 1.0
        for r in range(m):
            v = 2 * (xi[r] * (10.0 / 100.0))
            if sign < 0.0:
                v *= -1.0
            zi[r] = v
            u = v + mu0
            out[r] += (u - mu0) * (u - mu0)
            t2[r] += (u - mu1) * (u - mu1)
    for r in range(m):
        if not out[r] < t2[r] * s + d * k:
            out[r] = t2[r] * s + d * k


@kernel
def bi_rastrigin_tail(c, k, m, out):
    """Second part of ``bi_rastrigin_func``: adds ``10 (k - sum cos 2 pi c_i)`` of the
    (rotated) mirrored points ``c`` (>= k, B) to ``out``."""
    acc = np.zeros(m)
    for i in range(k):
        ci = c[i]
        for r in range(m):
            acc[r] += math.cos(2.0 * PI * ci[r])
    for r in range(m):
        out[r] += 10.0 * (k - acc[r])


@kernel
def basic(code, z, k, m, t, out):
    """Basic function ``code`` (its index in :data:`~mawdo.suites.cec_basic.NAMES`) of the
    block ``z`` (>= k, B) into ``out`` (m,), with its
    :func:`~mawdo.suites.cec_basic.constants` row ``t``."""
    if code == 0:
        B.bent_cigar(z, k, m, t, out)
    elif code == 1:
        B.discus(z, k, m, t, out)
    elif code == 2:
        B.ellips(z, k, m, t, out)
    elif code == 3:
        B.sum_diff_pow(z, k, m, t, out)
    elif code == 4:
        B.zakharov(z, k, m, t, out)
    elif code == 5:
        B.rosenbrock(z, k, m, t, out)
    elif code == 6:
        B.rastrigin(z, k, m, t, out)
    elif code == 7:
        B.levy(z, k, m, 1.0, out)
    elif code == 8:
        B.levy(z, k, m, 0.0, out)
    elif code == 9:
        B.schwefel(z, k, m, t, out)
    elif code == 10:
        B.ackley(z, k, m, t, out)
    elif code == 11:
        B.weierstrass(z, k, m, t, out)
    elif code == 12:
        B.griewank(z, k, m, t, out)
    elif code == 13:
        B.katsuura(z, k, m, t, out)
    elif code == 14:
        B.grie_rosen(z, k, m, t, out)
    elif code == 15:
        B.escaffer6(z, k, m, t, out)
    elif code == 16:
        B.cat(z, k, m, False, out)
    elif code == 17:
        B.cat(z, k, m, True, out)
    elif code == 18:
        B.schaffer_f7(z, k, m, t, out)
    else:  # the Lunacek bi-Rastrigin is not one: it rotates in its middle
        out[:m] = math.nan


@kernel
def cf_cal(xt, m, shifts, deltas, fits, w, out):
    """``cf_cal`` at the block's points ``xt`` (D, B): the components' values ``fits`` (c, B;
    biases added) weighted by ``w_i = exp(-|x - o_i|^2 / (2 D delta_i^2)) / |x - o_i|``
    (1e99 at ``o_i``; equal weights where every ``w_i`` underflows), into ``out``. ``w``
    (c, B) is scratch."""
    dim = xt.shape[0]
    c = fits.shape[0]
    for i in range(c):
        wi = w[i]
        wi[:m] = 0.0
        for j in range(dim):
            xj, o = xt[j], shifts[i, j]
            for r in range(m):
                wi[r] += (xj[r] - o) * (xj[r] - o)
        for r in range(m):
            d2 = wi[r]
            if d2 != 0:
                wi[r] = math.pow(1.0 / d2, 0.5) * math.exp(-d2 / 2.0 / dim / (deltas[i] ** 2))
            else:
                wi[r] = INF
    for r in range(m):
        w_max = w_sum = 0.0
        for i in range(c):
            w_max = w[i, r] if w[i, r] > w_max else w_max
            w_sum += w[i, r]
        acc = 0.0
        for i in range(c):
            if w_max == 0:  # every weight underflowed: equal weights
                acc += 1.0 / c * fits[i, r]
            else:
                acc += w[i, r] / w_sum * fits[i, r]
        out[r] = acc
