"""Benchmark values read back from a results store (final values, convergence curves)."""

from __future__ import annotations

from typing import Any

import numpy as np

from mawdo.experiments.store import Store


def finals(store: Store) -> dict[tuple[str, str], dict[str, Any]]:
    """Final values per ``(algorithm, function)``: arrays ``run, fun, error, nfev, wall`` of the
    successful runs (run order) and ``failed``, the number of failed runs."""
    acc: dict[tuple[str, str], list] = {}
    for a, f, r in store.rows(skip=("curve", "curve_nfev", "params")):
        acc.setdefault((a, f), []).append(r)
    out: dict[tuple[str, str], dict[str, Any]] = {}
    for key, items in acc.items():
        ok = [r for r in items if not r.failed]
        out[key] = {
            "run": np.array([r.run for r in ok], dtype=np.int64),
            "fun": np.array([r.fun for r in ok], dtype=float),
            "error": np.array([r.error for r in ok], dtype=float),
            "nfev": np.array([r.nfev for r in ok], dtype=float),
            "wall": np.array([r.wall_time for r in ok], dtype=float),
            "failed": len(items) - len(ok),
        }
    return out


def curves(store: Store, algorithm: str, function: str) -> tuple[np.ndarray, np.ndarray, float]:
    """Best-so-far curves of the successful runs of one (algorithm, function).

    Returns
    -------
    curve : numpy.ndarray
        ``(R, T)`` best-so-far values; shorter curves are padded with their last value.
    curve_nfev : numpy.ndarray
        ``(R, T)`` evaluations spent, padded the same way.
    f_star : float
        The function's optimum (NaN if unknown).
    """
    recs = [r for _, _, r in store.rows(algorithm, function) if not r.failed]
    if not recs:
        return np.empty((0, 0)), np.empty((0, 0)), float("nan")
    T = max(r.curve.size for r in recs)
    c = np.stack([np.pad(r.curve, (0, T - r.curve.size), mode="edge") for r in recs])
    n = np.stack([np.pad(r.curve_nfev, (0, T - r.curve_nfev.size), mode="edge") for r in recs])
    fs = recs[0].f_star
    return c, n, float("nan") if fs is None else float(fs)
