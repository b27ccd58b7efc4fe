"""The basic functions of CEC 2017 / CEC 2022 on a whole population, as the official C code
computes them: Numba loops in the C code's order of operations.

Each function takes ``z`` of shape ``(n, k)``, the points after the official shift, scaling
and rotation (``sr_func`` of ``cec17_test_func.cpp``), and returns the ``n`` values. ``k`` is
the dimension the C code calls ``nx``: the full D for a plain or composition function, one
group's size inside a hybrid. Every sum and product runs term after term as in the C loops,
with the C library's ``pow``, ``sin``, ``cos``, ``exp``, ``fmod``: most values are bitwise
the C code's (tests/suites/test_cec_official.py). A NumPy pairwise sum instead rounded HGBat
near its optimum differently by up to 1e-11 relative.

Where the C code departs from the competitions' definitions, these functions follow the code
(docs/deviations.md#d-cec-official-code): Schaffer's F7 reads the shifted, unrotated point
(:func:`schaffer_f7` takes that point), the non-continuous Rastrigin is the plain Rastrigin
(its rounding is overwritten before use), and the CEC 2017 Levy function has its minimum at
``z = 1``, not at the shift.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

PI = 3.1415926535897932384626433832795029
E = 2.7182818284590452353602874713526625

RATE = {
    "rosenbrock": 2.048 / 100.0,
    "rastrigin": 5.12 / 100.0,
    "weierstrass": 0.5 / 100.0,
    "griewank": 600.0 / 100.0,
    "schwefel": 1000.0 / 100.0,
    "katsuura": 5.0 / 100.0,
    "grie_rosen": 5.0 / 100.0,
    "happycat": 5.0 / 100.0,
    "hgbat": 5.0 / 100.0,
}
"""``sh_rate`` of sr_func: the search box [-100, 100] scaled to each function's own (1 if
absent)."""

# IEEE division (x/0 -> inf or nan, as in C), not Python's ZeroDivisionError
kernel = njit(cache=True, nogil=True, error_model="numpy")


@kernel
def bent_cigar(z):
    """Bent Cigar: ``z_1^2 + 10^6 sum_{i>1} z_i^2``."""
    n, k = z.shape
    f = np.empty(n)
    for r in range(n):
        acc = z[r, 0] * z[r, 0]
        for i in range(1, k):
            acc += 1e6 * z[r, i] * z[r, i]
        f[r] = acc
    return f


@kernel
def discus(z):
    """Discus: ``10^6 z_1^2 + sum_{i>1} z_i^2``."""
    n, k = z.shape
    f = np.empty(n)
    for r in range(n):
        acc = 1e6 * z[r, 0] * z[r, 0]
        for i in range(1, k):
            acc += z[r, i] * z[r, i]
        f[r] = acc
    return f


@kernel
def ellips(z):
    """High-conditioned elliptic: ``sum_i 10^(6 (i-1)/(k-1)) z_i^2``."""
    n, k = z.shape
    f = np.zeros(n)
    for r in range(n):
        for i in range(k):
            f[r] += math.pow(10.0, 6.0 * i / (k - 1)) * z[r, i] * z[r, i]
    return f


@kernel
def sum_diff_pow(z):
    """Sum of different powers: ``sum_i |z_i|^i`` (i from 1)."""
    n, k = z.shape
    f = np.zeros(n)
    for r in range(n):
        for i in range(k):
            f[r] += math.pow(abs(z[r, i]), i + 1.0)
    return f


@kernel
def zakharov(z):
    """Zakharov: ``sum z_i^2 + s^2 + s^4`` with ``s = sum 0.5 i z_i``."""
    n, k = z.shape
    f = np.empty(n)
    for r in range(n):
        s1 = s2 = 0.0
        for i in range(k):
            s1 += z[r, i] * z[r, i]
            s2 += 0.5 * (i + 1) * z[r, i]
        f[r] = s1 + s2 * s2 + math.pow(s2, 4.0)
    return f


@kernel
def rosenbrock(z):
    """Rosenbrock on ``z + 1``: ``sum 100 (z_i^2 - z_{i+1})^2 + (z_i - 1)^2``."""
    n, k = z.shape
    f = np.zeros(n)
    for r in range(n):
        a = z[r, 0] + 1.0
        for i in range(k - 1):
            b = z[r, i + 1] + 1.0
            t1 = a * a - b
            t2 = a - 1.0
            f[r] += 100.0 * t1 * t1 + t2 * t2
            a = b
    return f


@kernel
def rastrigin(z):
    """Rastrigin: ``sum z_i^2 - 10 cos(2 pi z_i) + 10``."""
    n, k = z.shape
    f = np.zeros(n)
    for r in range(n):
        for i in range(k):
            f[r] += z[r, i] * z[r, i] - 10.0 * math.cos(2.0 * PI * z[r, i]) + 10.0
    return f


@kernel
def schaffer_f7(y):
    """Schaffer's F7 on ``y`` (the C code's shifted, unrotated point):
    ``(1/(k-1) sum sqrt(s_i) (1 + sin^2(50 s_i^0.2)))^2``, ``s_i = sqrt(y_i^2 + y_{i+1}^2)``."""
    n, k = y.shape
    f = np.zeros(n)
    for r in range(n):
        for i in range(k - 1):
            s = math.pow(y[r, i] * y[r, i] + y[r, i + 1] * y[r, i + 1], 0.5)
            t = math.sin(50.0 * math.pow(s, 0.2))
            f[r] += math.pow(s, 0.5) + math.pow(s, 0.5) * t * t
        f[r] = f[r] * f[r] / (k - 1) / (k - 1)
    return f


@kernel
def _levy(z, offset):
    n, k = z.shape
    f = np.empty(n)
    for r in range(n):
        w0 = 1.0 + (z[r, 0] - offset) / 4.0
        wl = 1.0 + (z[r, k - 1] - offset) / 4.0
        s0, sl = math.sin(PI * w0), math.sin(2 * PI * wl)
        acc = 0.0
        for i in range(k - 1):
            w = 1.0 + (z[r, i] - offset) / 4.0
            t = math.sin(PI * w + 1)
            acc += (w - 1) * (w - 1) * (1 + 10 * (t * t))
        f[r] = s0 * s0 + acc + (wl - 1) * (wl - 1) * (1 + sl * sl)
    return f


def levy2017(z):
    """CEC 2017's Levy: ``w = 1 + (z - 1)/4``, minimum at ``z = 1``."""
    return _levy(z, 1.0)


