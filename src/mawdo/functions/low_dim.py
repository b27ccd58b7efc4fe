"""Fixed-dimension functions (paper F12-F16 and the forensic alternates), vectorised formulas.

Each formula maps ``X`` of shape ``(n, D)`` to ``(n,)`` for its one dimension ``D``. Constants
are the Dixon-Szego values printed in docs/functions.md#f-constants (Hartmann 6, Shekel) and the
customary published
data for the alternates (Kowalik's 11-point data set).
"""

from __future__ import annotations

import numpy as np

from mawdo.util import libm

# --- Hartmann 6 (F13), docs/functions.md#f-constants ----------------------------------------------
HARTMANN6_C = np.array([1.0, 1.2, 3.0, 3.2])
HARTMANN6_A = np.array(
    [
        [10.0, 3.0, 17.0, 3.5, 1.7, 8.0],
        [0.05, 10.0, 17.0, 0.1, 8.0, 14.0],
        [3.0, 3.5, 1.7, 10.0, 17.0, 8.0],
        [17.0, 8.0, 0.05, 10.0, 0.1, 14.0],
    ]
)
HARTMANN6_P = 1e-4 * np.array(
    [
        [1312.0, 1696.0, 5569.0, 124.0, 8283.0, 5886.0],
        [2329.0, 4135.0, 8307.0, 3736.0, 1004.0, 9991.0],
        [2348.0, 1451.0, 3522.0, 2883.0, 3047.0, 6650.0],
        [4047.0, 8828.0, 8732.0, 5743.0, 1091.0, 381.0],
    ]
)
# The GWO/WOA MATLAB code (and EvoloPy F20, which copies it) prints P[3][2] (1-based) as .1415
# instead of .1451; kept only for the ``hartmann_6_mirjalili_typo`` alternate.
HARTMANN6_P_MIRJALILI = HARTMANN6_P.copy()
HARTMANN6_P_MIRJALILI[2, 1] = 0.1415

# --- Shekel (F14-F16), docs/functions.md#f-constants: rows a_i and widths c_i; shekel_m uses the
# first m ---
SHEKEL_A = np.array(
    [
        [4.0, 4.0, 4.0, 4.0],
        [1.0, 1.0, 1.0, 1.0],
        [8.0, 8.0, 8.0, 8.0],
        [6.0, 6.0, 6.0, 6.0],
        [3.0, 7.0, 3.0, 7.0],
        [2.0, 9.0, 2.0, 9.0],
        [5.0, 5.0, 3.0, 3.0],
        [8.0, 1.0, 8.0, 1.0],
        [6.0, 2.0, 6.0, 2.0],
        [7.0, 3.6, 7.0, 3.6],
    ]
)
SHEKEL_C = np.array([0.1, 0.2, 0.2, 0.4, 0.4, 0.6, 0.3, 0.7, 0.5, 0.5])

# --- Kowalik (alternate), the standard 11-point data set (Kowalik & Osborne 1968) -------------
KOWALIK_A = np.array(
    [0.1957, 0.1947, 0.1735, 0.16, 0.0844, 0.0627, 0.0456, 0.0342, 0.0323, 0.0235, 0.0246]
)
KOWALIK_B = 1.0 / np.array([0.25, 0.5, 1.0, 2.0, 4.0, 6.0, 8.0, 10.0, 12.0, 14.0, 16.0])

for _const in (
    HARTMANN6_C,
    HARTMANN6_A,
    HARTMANN6_P,
    HARTMANN6_P_MIRJALILI,
    SHEKEL_A,
    SHEKEL_C,
    KOWALIK_A,
    KOWALIK_B,
):
    _const.setflags(write=False)


def six_hump_camel(X: np.ndarray) -> np.ndarray:
    """F12 six-hump camel: ``4x1^2 - 2.1x1^4 + x1^6/3 + x1 x2 - 4x2^2 + 4x2^4`` (D = 2).

    Minimum -1.0316284534898774 at ``(0.0898420..., -0.7126564...)`` and its mirror.
    """
    x1, x2 = X[:, 0], X[:, 1]
    # Powers as products (np.power may use a CPU-specific SIMD pow), so f(x_star) == f_star
    # holds bit for bit on every machine.
    a2, b2 = x1 * x1, x2 * x2
    a4, b4 = a2 * a2, b2 * b2
    return 4.0 * a2 - 2.1 * a4 + a4 * a2 / 3.0 + x1 * x2 - 4.0 * b2 + 4.0 * b4


def six_hump_camel_no_cross(X: np.ndarray) -> np.ndarray:
    """Six-hump camel without the ``x1 x2`` term (forensic alternate for the paper's F12 rows).

    ``4x1^2 - 2.1x1^4 + x1^6/3 - 4x2^2 + 4x2^4``; minimum -1 at ``(0, +-1/sqrt(2))``.
    """
    x1, x2 = X[:, 0], X[:, 1]
    a2, b2 = x1 * x1, x2 * x2
    a4, b4 = a2 * a2, b2 * b2
    return 4.0 * a2 - 2.1 * a4 + a4 * a2 / 3.0 - 4.0 * b2 + 4.0 * b4


