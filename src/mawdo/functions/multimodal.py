"""Scalable multimodal paper functions F7-F11 as pure vectorised formulas
(docs/functions.md#f-table).

Each formula maps ``X`` of shape ``(n, D)`` to ``(n,)``. The readings chosen for the paper's
ill-posed F8 and F11 and for its duplicated penalized function are documented in
``docs/functions.md``; the literal readings live in :mod:`mawdo.functions.alternates`.
"""

from __future__ import annotations

import numpy as np

from mawdo.util import libm


def rastrigin(X: np.ndarray) -> np.ndarray:
    """F7 Rastrigin: ``f(x) = sum_i x_i^2 - 10 cos(2 pi x_i) + 10``; minimum 0 at ``x = 0``."""
    return np.sum(X * X - 10.0 * libm.cos(2.0 * np.pi * X) + 10.0, axis=1)


def schaffer_f7(X: np.ndarray) -> np.ndarray:
    """F8 Schaffer F7, CEC 2014/2017 form; minimum 0 at ``x = 0``; needs ``D >= 2``.

    ``f(x) = [(1/(n-1)) sum_{i<n} sqrt(z_i) (1 + sin^2(50 z_i^0.2))]^2`` with
    ``z_i = sqrt(x_i^2 + x_{i+1}^2)``.
    """
    z = np.sqrt(X[:, :-1] ** 2 + X[:, 1:] ** 2)
    terms = np.sqrt(z) * (1.0 + libm.sin(50.0 * libm.power(z, 0.2)) ** 2)
    return (np.sum(terms, axis=1) / (X.shape[1] - 1)) ** 2


def sin2_pi(T: np.ndarray) -> np.ndarray:
    """``sin^2(pi t)``, elementwise, exactly 0 at integer ``t``.

    ``sin^2`` has period 1 in ``t``, so the argument is reduced to ``t - rint(t)`` in
    ``[-1/2, 1/2]`` first (an exact float subtraction). ``np.sin(np.pi * t)`` would give
    ``1.2e-16`` at ``t = 1`` and so a penalized function a value of ``1e-32`` at its optimum.
    """
    return libm.sin(np.pi * (T - np.rint(T))) ** 2


def penalty_u(X: np.ndarray, a: float, k: float, m: float) -> np.ndarray:
    """Boundary penalty ``u(x, a, k, m)``, elementwise (docs/functions.md#f-penalized).

    ``k (x - a)^m`` if ``x > a``; ``k (-x - a)^m`` if ``x < -a``; 0 otherwise.
    """
    # max(x - a, 0) is x - a exactly where x > a and 0 elsewhere (likewise for -x - a), so the
    # sum equals the three-case definition without evaluating the unused branches.
    return k * _power(np.maximum(X - a, 0.0), m) + k * _power(np.maximum(-X - a, 0.0), m)


def _power(T: np.ndarray, m: float) -> np.ndarray:
    """``T**m``; ``m = 4`` as two exact-rounding squarings, other ``m`` by the C library's
    ``pow`` (:mod:`mawdo.util.libm`: NumPy's may use a CPU-specific SIMD ``pow``)."""
    if m == 4:
        T2 = T * T
        return T2 * T2
    return libm.power(T, m)


def penalized_1_core(X: np.ndarray) -> np.ndarray:
    """The braces of penalized 1 with ``y = 1 + (x + 1)/4``.

    ``10 sin^2(pi y_1) + sum_{i<n} (y_i - 1)^2 [1 + 10 sin^2(pi y_{i+1})] + (y_n - 1)^2``
    """
    Y = 1.0 + (X + 1.0) / 4.0
    first = 10.0 * sin2_pi(Y[:, 0])
    middle = np.sum((Y[:, :-1] - 1.0) ** 2 * (1.0 + 10.0 * sin2_pi(Y[:, 1:])), axis=1)
    last = (Y[:, -1] - 1.0) ** 2
    return first + middle + last


def penalized_1(X: np.ndarray) -> np.ndarray:
    """F9 generalized penalized function 1 (with the standard ``pi/n`` factor); min 0 at ``-1``.

    ``f(x) = (pi/n) {core(y)} + sum_i u(x_i, 10, 100, 4)``, ``y = 1 + (x + 1)/4``.
    """
    n = X.shape[1]
    return (np.pi / n) * penalized_1_core(X) + np.sum(penalty_u(X, 10.0, 100.0, 4.0), axis=1)


def penalized_2(X: np.ndarray) -> np.ndarray:
    """F10 generalized penalized function 2; minimum 0 at ``x = 1``.

    ``f(x) = 0.1 {sin^2(3 pi x_1) + sum_{i<n} (x_i - 1)^2 [1 + sin^2(3 pi x_{i+1})]
    + (x_n - 1)^2 [1 + sin^2(2 pi x_n)]} + sum_i u(x_i, 5, 100, 4)``.
    """
    first = sin2_pi(3.0 * X[:, 0])  # sin^2(3 pi x_1)
    middle = np.sum((X[:, :-1] - 1.0) ** 2 * (1.0 + sin2_pi(3.0 * X[:, 1:])), axis=1)
    xn = X[:, -1]
    last = (xn - 1.0) ** 2 * (1.0 + sin2_pi(2.0 * xn))  # sin^2(2 pi x_n)
    return 0.1 * (first + middle + last) + np.sum(penalty_u(X, 5.0, 100.0, 4.0), axis=1)


def alpine_n1(X: np.ndarray) -> np.ndarray:
    """F11 Alpine N.1: ``f(x) = sum_i |x_i sin(x_i) + 0.1 x_i|``; minimum 0 at ``x = 0``."""
    return np.sum(np.abs(X * libm.sin(X) + 0.1 * X), axis=1)


def ackley(X: np.ndarray) -> np.ndarray:
    """Ackley (alternate reading of F8); minimum exactly 0 at ``x = 0``.

    ``f(x) = -20 exp(-0.2 r) - exp(c) + 20 + e`` with ``r = sqrt(mean x^2)`` and
    ``c = mean cos(2 pi x)``, evaluated as the algebraically equal
    ``-20 expm1(-0.2 r) - e expm1(c - 1)`` so that the origin gives exactly 0 in float64 on any
    machine (the textbook order gives 4.4e-16 there); elsewhere the two agree to rounding.
    """
    r = np.sqrt(np.mean(X * X, axis=1))
    c = np.mean(libm.cos(2.0 * np.pi * X), axis=1)
    return -20.0 * libm.expm1(-0.2 * r) - np.e * libm.expm1(c - 1.0)
