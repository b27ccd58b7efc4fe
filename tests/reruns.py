"""Shared check of the rerun tests: a task computed twice on this machine gives the same rows."""

from __future__ import annotations

import numpy as np


def assert_repeats(new, again) -> None:
    """The rows of two computations of one task: the same values, evaluations and points."""
    for r, q in zip(new, again, strict=True):
        assert r.error_text is None and r.fun == q.fun and r.nfev == q.nfev
        assert np.array_equal(r.best_x, q.best_x) and np.array_equal(r.evals, q.evals)
