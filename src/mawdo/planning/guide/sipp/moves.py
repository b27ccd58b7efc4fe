"""The moves of roadmap edges, as tables of straight uniform pieces, and the departures at
which a move of several pieces meets a mover.

Without limits an edge is one piece at full speed (:func:`straight_moves`,
:func:`straight_rows`); under acceleration or turn-rate limits it is its rest-to-rest profile
laid along the edge (:func:`profiled_moves`), several pieces, whose forbidden departures are
the union of each piece's (:func:`pieces_forbidden`) and whose driving is checked piece by
piece (:func:`pieces_free`). The search (:mod:`~mawdo.planning.guide.sipp.search`) calls the
latter two through :func:`pieces_forbidden_for` and :func:`pieces_free_for`, which a straight
search's specialisation compiles to nothing.
"""

from __future__ import annotations

import numpy as np
from numba import njit, types
from numba.extending import overload

from mawdo.planning.guide.sipp.intervals import forbidden, segment_free

__all__ = [
    "pieces_forbidden",
    "pieces_forbidden_for",
    "pieces_free",
    "pieces_free_for",
    "profiled_moves",
    "straight_moves",
    "straight_rows",
]


@njit(cache=True)
def straight_moves(nodes, indptr, indices, weights, speed):
    """The moves of every edge without limits: one piece at ``speed`` (px per step).

    Returns ``(eptr, edge, piece)``: edge ``e`` has the pieces ``eptr[e]:eptr[e + 1]`` and
    ``edge[e] = (T, hx, hy)``, its duration (time steps) and unit heading (zeros for a
    zero-length edge); ``piece[j] = (k0, ax, ay, ex, ey, dur, bx, by)``: it starts ``k0`` steps
    after the departure and runs ``dur`` steps from ``(ax, ay)`` to ``(bx, by)`` (pixels) at
    velocity ``(ex, ey)`` (px per step).
    """
    E = len(weights)
    edge, piece = np.zeros((E, 3)), np.zeros((E, 8))
    straight_rows(edge, piece, nodes, indptr, indices, weights, speed, 0)
    return np.arange(E + 1), edge, piece


@njit(cache=True)
def straight_rows(edge, piece, nodes, indptr, indices, weights, speed, first):
    """Write :func:`straight_moves`'s rows of the edges out of the vertices ``first ..
    len(indptr) - 2`` into ``edge`` and ``piece`` (rows of other edges untouched): a roadmap
    keeps its own edges' rows and writes each query's start's (the last vertex) only."""
    for u in range(first, len(indptr) - 1):
        for e in range(indptr[u], indptr[u + 1]):
            v, T, L = indices[e], weights[e] / speed, weights[e]
            ux, uy, vx, vy = nodes[u, 0], nodes[u, 1], nodes[v, 0], nodes[v, 1]
            edge[e, 0] = piece[e, 5] = T
            piece[e, 0] = 0.0
            piece[e, 1], piece[e, 2], piece[e, 6], piece[e, 7] = ux, uy, vx, vy
            piece[e, 3] = piece[e, 4] = edge[e, 1] = edge[e, 2] = 0.0
            if T > 0.0:  # a zero-length edge (the start on a vertex): a move of no duration
                piece[e, 3], piece[e, 4] = (vx - ux) / T, (vy - uy) / T
            if L > 0.0:
                edge[e, 1], edge[e, 2] = (vx - ux) / L, (vy - uy) / L