def _hartmann_6(X: np.ndarray, P: np.ndarray) -> np.ndarray:
    """``-sum_i c_i exp(-sum_j a_ij (x_j - p_ij)^2)`` for a (4, 6) matrix ``P``."""
    D = X[:, None, :] - P[None, :, :]  # (n, 4, 6): x_j - p_ij
    inner = np.sum(HARTMANN6_A * D * D, axis=2)  # (n, 4)
    return -np.sum(HARTMANN6_C * libm.exp(-inner), axis=1)


def hartmann_6(X: np.ndarray) -> np.ndarray:
    """F13 Hartmann 6 with the standard P matrix (docs/functions.md#f-constants); minimum
    -3.3223680114155147."""
    return _hartmann_6(X, HARTMANN6_P)


def hartmann_6_mirjalili_typo(X: np.ndarray) -> np.ndarray:
    """Hartmann 6 with the GWO/WOA code's ``P[3][2] = 0.1415`` typo (forensic alternate)."""
    return _hartmann_6(X, HARTMANN6_P_MIRJALILI)


def _shekel(X: np.ndarray, m: int) -> np.ndarray:
    """Shekel ``m``: ``-sum_{i<=m} 1 / ((x - a_i)^T (x - a_i) + c_i)`` (D = 4)."""
    D = X[:, None, :] - SHEKEL_A[None, :m, :]  # (n, m, 4)
    return -np.sum(1.0 / (np.sum(D * D, axis=2) + SHEKEL_C[:m]), axis=1)


def shekel_5(X: np.ndarray) -> np.ndarray:
    """F14 Shekel 5 (first 5 rows of ``A``, ``c``); minimum -10.153199679058227."""
    return _shekel(X, 5)


def shekel_7(X: np.ndarray) -> np.ndarray:
    """F15 Shekel 7 (first 7 rows of ``A``, ``c``); minimum -10.40294056681866."""
    return _shekel(X, 7)


def shekel_10(X: np.ndarray) -> np.ndarray:
    """F16 Shekel 10 (all 10 rows of ``A``, ``c``); minimum -10.536409816692043."""
    return _shekel(X, 10)


def easom(X: np.ndarray) -> np.ndarray:
    """Easom: ``-cos(x1) cos(x2) exp(-((x1 - pi)^2 + (x2 - pi)^2))``; minimum -1 at ``(pi, pi)``.

    Evaluated with ``u = x - pi`` as ``-cos(u1) cos(u2) exp(-(u1^2 + u2^2))`` (``cos(x) =
    -cos(x - pi)``, and the two signs cancel), so ``(pi, pi)`` gives exactly -1 on any machine.
    """
    u1, u2 = X[:, 0] - np.pi, X[:, 1] - np.pi
    return -libm.cos(u1) * libm.cos(u2) * libm.exp(-(u1 * u1 + u2 * u2))


def goldstein_price(X: np.ndarray) -> np.ndarray:
    """Goldstein-Price; minimum 3 at ``(0, -1)``.

    ``[1 + (x1 + x2 + 1)^2 (19 - 14x1 + 3x1^2 - 14x2 + 6x1x2 + 3x2^2)]
    * [30 + (2x1 - 3x2)^2 (18 - 32x1 + 12x1^2 + 48x2 - 36x1x2 + 27x2^2)]``
    """
    x1, x2 = X[:, 0], X[:, 1]
    a = 1.0 + (x1 + x2 + 1.0) ** 2 * (
        19.0 - 14.0 * x1 + 3.0 * x1**2 - 14.0 * x2 + 6.0 * x1 * x2 + 3.0 * x2**2
    )
    b = 30.0 + (2.0 * x1 - 3.0 * x2) ** 2 * (
        18.0 - 32.0 * x1 + 12.0 * x1**2 + 48.0 * x2 - 36.0 * x1 * x2 + 27.0 * x2**2
    )
    return a * b


def kowalik(X: np.ndarray) -> np.ndarray:
    """Kowalik (D = 4), standard 11-point data; best known minimum about 3.0749e-4.

    ``f(x) = sum_i [a_i - x1 (b_i^2 + b_i x2) / (b_i^2 + b_i x3 + x4)]^2``. The model has poles
    where the denominator vanishes; there the value is ``inf``/``nan`` (no warning is raised).
    """
    b = KOWALIK_B
    x1, x2, x3, x4 = (X[:, j : j + 1] for j in range(4))  # each (n, 1), broadcast over i
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        model = x1 * (b * b + b * x2) / (b * b + b * x3 + x4)
        return np.sum((KOWALIK_A - model) ** 2, axis=1)
