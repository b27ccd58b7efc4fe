"""The basic functions of CEC 2017 / CEC 2022 at one point, as the official C code computes
them: Numba loops in the C code's order of operations.

Each function takes a block of points held transposed, ``z`` of shape ``(>= k, B)``: column
``r`` is one point after the official shift, scaling and rotation (``sr_func`` of
``cec17_test_func.cpp``), of which the first ``k`` coordinates are used; it writes the values
of the first ``m`` points into ``out``. ``k`` is the dimension the C code calls ``nx``: the
full D for a plain or composition function, one group's size inside a hybrid. The loops run
over the block's points innermost, which vectorises what is not a library call, while every
point's sums and products still run term after term in the C loops' order, with the C
library's ``pow``, ``sin``, ``cos``, ``exp``, ``fmod``: most values are bitwise the C code's
(tests/suites/test_cec_official.py). A NumPy pairwise sum instead rounded HGBat near its
optimum differently by up to 1e-11 relative.

What depends on ``k`` alone (the elliptic weights ``10^(6 i/(k-1))``, Weierstrass's
``a^j``, ``2 pi b^j`` and value at 0, Katsuura's ``2^j`` and exponent, bi-Rastrigin's ``s``
and ``mu1``) is computed once per function and size by :func:`constants`, with the same
library calls on the same arguments, so the values are the C code's, which recomputes them at
every coordinate.

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

NAMES = (
    "bent_cigar", "discus", "ellips", "sum_diff_pow", "zakharov", "rosenbrock", "rastrigin",
    "levy2017", "levy2022", "schwefel", "ackley", "weierstrass", "griewank", "katsuura",
    "grie_rosen", "escaffer6", "happycat", "hgbat", "schaffer_f7", "bi_rastrigin",
)  # fmt: skip
"""The basic functions by the C code's names; a function's code is its index here."""
CODE = {name: i for i, name in enumerate(NAMES)}
ELLIPS, WEIERSTRASS, KATSUURA = CODE["ellips"], CODE["weierstrass"], CODE["katsuura"]
SCHAFFER_F7, BI_RASTRIGIN = CODE["schaffer_f7"], CODE["bi_rastrigin"]
WIDTH = 72
"""Length of a row of :func:`constants` (Weierstrass needs 43, Katsuura 65, the elliptic k)."""

# IEEE division (x/0 -> inf or nan, as in C), not Python's ZeroDivisionError
kernel = njit(cache=True, nogil=True, error_model="numpy")


@kernel
def constants(code, k):
    """What function ``code`` computes from its size ``k`` alone (length ``max(WIDTH, k)``)."""
    t = np.zeros(max(WIDTH, k))
    if code == ELLIPS:
        for i in range(k):
            t[i] = math.pow(10.0, 6.0 * i / (k - 1))
    elif code == WEIERSTRASS:  # a^j, 2 pi b^j (a = 0.5, b = 3), then the value at z = 0
        for j in range(21):
            aj, bj = math.pow(0.5, j), math.pow(3.0, j)
            t[j], t[21 + j] = aj, 2.0 * PI * bj
            t[42] += aj * math.cos(2.0 * PI * bj * 0.5)
    elif code == KATSUURA:
        t[0] = 10.0 / math.pow(1.0 * k, 1.2)
        for j in range(1, 33):
            t[j], t[32 + j] = math.pow(2.0, j), math.pow(2.0, -j)  # exact
    elif code == BI_RASTRIGIN:  # s and mu1 of the Lunacek function (mu0 = 2.5, d = 1)
        t[0] = 1.0 - 1.0 / (2.0 * math.pow(k + 20.0, 0.5) - 8.2)
        t[1] = -math.pow((2.5 * 2.5 - 1.0) / t[0], 0.5)
    return t


@kernel
def bent_cigar(z, k, m, t, out):
    """Bent Cigar: ``z_1^2 + 10^6 sum_{i>1} z_i^2``."""
    for r in range(m):
        out[r] = z[0, r] * z[0, r]
    for i in range(1, k):
        zi = z[i]
        for r in range(m):
            out[r] += 1e6 * zi[r] * zi[r]


@kernel
def discus(z, k, m, t, out):
    """Discus: ``10^6 z_1^2 + sum_{i>1} z_i^2``."""
    for r in range(m):
        out[r] = 1e6 * z[0, r] * z[0, r]
    for i in range(1, k):
        zi = z[i]
        for r in range(m):
            out[r] += zi[r] * zi[r]


@kernel
def ellips(z, k, m, t, out):
    """High-conditioned elliptic: ``sum_i 10^(6 (i-1)/(k-1)) z_i^2`` (weights ``t``)."""
    out[:m] = 0.0
    for i in range(k):
        zi, ti = z[i], t[i]
        for r in range(m):
            out[r] += ti * zi[r] * zi[r]


@kernel
def sum_diff_pow(z, k, m, t, out):
    """Sum of different powers: ``sum_i |z_i|^i`` (i from 1)."""
    out[:m] = 0.0
    for i in range(k):
        zi = z[i]
        for r in range(m):
            out[r] += math.pow(abs(zi[r]), i + 1.0)


@kernel
def zakharov(z, k, m, t, out):
    """Zakharov: ``sum z_i^2 + s^2 + s^4`` with ``s = sum 0.5 i z_i``."""
    s2 = np.zeros(m)
    out[:m] = 0.0
    for i in range(k):
        zi, c = z[i], 0.5 * (i + 1)
        for r in range(m):
            out[r] += zi[r] * zi[r]
            s2[r] += c * zi[r]
    for r in range(m):
        out[r] = out[r] + s2[r] * s2[r] + math.pow(s2[r], 4.0)


@kernel
def rosenbrock(z, k, m, t, out):
    """Rosenbrock on ``z + 1``: ``sum 100 (z_i^2 - z_{i+1})^2 + (z_i - 1)^2``."""
    out[:m] = 0.0
    for i in range(k - 1):
        zi, zn = z[i], z[i + 1]
        for r in range(m):
            a, b = zi[r] + 1.0, zn[r] + 1.0
            t1 = a * a - b
            t2 = a - 1.0
            out[r] += 100.0 * t1 * t1 + t2 * t2


@kernel
def rastrigin(z, k, m, t, out):
    """Rastrigin: ``sum z_i^2 - 10 cos(2 pi z_i) + 10``."""
    out[:m] = 0.0
    for i in range(k):
        zi = z[i]
        for r in range(m):
            out[r] += zi[r] * zi[r] - 10.0 * math.cos(2.0 * PI * zi[r]) + 10.0


@kernel
def schaffer_f7(y, k, m, t, out):
    """Schaffer's F7 on ``y`` (the C code's shifted, unrotated point):
    ``(1/(k-1) sum sqrt(s_i) (1 + sin^2(50 s_i^0.2)))^2``, ``s_i = sqrt(y_i^2 + y_{i+1}^2)``."""
    out[:m] = 0.0
    for i in range(k - 1):
        yi, yn = y[i], y[i + 1]
        for r in range(m):
            s = math.pow(yi[r] * yi[r] + yn[r] * yn[r], 0.5)
            u = math.sin(50.0 * math.pow(s, 0.2))
            root = math.pow(s, 0.5)  # the C code calls pow(s, 0.5) twice: the same number
            out[r] += root + root * u * u
    for r in range(m):
        out[r] = out[r] * out[r] / (k - 1) / (k - 1)


@kernel
def levy(z, k, m, offset, out):
    """Levy on ``w = 1 + (z - offset)/4``: CEC 2017 has ``offset`` 1 (minimum at ``z = 1``),
    CEC 2022 has 0."""
    out[:m] = 0.0
    for i in range(k - 1):
        zi = z[i]
        for r in range(m):
            w = 1.0 + (zi[r] - offset) / 4.0
            u = math.sin(PI * w + 1)
            out[r] += (w - 1) * (w - 1) * (1 + 10 * (u * u))
    for r in range(m):
        w0 = 1.0 + (z[0, r] - offset) / 4.0
        wl = 1.0 + (z[k - 1, r] - offset) / 4.0
        s0, sl = math.sin(PI * w0), math.sin(2 * PI * wl)
        out[r] = s0 * s0 + out[r] + (wl - 1) * (wl - 1) * (1 + sl * sl)


@kernel
def schwefel(z, k, m, t, out):
    """Modified Schwefel on ``z + 420.9687462275036``, with its penalty beyond +-500."""
    out[:m] = 0.0
    for i in range(k):
        zi = z[i]
        for r in range(m):
            v = zi[r] + 4.209687462275036e002
            if v > 500:
                u = 500.0 - np.fmod(v, 500.0)  # C's fmod (exact)
                out[r] -= u * math.sin(math.pow(u, 0.5))
                q = (v - 500.0) / 100
                out[r] += q * q / k
            elif v < -500:
                a = np.fmod(abs(v), 500.0)
                out[r] -= (-500.0 + a) * math.sin(math.pow(500.0 - a, 0.5))
                q = (v + 500.0) / 100
                out[r] += q * q / k
            else:
                out[r] -= v * math.sin(math.pow(abs(v), 0.5))
    for r in range(m):
        out[r] += 4.189828872724338e002 * k


@kernel
def ackley(z, k, m, t, out):
    """Ackley: ``e - 20 exp(-0.2 sqrt(mean z^2)) - exp(mean cos 2 pi z) + 20``."""
    s2 = np.zeros(m)
    out[:m] = 0.0
    for i in range(k):
        zi = z[i]
        for r in range(m):
            out[r] += zi[r] * zi[r]
            s2[r] += math.cos(2.0 * PI * zi[r])
    for r in range(m):
        s1 = -0.2 * math.sqrt(out[r] / k)
        out[r] = E - 20.0 * math.exp(s1) - math.exp(s2[r] / k) + 20.0


@kernel
def weierstrass(z, k, m, t, out):
    """Weierstrass (a = 0.5, b = 3, k_max = 20), minus its value at 0 (``t``: a^j, 2 pi b^j,
    the value at 0 of one coordinate)."""
    s = np.empty(m)
    out[:m] = 0.0
    for i in range(k):
        zi = z[i]
        s[:] = 0.0
        for j in range(21):
            aj, cj = t[j], t[21 + j]
            for r in range(m):
                s[r] += aj * math.cos(cj * (zi[r] + 0.5))
        for r in range(m):
            out[r] += s[r]
    for r in range(m):
        out[r] -= k * t[42]


@kernel
def griewank(z, k, m, t, out):
    """Griewank: ``1 + sum z_i^2/4000 - prod cos(z_i/sqrt(i))``."""
    p = np.ones(m)
    out[:m] = 0.0
    for i in range(k):
        zi, root = z[i], math.sqrt(1.0 + i)
        for r in range(m):
            out[r] += zi[r] * zi[r]
            p[r] *= math.cos(zi[r] / root)
    for r in range(m):
        out[r] = 1.0 + out[r] / 4000.0 - p[r]


@kernel
def katsuura(z, k, m, t, out):
    """Katsuura: ``c prod (1 + i sum_j |2^j z_i - round(2^j z_i)|/2^j)^(10/k^1.2) - c``,
    ``c = 10/k^2`` (``t``: the exponent, then 2^j, then 2^-j: dividing by 2^j and
    multiplying by 2^-j give the same number)."""
    c = 10.0 / k / k
    temp = np.empty(m)
    out[:m] = 1.0
    for i in range(k):
        zi = z[i]
        temp[:] = 0.0
        for j in range(1, 33):
            t1, inv = t[j], t[32 + j]
            for r in range(m):
                t2 = t1 * zi[r]
                temp[r] += abs(t2 - math.floor(t2 + 0.5)) * inv
        for r in range(m):
            out[r] *= math.pow(1.0 + (i + 1) * temp[r], t[0])
    for r in range(m):
        out[r] = out[r] * c - c


@kernel
def grie_rosen(z, k, m, t, out):
    """Expanded Griewank plus Rosenbrock on ``z + 1``, pairs ``(z_i, z_{i+1})`` then
    ``(z_k, z_1)``."""
    out[:m] = 0.0
    for i in range(k):
        zi, zn = z[i], z[(i + 1) % k]
        for r in range(m):
            a, b = zi[r] + 1.0, zn[r] + 1.0
            t1 = a * a - b
            t2 = a - 1.0
            u = 100.0 * t1 * t1 + t2 * t2
            out[r] += u * u / 4000.0 - math.cos(u) + 1.0


@kernel
def escaffer6(z, k, m, t, out):
    """Expanded Schaffer's F6, pairs ``(z_i, z_{i+1})`` then ``(z_k, z_1)``."""
    out[:m] = 0.0
    for i in range(k):
        zi, zn = z[i], z[(i + 1) % k]
        for r in range(m):
            a, b = zi[r], zn[r]
            t1 = math.sin(math.sqrt(a * a + b * b))
            t1 = t1 * t1
            t2 = 1.0 + 0.001 * (a * a + b * b)
            out[r] += 0.5 + (t1 - 0.5) / (t2 * t2)


@kernel
def cat(z, k, m, hg, out):
    """HGBat (``hg``: ``|r2^2 - (sum z)^2|^(1/2)``) or HappyCat (``|r2 - k|^(1/4)``) on
    ``z - 1``, plus ``(r2/2 + sum z)/k + 1/2``."""
    s = np.zeros(m)
    out[:m] = 0.0
    for i in range(k):
        zi = z[i]
        for r in range(m):
            v = zi[r] - 1.0
            out[r] += v * v
            s[r] += v
    for r in range(m):
        r2 = out[r]
        if hg:
            out[r] = math.pow(abs(r2 * r2 - s[r] * s[r]), 0.5) + (0.5 * r2 + s[r]) / k + 0.5
        else:
            out[r] = math.pow(abs(r2 - k), 0.25) + (0.5 * r2 + s[r]) / k + 0.5
