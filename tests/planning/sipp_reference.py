"""Brute-force reference for the safe-interval guide: earliest arrival on a fine time grid.

States are (vertex, grid time ``k h``). From a state the robot may wait one grid step or drive
an edge of the guide's graph at full speed, departing exactly at ``k h``; after arriving at
``k h + T`` it waits until the next grid time. Every wait and move is judged by the independent
shapely checker (:func:`mawdo.planning.judge.check.check_trajectory`): free iff its least clearance
to every obstacle exceeds ``margin`` (the guide's clearance). Shares no code with the guide's
geometry or search.
"""

from __future__ import annotations

import math

import numpy as np

from mawdo.planning.judge.check import check_trajectory


def _clear(points, times, scenario, margin) -> np.ndarray:
    """Per step of the trajectory: least clearance over all obstacles exceeds ``margin``."""
    rep = check_trajectory(np.asarray(points), scenario, times=np.asarray(times))
    return rep.clearance.min(axis=1) > margin


def _edge_table(scenario, u, v, T, h, K, margin):
    """For departures ``k h`` (k < K): the move ``u -> v`` is free, and so is the wait after it
    until the next grid time. Departures are checked in classes ``k = c mod G`` so that each
    class is one trajectory with non-decreasing times (the jumps back to ``u`` are ignored)."""
    move = np.zeros(K, bool)
    tail = np.zeros(K, bool)
    G = int(math.ceil(T / h)) + 1
    for c in range(G):
        ks = np.arange(c, K, G)
        if not len(ks):
            continue
        pts, times = [], []
        for k in ks:
            k2 = int(math.ceil(k + T / h - 1e-9))
            pts += [u, v, v]
            times += [k * h, k * h + T, max(k2 * h, k * h + T)]
        ok = _clear(pts, times, scenario, margin)
        move[ks] = ok[0::3]
        tail[ks] = ok[1::3]
    return move, tail


def grid_earliest_arrival(scenario, nodes, edges, start, goal, h, K, margin):
    """Earliest arrival (time steps) at ``goal`` on the time grid ``k h``, ``k < K``.

    Parameters
    ----------
    nodes : numpy.ndarray, shape (n, 2)
    edges : list of (int, int, float)
        Directed edges ``(u, v, length_px)``.
    start, goal : int
        Vertex indices; the robot is at ``start`` at time 0.
    h : float
        Grid step (time steps).
    K : int
        Grid times searched.
    margin : float
        Clearance (px) a wait or move must exceed.

    Returns
    -------
    float
        The arrival, ``inf`` if none within the grid.
    """
    speed = scenario.robot_speed
    n = len(nodes)
    wait = np.zeros((n, K), bool)
    for v in range(n):
        wait[v] = _clear([nodes[v]] * (K + 1), h * np.arange(K + 1), scenario, margin)
    tables = [
        _edge_table(scenario, nodes[u], nodes[v], w / speed, h, K, margin) for u, v, w in edges
    ]
    reach = np.zeros((n, K + 1), bool)
    reach[start, 0] = _clear([nodes[start]], [0.0], scenario, margin)[0]
    best = math.inf
    for k in range(K):
        if k * h >= best:
            break
        for v in np.nonzero(reach[:, k])[0]:
            if wait[v, k]:
                reach[v, k + 1] = True
        for (u, v, w), (move, tail) in zip(edges, tables, strict=True):
            if not reach[u, k] or not move[k]:
                continue
            T = w / speed
            if v == goal:
                best = min(best, k * h + T)
            k2 = int(math.ceil(k + T / h - 1e-9))
            if tail[k] and k2 <= K:
                reach[v, k2] = True
    return best
