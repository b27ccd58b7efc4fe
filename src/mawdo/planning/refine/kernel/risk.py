"""The collision-risk term's sum for a population (:mod:`mawdo.planning.refine.risk`), compiled:
each candidate's path is walked once, the robot's centre taken at every time step, and each
agent's contact probability read from a table of the Rice CDF (:func:`rice_table`).

The table is indexed by ``u = R / s`` (contact distance over the centre's s.d.) and
``x = (d - R) / s`` (how far outside the contact distance the predicted centre is, in s.d.s):
in these variables the probability is a smooth function on a bounded box, read by bilinear
interpolation. Outside the box: ``x > X_HI`` is 0 (below 1e-7), ``x < X_LO`` is 1 (the same),
``u > U_HI`` is read at ``U_HI`` and carried toward the straight edge's ``Phi(-x)`` as
``U_HI / u`` (the disc's edge is then nearly straight at the scale of ``s``; its curvature's
effect falls as ``s / R``).
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

#: The table's box and steps: ``x = (d - R) / s`` in [X_LO, X_HI], ``u = R / s`` in [0, U_HI].
X_LO, X_HI, X_STEP = -6.0, 6.0, 0.05
U_HI, U_STEP = 40.0, 0.05


def rice_table() -> np.ndarray:
    """``P[iu, ix]``: the Rice CDF ``1 - Q_1(d / s, R / s)`` at ``u = iu U_STEP``,
    ``x = X_LO + ix X_STEP`` (``d = s (x + u)``; 0 where that is negative is never read
    as a distance: it is the probability at ``d = 0``)."""
    from scipy.special import chndtr

    u = np.arange(0.0, U_HI + U_STEP / 2, U_STEP)
    x = np.arange(X_LO, X_HI + X_STEP / 2, X_STEP)
    uu, xx = np.meshgrid(u, x, indexing="ij")
    d = np.maximum(xx + uu, 0.0)
    return np.ascontiguousarray(np.clip(chndtr(uu**2, 2.0, d**2), 0.0, 1.0))


@njit(cache=True, nogil=True, error_model="numpy")
def contact_probability(d, r, s, table):  # pragma: no cover - compiled
    """Probability that a centre at distance ``d`` (px) with per-axis s.d. ``s`` lies within
    ``r`` (px) of the robot's centre, read from ``table`` (:func:`rice_table`)."""
    if s <= 0.0:
        return 1.0 if d < r else 0.0
    x = (d - r) / s
    if x >= X_HI:
        return 0.0
    if x <= X_LO:
        return 1.0
    ratio = r / s
    u = min(ratio, U_HI) / U_STEP
    fx = (x - X_LO) / X_STEP
    iu = min(int(u), table.shape[0] - 2)
    ix = min(int(fx), table.shape[1] - 2)
    gu, gx = u - iu, fx - ix
    lo = table[iu, ix] * (1.0 - gx) + table[iu, ix + 1] * gx
    hi = table[iu + 1, ix] * (1.0 - gx) + table[iu + 1, ix + 1] * gx
    p = lo * (1.0 - gu) + hi * gu
    if ratio > U_HI:  # the edge's curvature fades as s / R: toward the half-plane's Phi(-x)
        edge = 0.5 * math.erfc(x / math.sqrt(2.0))
        p = edge + (p - edge) * (U_HI / ratio)
    return p


@njit(cache=True, nogil=True, error_model="numpy")
def expected_contacts(X, start, goal, speed, centres, reach, sd, table, out):  # pragma: no cover
    """``out[i]``: the sum over time steps ``k = 1 .. K`` while candidate ``i``'s robot drives
    (``speed k`` below the path's length) and over agents ``a`` of the contact probability.

    Parameters
    ----------
    X : float64 (n, 2 m)
        Candidates' waypoints (pixels); the path is ``start, w1..wm, goal``.
    start, goal : float64 (2,)
    speed : float
        Pixels per time step (> 0).
    centres : float64 (K, A, 2)
        Each agent's predicted centre at step ``k + 1`` after the path's start time.
    reach : float64 (A,)
        Contact distance per agent (robot radius plus the agent's own, pixels).
    sd : float64 (K, A)
        Per-axis s.d. of each predicted centre (pixels).
    table : float64 (U, X)
        :func:`rice_table`.
    out : float64 (n,)
        Filled; NaN for a candidate with a non-finite coordinate.
    """
    n, dim = X.shape
    m = dim // 2
    K, A = sd.shape
    for i in range(n):
        finite = True
        for j in range(dim):
            if not math.isfinite(X[i, j]):
                finite = False
        if not finite:
            out[i] = np.nan
            continue
        total = 0.0
        seg = 0  # the segment from point seg to point seg + 1 (0: from start)
        ax, ay = start[0], start[1]
        bx, by = (X[i, 0], X[i, 1]) if m > 0 else (goal[0], goal[1])
        seg_len = math.hypot(bx - ax, by - ay)
        done = 0.0  # arc length up to point seg
        for k in range(K):
            arc = speed * (k + 1)
            while done + seg_len <= arc and seg < m:
                done += seg_len
                seg += 1
                ax, ay = bx, by
                bx, by = (X[i, 2 * seg], X[i, 2 * seg + 1]) if seg < m else (goal[0], goal[1])
                seg_len = math.hypot(bx - ax, by - ay)
            if done + seg_len <= arc:  # arrived: the run ends at the goal
                break
            f = (arc - done) / seg_len
            px, py = ax + f * (bx - ax), ay + f * (by - ay)
            for a in range(A):
                dx, dy = px - centres[k, a, 0], py - centres[k, a, 1]
                d2 = dx * dx + dy * dy
                far = reach[a] + X_HI * sd[k, a]
                if d2 >= far * far:  # (most pairs: no square root, no table)
                    continue
                total += contact_probability(math.sqrt(d2), reach[a], sd[k, a], table)
        out[i] = total