def levy2022(z):
    """CEC 2022's Levy: ``w = 1 + z/4``."""
    return _levy(z, 0.0)


@kernel
def schwefel(z):
    """Modified Schwefel on ``z + 420.9687462275036``, with its penalty beyond +-500."""
    n, k = z.shape
    f = np.zeros(n)
    for r in range(n):
        acc = 0.0
        for i in range(k):
            v = z[r, i] + 4.209687462275036e002
            if v > 500:
                m = 500.0 - v % 500.0  # fmod: v > 0 here, and fmod is exact
                acc -= m * math.sin(math.pow(m, 0.5))
                t = (v - 500.0) / 100
                acc += t * t / k
            elif v < -500:
                a = abs(v) % 500.0
                acc -= (-500.0 + a) * math.sin(math.pow(500.0 - a, 0.5))
                t = (v + 500.0) / 100
                acc += t * t / k
            else:
                acc -= v * math.sin(math.pow(abs(v), 0.5))
        f[r] = acc + 4.189828872724338e002 * k
    return f


@kernel
def ackley(z):
    """Ackley: ``e - 20 exp(-0.2 sqrt(mean z^2)) - exp(mean cos 2 pi z) + 20``."""
    n, k = z.shape
    f = np.empty(n)
    for r in range(n):
        s1 = s2 = 0.0
        for i in range(k):
            s1 += z[r, i] * z[r, i]
            s2 += math.cos(2.0 * PI * z[r, i])
        s1 = -0.2 * math.sqrt(s1 / k)
        s2 /= k
        f[r] = E - 20.0 * math.exp(s1) - math.exp(s2) + 20.0
    return f


@kernel
def weierstrass(z):
    """Weierstrass (a = 0.5, b = 3, k_max = 20), minus its value at 0.

    ``a^j`` and ``b^j`` are exact doubles and the value at 0 does not depend on the point, so
    they are computed once instead of per coordinate as in the C code: the same numbers.
    """
    n, k = z.shape
    f = np.zeros(n)
    aj, bj = np.empty(21), np.empty(21)
    s2 = 0.0
    for j in range(21):
        aj[j], bj[j] = math.pow(0.5, j), math.pow(3.0, j)
        s2 += aj[j] * math.cos(2.0 * PI * bj[j] * 0.5)
    for r in range(n):
        for i in range(k):
            s = 0.0
            for j in range(21):
                s += aj[j] * math.cos(2.0 * PI * bj[j] * (z[r, i] + 0.5))
            f[r] += s
        f[r] -= k * s2
    return f


