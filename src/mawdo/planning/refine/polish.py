"""Polish: a greedy local descent on the best plan of a (re)plan, under the same cost.

The swarm finds the route's topology and timing; what it leaves is local slack, waypoints a
little off the line between their neighbours, which a population of 240 rarely removes in 15
iterations. Each polish round moves single waypoints toward the midpoint of their neighbours
(the start and the goal at the ends), evaluates all those variants in one batched cost call and
keeps the cheapest if it lowers the cost. It is a discrete Laplacian smoothing step, accepted
only on the plan's own cost, so collisions, timing and every weight of Eqs. 24-27 are judged
exactly as the optimizer judges them (docs/deviations.md#d-polish).
"""

from __future__ import annotations

import functools

import numpy as np

# a round must lower the cost by more than this (relative) to count: rounding can make a
# collinear variant an ulp cheaper, which is not a better route
POLISH_TOL = 1e-9


def midpoint_moves(x, start, goal, fractions) -> np.ndarray:
    """Variants of one plan, each with a single waypoint moved toward its neighbours' midpoint.

    Parameters
    ----------
    x : numpy.ndarray, shape (2 m,)
        Waypoints ``(x1, y1, ..., xm, ym)`` in pixels, in the order the robot visits them.
    start, goal : array_like, shape (2,)
        The plan's fixed ends (pixels); they are the neighbours of the first and last waypoint.
    fractions : sequence of float
        Step lengths as fractions of the way to the midpoint, each in (0, 1]; 1 puts the
        waypoint on the midpoint.

    Returns
    -------
    numpy.ndarray, shape (len(fractions) m, 2 m)
        Row ``a m + i`` is ``x`` with waypoint ``i`` moved by ``fractions[a]``:
        ``w_i + f ((w_{i-1} + w_{i+1}) / 2 - w_i)``.
    """
    w = np.asarray(x, float).reshape(-1, 2)
    m = len(w)
    chain = np.empty((m + 2, 2))
    chain[0], chain[1:-1], chain[-1] = start, w, goal
    pull = 0.5 * (chain[:-2] + chain[2:]) - w  # (m, 2): toward the midpoint
    f = np.asarray(fractions, float)
    # every row a copy of the plan, then row a m + i's waypoint i replaced: one flat scatter
    # (called once per polish round; a (F, m, m, 2) fancy-indexed copy cost more than the rest)
    out = np.tile(w.reshape(-1), (f.size * m, 1))
    moved = w[None, :, :] + f[:, None, None] * pull[None, :, :]  # (F, m, 2)
    out.reshape(-1)[_diagonal(f.size, m)] = moved.reshape(-1)
    return out


@functools.lru_cache(maxsize=16)
def _diagonal(n_fractions: int, m: int) -> np.ndarray:
    """Flat indices, in a ``(n_fractions m, 2 m)`` array, of waypoint ``i``'s two coordinates
    in row ``a m + i``, ordered as ``(a, i, coordinate)`` (read-only, shared)."""
    a, i, k = np.meshgrid(np.arange(n_fractions), np.arange(m), np.arange(2), indexing="ij")
    flat = ((a * m + i) * (2 * m) + 2 * i + k).reshape(-1)
    flat.setflags(write=False)
    return flat


def polish(cost, x, fx: float, start, goal, rounds: int, fractions, lb=None, ub=None):
    """Greedy descent by :func:`midpoint_moves`: at most ``rounds`` rounds, stopping early
    when no variant lowers the cost by more than ``POLISH_TOL`` (relative).

    Parameters
    ----------
    cost : callable
        ``cost(X (n, 2 m)) -> (n,)`` float, the plan's cost from ``start`` at its start time.
    x : numpy.ndarray, shape (2 m,)
        Plan to polish (pixels); ``fx`` is its cost.
    start, goal : array_like, shape (2,)
        The plan's fixed ends (pixels).
    rounds : int
        Most rounds (>= 0); each costs one call of ``len(fractions) m`` candidates.
    fractions : sequence of float
        Step lengths of :func:`midpoint_moves`.
    lb, ub : array_like, optional
        Waypoint bounds; variants are clipped to them (a midpoint of in-bound neighbours is in
        bounds, so this only matters for ends outside the box).

    Returns
    -------
    x, fx, nfev : numpy.ndarray, float, int
        The polished plan, its cost (never above ``fx``) and the evaluations spent.
    """
    x, fx, nfev = np.array(x, float), float(fx), 0
    for _ in range(rounds):
        cand = midpoint_moves(x, start, goal, fractions)
        if lb is not None:
            cand = np.clip(cand, lb, ub)
        F = np.asarray(cost(cand), float)
        nfev += len(cand)
        j = int(np.argmin(F))
        if not F[j] < fx - POLISH_TOL * abs(fx):
            break
        x, fx = cand[j].copy(), float(F[j])
    return x, fx, nfev
