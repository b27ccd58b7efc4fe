"""The basic functions of CEC 2017 / CEC 2022 on a whole population, as the official C code
computes them.

Each function takes ``z`` of shape ``(n, k)``, the points after the official shift, scaling
and rotation (``sr_func`` of ``cec17_test_func.cpp``), and returns the ``n`` values. ``k`` is
the dimension the C code calls ``nx``: the full D for a plain or composition function, one
group's size inside a hybrid. Sums run in the C code's order of terms only up to rounding:
values agree with the C code to about 1e-15 relative (tests/suites/test_cec_official.py).

Where the C code departs from the competitions' definitions, these functions follow the code
(docs/deviations.md#d-cec-official-code): Schaffer's F7 reads the shifted, unrotated point
(:func:`schaffer_f7` takes that point), the non-continuous Rastrigin is the plain Rastrigin
(its rounding is overwritten before use), and the CEC 2017 Levy function has its minimum at
``z = 1``, not at the shift.
"""

from __future__ import annotations

import numpy as np

PI = 3.1415926535897932384626433832795029
E = 2.7182818284590452353602874713526625

# ``sh_rate`` of each function in sr_func: the search box [-100, 100] shrunk to the function's
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


def rotate(y, matrix):
    """``rotatefunc``: ``z_i = sum_j y_j M_ij``, summed over j in order for every row.

    Not ``y @ M.T``: a BLAS product rounds a row differently by batch size (gemv for one row,
    gemm blocks for many), which would make a point's value depend on the other points of its
    batch; the running sum is the C code's own order and the same for any batch.
    """
    z = y[:, :1] * matrix[:, 0]
    for j in range(1, y.shape[1]):
        z += y[:, j : j + 1] * matrix[:, j]
    return z


def seqsum(a, axis=-1):
    """Sum along ``axis`` term after term, as the C code's loops add (``np.sum`` adds pairwise,
    which near an optimum of HGBat rounds differently by up to 1e-11 relative)."""
    return np.take(np.cumsum(a, axis=axis), -1, axis=axis)


def seqprod(a, axis=-1):
    """Product along ``axis`` factor after factor, as the C code's loops multiply."""
    return np.take(np.cumprod(a, axis=axis), -1, axis=axis)


def _index(k: int) -> np.ndarray:
    return np.arange(k, dtype=float)


def bent_cigar(z):
    """Bent Cigar: ``z_1^2 + 10^6 sum_{i>1} z_i^2``."""
    t = 1e6 * z * z
    t[:, 0] = z[:, 0] * z[:, 0]
    return seqsum(t)


def discus(z):
    """Discus: ``10^6 z_1^2 + sum_{i>1} z_i^2``."""
    t = z * z
    t[:, 0] = 1e6 * z[:, 0] * z[:, 0]
    return seqsum(t)


def ellips(z):
    """High-conditioned elliptic: ``sum_i 10^(6 (i-1)/(k-1)) z_i^2``."""
    k = z.shape[1]
    return seqsum(10.0 ** (6.0 * _index(k) / (k - 1)) * z * z)


def sum_diff_pow(z):
    """Sum of different powers: ``sum_i |z_i|^(i)`` (i from 1)."""
    return seqsum(np.abs(z) ** (_index(z.shape[1]) + 1))


def zakharov(z):
    """Zakharov: ``sum z_i^2 + s^2 + s^4`` with ``s = sum 0.5 i z_i``."""
    s2 = seqsum(0.5 * (_index(z.shape[1]) + 1) * z)
    return seqsum(z * z) + s2**2 + s2**4


def rosenbrock(z):
    """Rosenbrock on ``z + 1``: ``sum 100 (z_i^2 - z_{i+1})^2 + (z_i - 1)^2``."""
    z = z + 1.0
    t1 = z[:, :-1] * z[:, :-1] - z[:, 1:]
    t2 = z[:, :-1] - 1.0
    return seqsum(100.0 * t1 * t1 + t2 * t2)


