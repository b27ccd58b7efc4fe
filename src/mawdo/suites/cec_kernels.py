"""The C code's shared steps on a whole population, as Numba loops in its order: the rotation
(``rotatefunc``), the Lunacek bi-Rastrigin (``bi_rastrigin_func``, which does its own shifting)
and the composition's weighting (``cf_cal``)."""

from __future__ import annotations

import math

import numpy as np

from mawdo.suites.cec_basic import PI, kernel

INF = 1.0e99


@kernel
def rotate(y, matrix_t):
    """``rotatefunc``: ``z_i = sum_j y_j M_ij`` for every row of ``y``, given ``M`` transposed
    (contiguous), summed over j in order.

    Not ``y @ M.T``: a BLAS product rounds a row differently by batch size (gemv for one row,
    gemm blocks for many), which would make a point's value depend on the other points of its
    batch. Here each ``z_i`` adds its terms in the C code's order, whatever the batch; the loop
    runs over i innermost so that it vectorises without reordering any sum.
    """
    n, d = y.shape
    z = np.zeros((n, d))
    for r in range(n):
        for j in range(d):
            yj = y[r, j]
            for i in range(d):
                z[r, i] += yj * matrix_t[j, i]
    return z


@kernel
def bi_rastrigin(x, shift, matrix_t, shifted, rotated):
    """Lunacek bi-Rastrigin of the raw points ``x`` (n, k), as ``bi_rastrigin_func``.

    ``shift`` gives the sign of each coordinate's mirror (the C code reads it even when it does
    not shift, inside a hybrid); the rotation (transposed) is used only when ``rotated``.
    """
    n, k = x.shape
    mu0, d = 2.5, 1.0
    s = 1.0 - 1.0 / (2.0 * math.pow(k + 20.0, 0.5) - 8.2)
    mu1 = -math.pow((mu0 * mu0 - d) / s, 0.5)
    z = np.empty((n, k))
    f = np.empty(n)
    for r in range(n):
        t1 = t2 = 0.0
        for i in range(k):
            y = (x[r, i] - shift[i]) if shifted else x[r, i]
            y *= 10.0 / 100.0
            v = 2 * y
            if shift[i] < 0.0:
                v *= -1.0
            z[r, i] = v
            t = v + mu0
            t1 += (t - mu0) * (t - mu0)
            t2 += (t - mu1) * (t - mu1)
        f[r] = t1 if t1 < t2 * s + d * k else t2 * s + d * k
    c = rotate(z, matrix_t) if rotated else z
    for r in range(n):
        acc = 0.0
        for i in range(k):
            acc += math.cos(2.0 * PI * c[r, i])
        f[r] += 10.0 * (k - acc)
    return f


@kernel
def cf_cal(x, shifts, deltas, fits):
    """``cf_cal``: the components' values ``fits`` (n, c; biases added) weighted by
    ``w_i = exp(-|x - o_i|^2 / (2 D delta_i^2)) / |x - o_i|`` (1e99 at ``o_i``; equal weights
    where every ``w_i`` underflows)."""
    n, dim = x.shape
    c = fits.shape[1]
    f = np.empty(n)
    w = np.empty(c)
    for r in range(n):
        w_max = w_sum = 0.0
        for i in range(c):
            d2 = 0.0
            for j in range(dim):
                d2 += (x[r, j] - shifts[i, j]) * (x[r, j] - shifts[i, j])
            if d2 != 0:
                w[i] = math.pow(1.0 / d2, 0.5) * math.exp(-d2 / 2.0 / dim / (deltas[i] ** 2))
            else:
                w[i] = INF
            if w[i] > w_max:
                w_max = w[i]
        for i in range(c):
            w_sum += w[i]
        if w_max == 0:
            w[:] = 1.0
            w_sum = c
        acc = 0.0
        for i in range(c):
            acc += w[i] / w_sum * fits[r, i]
        f[r] = acc
    return f
