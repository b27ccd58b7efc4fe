"""Boundary policies: what happens to a coordinate that leaves the box.

Both are pure array functions of ``(position, velocity, lo, hi)`` returning new arrays
(the optimizers' kernels apply them in place; ``confine_positions`` is the in-place form for
positions alone).
"""

from __future__ import annotations

import numpy as np

BOUNDARY_POLICIES = ("clip", "reflect")


def clip(p: np.ndarray, u: np.ndarray, lo, hi) -> tuple[np.ndarray, np.ndarray]:
    """Clamp positions into ``[lo, hi]``; velocities unchanged (MAWDO paper Eq. 3, GWO.m, WOA.m)."""
    return np.clip(p, lo, hi), u


def reflect_damped(
    p: np.ndarray, u: np.ndarray, lo, hi, eta: float = 0.5
) -> tuple[np.ndarray, np.ndarray]:
    """Reflective-damped boundary (MAWDO paper Eqs. 15-16).

    A coordinate past bound ``b`` becomes ``2b - p`` and its velocity ``-eta * u``; whatever is
    still outside after one reflection (a step longer than the box) is clipped
    (docs/deviations.md#d-mawdo-boundary).

    Parameters
    ----------
    p, u : numpy.ndarray
        Positions and velocities of the same shape.
    lo, hi : float or numpy.ndarray
        Bounds, broadcastable to ``p``.
    eta : float
        Damping coefficient in [0, 1]; 0.5 in the paper.
    """
    over = p > hi
    under = p < lo
    out = over | under
    p = np.where(over, 2.0 * hi - p, np.where(under, 2.0 * lo - p, p))
    u = np.where(out, -eta * u, u)
    return np.clip(p, lo, hi), u


def confine_positions(policy: str, p: np.ndarray, lo, hi) -> np.ndarray:
    """Positions only, in place: what :func:`apply_boundary` does to ``p`` (for restarted
    parcels, whose velocity is reset anyway), with masks as the only temporaries."""
    if policy == "reflect":
        over, under = p > hi, p < lo  # both taken before either reflection, as reflect_damped
        np.subtract(2.0 * hi, p, out=p, where=over)
        np.subtract(2.0 * lo, p, out=p, where=under)
    elif policy != "clip":
        raise ValueError(f"unknown boundary policy {policy!r}; use one of {BOUNDARY_POLICIES}")
    return np.clip(p, lo, hi, out=p)


def apply_boundary(policy: str, p, u, lo, hi, eta: float = 0.5):
    """Dispatch on the policy name (``"clip"`` or ``"reflect"``)."""
    if policy == "clip":
        return clip(p, u, lo, hi)
    if policy == "reflect":
        return reflect_damped(p, u, lo, hi, eta)
    raise ValueError(f"unknown boundary policy {policy!r}; use one of {BOUNDARY_POLICIES}")
