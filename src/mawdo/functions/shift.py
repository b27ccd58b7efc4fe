"""The shift wrapper: move a function's optimum to a seeded random point
(docs/functions.md#f-shift, origin bias).

F1-F4, F6-F8 and F11 have their optimum at the centre of a symmetric box, where WDO's gravity
term pulls; a fair suite also runs every function with its optimum moved to a seeded random point
inside the middle 80% of the box.
"""

from __future__ import annotations

import dataclasses
from functools import partial

import numpy as np

from .base import BenchmarkFunction, Formula

SHIFT_MARGIN = 0.1
"""Fraction of the box width kept free on each side of the shifted optimum (middle 80%)."""


def _shifted_formula(func: Formula, s: np.ndarray, x_star: np.ndarray, X: np.ndarray) -> np.ndarray:
    """``g(x) = f(x - s + x_star)``; written ``(x - s) + x_star`` so ``g(s)`` is ``f(x_star)``
    bit for bit (``s - s`` is exactly 0)."""
    return func((X - s) + x_star)


def shift_point(f: BenchmarkFunction, seed: int) -> np.ndarray:
    """The shifted optimum ``s`` of ``f`` for ``seed``: uniform in the middle 80% of the box.

    Parameters
    ----------
    f : BenchmarkFunction
        The function whose box is used.
    seed : int
        Non-negative seed of ``numpy.random.default_rng``; the same seed gives the same point.

    Returns
    -------
    numpy.ndarray
        ``lb + 0.1 w + 0.8 w u`` with ``w = ub - lb`` and ``u ~ U[0,1)^D``, shape ``(D,)``.
    """
    if isinstance(seed, bool) or not isinstance(seed, int | np.integer):
        raise TypeError(f"shift seed must be an int, got {type(seed).__name__}")
    if seed < 0:
        raise ValueError(f"shift seed must be >= 0, got {seed}")
    u = np.random.default_rng(int(seed)).random(f.dim)
    width = f.ub - f.lb
    return f.lb + SHIFT_MARGIN * width + (1.0 - 2.0 * SHIFT_MARGIN) * width * u


def shifted(f: BenchmarkFunction, seed: int) -> BenchmarkFunction:
    """``f`` with its optimum moved to a seeded random point ``s`` in the middle 80% of its box.

    The new function is ``g(x) = f(x - s + x_star)`` on the same box, so ``g(s) == f_star``
    exactly and ``g`` keeps ``f``'s landscape, translated. Other minimisers of ``f`` (e.g. the
    camel's mirror optimum) and the parts of the landscape that leave the box move with it.

    Parameters
    ----------
    f : BenchmarkFunction
        The function to shift (its dimension and bounds are kept).
    seed : int
        Non-negative int; ``numpy.random.default_rng(seed)`` draws the shift, so the result is
        deterministic per seed and different seeds give different optima.

    Returns
    -------
    BenchmarkFunction
        Named ``"<name>@shifted"``, with ``x_star = s``, the same ``f_star``, ``noise`` and
        ``paper_id``, and a fixed dimension (shift a function after :meth:`~BenchmarkFunction.
        with_dim`, not before).
    """
    if not isinstance(f, BenchmarkFunction):
        raise TypeError(f"shifted() needs a BenchmarkFunction, got {type(f).__name__}")
    s = shift_point(f, seed)
    s.setflags(write=False)
    return dataclasses.replace(
        f,
        name=f"{f.name}@shifted",
        x_star=s,
        func=partial(_shifted_formula, f.func, s, f.x_star),
        scalable=False,
        optimum=None,
        description=f"{f.description}; optimum shifted to a point drawn with seed {int(seed)}",
    )