@kernel
def griewank(z):
    """Griewank: ``1 + sum z_i^2/4000 - prod cos(z_i/sqrt(i))``."""
    n, k = z.shape
    f = np.empty(n)
    for r in range(n):
        s, p = 0.0, 1.0
        for i in range(k):
            s += z[r, i] * z[r, i]
            p *= math.cos(z[r, i] / math.sqrt(1.0 + i))
        f[r] = 1.0 + s / 4000.0 - p
    return f


@kernel
def katsuura(z):
    """Katsuura: ``c prod (1 + i sum_j |2^j z_i - round(2^j z_i)|/2^j)^(10/k^1.2) - c``,
    ``c = 10/k^2``."""
    n, k = z.shape
    f = np.empty(n)
    e = 10.0 / math.pow(1.0 * k, 1.2)
    c = 10.0 / k / k
    p2 = np.empty(33)
    for j in range(1, 33):
        p2[j] = math.pow(2.0, j)  # exact
    for r in range(n):
        p = 1.0
        for i in range(k):
            temp = 0.0
            for j in range(1, 33):
                t1 = p2[j]
                t2 = t1 * z[r, i]
                temp += abs(t2 - math.floor(t2 + 0.5)) / t1
            p *= math.pow(1.0 + (i + 1) * temp, e)
        f[r] = p * c - c
    return f


@kernel
def grie_rosen(z):
    """Expanded Griewank plus Rosenbrock on ``z + 1``, pairs ``(z_i, z_{i+1})`` then
    ``(z_k, z_1)``."""
    n, k = z.shape
    f = np.zeros(n)
    for r in range(n):
        for i in range(k):
            a, b = z[r, i] + 1.0, z[r, (i + 1) % k] + 1.0
            t1 = a * a - b
            t2 = a - 1.0
            t = 100.0 * t1 * t1 + t2 * t2
            f[r] += t * t / 4000.0 - math.cos(t) + 1.0
    return f


@kernel
def escaffer6(z):
    """Expanded Schaffer's F6, pairs ``(z_i, z_{i+1})`` then ``(z_k, z_1)``."""
    n, k = z.shape
    f = np.zeros(n)
    for r in range(n):
        for i in range(k):
            a, b = z[r, i], z[r, (i + 1) % k]
            t1 = math.sin(math.sqrt(a * a + b * b))
            t1 = t1 * t1
            t2 = 1.0 + 0.001 * (a * a + b * b)
            f[r] += 0.5 + (t1 - 0.5) / (t2 * t2)
    return f


@kernel
def _cat(z, hg):
    n, k = z.shape
    f = np.empty(n)
    for r in range(n):
        r2 = s = 0.0
        for i in range(k):
            v = z[r, i] - 1.0
            r2 += v * v
            s += v
        if hg:  # HGBat: |r2^2 - s^2|^(1/2)
            f[r] = math.pow(abs(r2 * r2 - s * s), 0.5) + (0.5 * r2 + s) / k + 0.5
        else:  # HappyCat: |r2 - k|^(1/4)
            f[r] = math.pow(abs(r2 - k), 0.25) + (0.5 * r2 + s) / k + 0.5
    return f


def happycat(z):
    """HappyCat on ``z - 1``: ``|r2 - k|^(1/4) + (r2/2 + sum z)/k + 1/2``."""
    return _cat(z, False)


def hgbat(z):
    """HGBat on ``z - 1``: ``|r2^2 - (sum z)^2|^(1/2) + (r2/2 + sum z)/k + 1/2``."""
    return _cat(z, True)


BASIC = {
    f.__name__: f
    for f in (
        bent_cigar, discus, ellips, sum_diff_pow, zakharov, rosenbrock, rastrigin, levy2017,
        levy2022, schwefel, ackley, weierstrass, griewank, katsuura, grie_rosen, escaffer6,
        happycat, hgbat,
    )
}  # fmt: skip
"""The functions of a shifted, scaled and rotated ``z``, by the C code's names."""
