"""Literal and variant readings of the paper's printed formulas (forensic alternates,
docs/functions.md#f-decisions).

These reproduce what the paper's Table 2 literally prints where the printed formula is ill-posed
(F8, F11) or where reference codes differ (F9 without ``pi/n``). They are registered beside the
paper suite so reports can show how the reading changes the picture; they are not the defaults.
Each maps ``X`` of shape ``(n, D)`` to ``(n,)``.
"""

from __future__ import annotations

import numpy as np

from mawdo.util import libm

from .multimodal import penalized_1_core, penalty_u

# Per-coordinate minimiser of sin(x) + 0.1 x^2: the root of cos(x) + 0.2 x = 0 near -1.3064,
# refined by Newton's method to the double with the smallest residual (5.6e-17). The json's
# ``literal_minimizer`` row uses -1.3064400196075439, the float32 value of -1.30644 (1.1e-8
# away); both give the same minimum to rounding.
F11_LITERAL_XMIN = -1.306440008369511
# Step of the minimiser of f8_paper_literal: s + 0.2 s^2 is smallest at s = -2.5 (value -1.25).
F8_LITERAL_STEP = -2.5


def f8_paper_literal(X: np.ndarray) -> np.ndarray:
    """Paper F8 as printed: ``sum_{i=2..n} (s_i + 0.2 s_i^2)``, ``s_i = x_i - x_{i-1}``.

    ``s_1`` would need the undefined ``x_0``; it is dropped (equivalently ``x_0 := x_1``), which
    is the reading the shared test vectors fix. Needs ``D >= 2``; the minimum is ``-1.25 (n-1)``
    at any staircase ``x_i = x_1 - 2.5 (i - 1)``, so 0 (at the origin) is not the minimum.
    """
    S = np.diff(X, axis=1)  # s_i = x_i - x_{i-1}, i = 2..n
    return np.sum(S + 0.2 * S * S, axis=1)


def f11_paper_literal(X: np.ndarray) -> np.ndarray:
    """Paper F11 as printed: ``sum_i [sin(x_i) + 0.1 x_i^2]``; minimum ``n * (-0.7946)``.

    The minimum is at ``x_i = -1.30644...`` for every ``i`` (about -23.84 for ``n = 30``), so the
    paper's stated ``minf = 0`` does not hold for this reading.
    """
    return np.sum(libm.sin(X) + 0.1 * X * X, axis=1)


def penalized_1_no_pi_over_n(X: np.ndarray) -> np.ndarray:
    """Penalized 1 without the ``pi/n`` factor, as the paper's F9 row omits it; min 0 at ``-1``.

    ``f(x) = core(y) + sum_i u(x_i, 10, 100, 4)``, ``y = 1 + (x + 1)/4``, with the standard core
    ``10 sin^2(pi y_1) + sum_{i<n} (y_i - 1)^2 [1 + 10 sin^2(pi y_{i+1})] + (y_n - 1)^2`` (the
    paper's row also moves ``10 sin^2(pi y_i)`` inside the sum; the shared test vectors fix the
    standard core, so only the missing factor is reproduced here).
    """
    return penalized_1_core(X) + np.sum(penalty_u(X, 10.0, 100.0, 4.0), axis=1)
