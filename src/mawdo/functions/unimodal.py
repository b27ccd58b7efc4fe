"""Unimodal paper functions F1-F6 as pure vectorised formulas (docs/functions.md#f-table, paper
Table 2).

Every formula maps a batch of points ``X`` of shape ``(n, D)`` to values of shape ``(n,)``; rows
are independent points and nothing loops over them in Python. These are the noiseless formulas:
F6's additive ``U[0,1)`` noise is added by :class:`~mawdo.functions.base.BenchmarkFunction`.
"""

from __future__ import annotations

import numpy as np


def sphere(X: np.ndarray) -> np.ndarray:
    """F1 sphere: ``f(x) = sum_i x_i^2``; minimum 0 at ``x = 0``."""
    return np.sum(X * X, axis=1)


def schwefel_2_22(X: np.ndarray) -> np.ndarray:
    """F2 Schwefel 2.22: ``f(x) = sum_i |x_i| + prod_i |x_i|``; minimum 0 at ``x = 0``."""
    A = np.abs(X)
    return np.sum(A, axis=1) + np.prod(A, axis=1)


def schwefel_1_2(X: np.ndarray) -> np.ndarray:
    """F3 Schwefel 1.2: ``f(x) = sum_i (sum_{j<=i} x_j)^2``; minimum 0 at ``x = 0``."""
    C = np.cumsum(X, axis=1)  # partial sums sum_{j<=i} x_j
    return np.sum(C * C, axis=1)


def schwefel_2_21(X: np.ndarray) -> np.ndarray:
    """F4 Schwefel 2.21: ``f(x) = max_i |x_i|``; minimum 0 at ``x = 0``."""
    return np.max(np.abs(X), axis=1)


def rosenbrock(X: np.ndarray) -> np.ndarray:
    """F5 Rosenbrock: ``f(x) = sum_{i<n} 100 (x_{i+1} - x_i^2)^2 + (x_i - 1)^2``; min 0 at ones."""
    head, tail = X[:, :-1], X[:, 1:]
    return np.sum(100.0 * (tail - head * head) ** 2 + (head - 1.0) ** 2, axis=1)


def quartic(X: np.ndarray) -> np.ndarray:
    """F6 quartic, noiseless part: ``f(x) = sum_i i x_i^4`` (``i = 1..n``); minimum 0 at 0.

    The paper's ``+ random(0,1)`` term is not part of this formula (docs/functions.md#f-noise: one
    ``U[0,1)`` draw
    per evaluation, added by the caller from the run's stream).
    """
    i = np.arange(1, X.shape[1] + 1, dtype=float)
    X2 = X * X  # x^4 as two squarings: exact-rounding products, identical on every CPU
    return np.sum(i * (X2 * X2), axis=1)