def rastrigin(z):
    """Rastrigin: ``sum z_i^2 - 10 cos(2 pi z_i) + 10``."""
    return seqsum(z * z - 10.0 * np.cos(2.0 * PI * z) + 10.0)


def schaffer_f7(y):
    """Schaffer's F7 on ``y`` (the C code's shifted, unrotated point):
    ``(1/(k-1) sum sqrt(s_i) (1 + sin^2(50 s_i^0.2)))^2``, ``s_i = sqrt(y_i^2 + y_{i+1}^2)``."""
    k = y.shape[1]
    s = np.power(y[:, :-1] * y[:, :-1] + y[:, 1:] * y[:, 1:], 0.5)
    t = np.sin(50.0 * np.power(s, 0.2))
    f = seqsum(np.power(s, 0.5) + np.power(s, 0.5) * t * t)
    return f * f / (k - 1) / (k - 1)


def levy(z, offset: float):
    """Levy with ``w = 1 + (z - offset)/4`` (CEC 2017: offset 1; CEC 2022: 0)."""
    w = 1.0 + (z - offset) / 4.0
    term1 = np.sin(PI * w[:, 0]) ** 2
    last = w[:, -1]
    term3 = (last - 1) ** 2 * (1 + np.sin(2 * PI * last) ** 2)
    wi = w[:, :-1]
    return term1 + seqsum((wi - 1) ** 2 * (1 + 10 * np.sin(PI * wi + 1) ** 2)) + term3


def levy2017(z):
    """CEC 2017's Levy (``w = 1 + (z - 1)/4``)."""
    return levy(z, 1.0)


def levy2022(z):
    """CEC 2022's Levy (``w = 1 + z/4``)."""
    return levy(z, 0.0)


def schwefel(z):
    """Modified Schwefel on ``z + 420.9687462275036`` with the quadratic penalty beyond +-500."""
    k = z.shape[1]
    z = z + 4.209687462275036e002
    a = np.abs(z)
    m = 500.0 - np.fmod(a, 500)
    hi = -(500.0 - np.fmod(z, 500)) * np.sin(np.power(500.0 - np.fmod(z, 500), 0.5))
    hi = hi + ((z - 500.0) / 100) ** 2 / k
    lo = -(-500.0 + np.fmod(a, 500)) * np.sin(np.power(m, 0.5))
    lo = lo + ((z + 500.0) / 100) ** 2 / k
    mid = -z * np.sin(np.power(a, 0.5))
    terms = np.where(z > 500, hi, np.where(z < -500, lo, mid))
    return seqsum(terms) + 4.189828872724338e002 * k


def ackley(z):
    """Ackley: ``e - 20 exp(-0.2 sqrt(mean z^2)) - exp(mean cos 2 pi z) + 20``."""
    k = z.shape[1]
    s1 = -0.2 * np.sqrt(seqsum(z * z) / k)
    s2 = seqsum(np.cos(2.0 * PI * z)) / k
    return E - 20.0 * np.exp(s1) - np.exp(s2) + 20.0


_J = np.arange(21, dtype=float)
_AJ, _BJ = np.power(0.5, _J), np.power(3.0, _J)


def weierstrass(z):
    """Weierstrass (a = 0.5, b = 3, k_max = 20), minus its value at 0."""
    k = z.shape[1]
    s = seqsum(_AJ * np.cos(2.0 * PI * _BJ * (z[..., None] + 0.5)))
    s2 = seqsum(_AJ * np.cos(2.0 * PI * _BJ * 0.5))
    return seqsum(s) - k * s2


def griewank(z):
    """Griewank: ``1 + sum z_i^2/4000 - prod cos(z_i/sqrt(i))``."""
    k = z.shape[1]
    p = seqprod(np.cos(z / np.sqrt(1.0 + _index(k))))
    return 1.0 + seqsum(z * z) / 4000.0 - p