@njit(cache=True)
def profiled_moves(nodes, indptr, indices, weights, table):
    """The moves of every edge under limits: its rest-to-rest profile ``table``
    (:func:`~mawdo.planning.guide.sipp.profile.profile_table` of ``weights``), laid along the
    edge; as :func:`straight_moves` returns."""
    tptr, k0, c0, dur, w, steps = table
    edge, piece = np.zeros((len(weights), 3)), np.empty((len(k0), 8))
    for u in range(len(indptr) - 1):
        ux, uy = nodes[u, 0], nodes[u, 1]
        for e in range(indptr[u], indptr[u + 1]):
            L = weights[e]
            dx, dy = 0.0, 0.0
            if L > 0.0:
                dx, dy = (nodes[indices[e], 0] - ux) / L, (nodes[indices[e], 1] - uy) / L
            edge[e, 0], edge[e, 1], edge[e, 2] = steps[e], dx, dy
            for j in range(tptr[e], tptr[e + 1]):
                c1 = c0[j] + w[j] * dur[j]
                piece[j, 0], piece[j, 5] = k0[j], dur[j]
                piece[j, 1], piece[j, 2] = ux + c0[j] * dx, uy + c0[j] * dy
                piece[j, 3], piece[j, 4] = w[j] * dx, w[j] * dy
                piece[j, 6], piece[j, 7] = ux + c1 * dx, uy + c1 * dy
    return tptr, edge, piece


@njit(cache=True)
def pieces_forbidden(piece, i, j, lo, hi, mv):
    """Departures in ``[lo, hi]`` (time steps) at which the pieces ``i:j`` of a move (one
    edge's, rows of :func:`straight_moves`'s ``piece``) meet a mover: the union of each
    piece's, shifted by its start; sorted, disjoint closed intervals ``(k, 2)``."""
    parts = np.empty((0, 2))
    for q in range(i, j):
        k0, ax, ay, ex, ey, dur = piece[q, :6]
        F = forbidden(ax, ay, ex, ey, dur, lo + k0, hi + k0, mv)
        parts = np.concatenate((parts, F - k0))
    parts = parts[np.argsort(parts[:, 0])]
    out = np.empty_like(parts)
    k = 0
    for q in range(len(parts)):
        if k > 0 and parts[q, 0] <= out[k - 1, 1]:
            out[k - 1, 1] = max(out[k - 1, 1], parts[q, 1])
        else:
            out[k] = parts[q]
            k += 1
    return out[:k]


@njit(cache=True)
def pieces_free(piece, i, j, tau, mv):
    """True iff the pieces ``i:j`` of a move departing at ``tau`` keep clear of every mover
    (each by :func:`~mawdo.planning.guide.sipp.intervals.segment_free`)."""
    for q in range(i, j):
        t1 = tau + piece[q, 0]
        if not segment_free(
            piece[q, 1], piece[q, 2], piece[q, 6], piece[q, 7], t1, t1 + piece[q, 5], mv
        ):
            return False
    return True


def pieces_forbidden_for(whole, piece, i, j, lo, hi, mv):
    """:func:`pieces_forbidden` in compiled code where moves may have several pieces
    (``whole`` a bool); nothing to compile where ``whole`` is None (straight moves, one piece
    each: never asked). The choice is made on the argument's type, so the straight search's
    specialisation never compiles the several-piece code (about 3 s of a cold first plan)."""
    raise NotImplementedError("called from compiled code only")


@overload(pieces_forbidden_for)
def _pieces_forbidden_for(whole, piece, i, j, lo, hi, mv):
    if isinstance(whole, types.NoneType):
        return lambda whole, piece, i, j, lo, hi, mv: np.empty((0, 2))
    return lambda whole, piece, i, j, lo, hi, mv: pieces_forbidden(piece, i, j, lo, hi, mv)


def pieces_free_for(whole, piece, i, j, tau, mv):
    """:func:`pieces_free` in compiled code, chosen on ``whole``'s type as
    `pieces_forbidden_for` is (True where ``whole`` is None: never asked)."""
    raise NotImplementedError("called from compiled code only")


@overload(pieces_free_for)
def _pieces_free_for(whole, piece, i, j, tau, mv):
    if isinstance(whole, types.NoneType):
        return lambda whole, piece, i, j, tau, mv: True
    return lambda whole, piece, i, j, tau, mv: pieces_free(piece, i, j, tau, mv)