_P2 = np.power(2.0, np.arange(1, 33, dtype=float))


def katsuura(z):
    """Katsuura: ``c prod (1 + i sum_j |2^j z_i - round(2^j z_i)|/2^j)^(10/k^1.2) - c``,
    ``c = 10/k^2``."""
    k = z.shape[1]
    t = _P2 * z[..., None]
    temp = seqsum(np.abs(t - np.floor(t + 0.5)) / _P2)
    f = seqprod(np.power(1.0 + (_index(k) + 1) * temp, 10.0 / np.power(1.0 * k, 1.2)))
    c = 10.0 / k / k
    return f * c - c


def _pairs(z):
    """``z_i`` and ``z_{i+1}`` with the wrap-around pair ``(z_k, z_1)`` last."""
    return z, np.roll(z, -1, axis=1)


def grie_rosen(z):
    """Expanded Griewank plus Rosenbrock on ``z + 1`` (pairs wrap around)."""
    a, b = _pairs(z + 1.0)
    t1 = a * a - b
    t2 = a - 1.0
    t = 100.0 * t1 * t1 + t2 * t2
    return seqsum(t * t / 4000.0 - np.cos(t) + 1.0)


def escaffer6(z):
    """Expanded Schaffer's F6 (pairs wrap around)."""
    a, b = _pairs(z)
    r = a * a + b * b
    t1 = np.sin(np.sqrt(r)) ** 2
    t2 = 1.0 + 0.001 * r
    return seqsum(0.5 + (t1 - 0.5) / (t2 * t2))


def happycat(z):
    """HappyCat on ``z - 1``: ``|r2 - k|^(1/4) + (r2/2 + sum z)/k + 1/2``."""
    k = z.shape[1]
    z = z - 1.0
    r2, s = seqsum(z * z), seqsum(z)
    return np.power(np.abs(r2 - k), 2 * (1.0 / 8.0)) + (0.5 * r2 + s) / k + 0.5


def hgbat(z):
    """HGBat on ``z - 1``: ``|r2^2 - (sum z)^2|^(1/2) + (r2/2 + sum z)/k + 1/2``."""
    k = z.shape[1]
    z = z - 1.0
    r2, s = seqsum(z * z), seqsum(z)
    return np.power(np.abs(r2**2 - s**2), 2 * (1.0 / 4.0)) + (0.5 * r2 + s) / k + 0.5


def bi_rastrigin(x, shift, matrix, shifted: bool, rotated: bool):
    """Lunacek bi-Rastrigin of the raw points ``x`` (n, k), as ``bi_rastrigin_func``.

    ``shift`` gives the sign of each coordinate's mirror (the C code reads it even when it does
    not shift, inside a hybrid); ``matrix`` is used only when ``rotated``.
    """
    k = x.shape[1]
    mu0, d = 2.5, 1.0
    s = 1.0 - 1.0 / (2.0 * np.power(k + 20.0, 0.5) - 8.2)
    mu1 = -np.power((mu0 * mu0 - d) / s, 0.5)
    y = (x - shift if shifted else x) * (10.0 / 100.0)
    z = np.where(shift[:k] < 0.0, -(2 * y), 2 * y)
    t = z + mu0
    tmp1 = seqsum((t - mu0) ** 2)
    tmp2 = seqsum((t - mu1) ** 2) * s + d * k
    c = rotate(z, matrix) if rotated else z
    return np.minimum(tmp1, tmp2) + 10.0 * (k - seqsum(np.cos(2.0 * PI * c)))


BASIC = {
    f.__name__: f
    for f in (
        bent_cigar, discus, ellips, sum_diff_pow, zakharov, rosenbrock, rastrigin, levy2017,
        levy2022, schwefel, ackley, weierstrass, griewank, katsuura, grie_rosen, escaffer6,
        happycat, hgbat,
    )
}  # fmt: skip
"""The functions of a shifted, scaled and rotated ``z``, by the C code's names."""
