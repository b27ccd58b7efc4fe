"""The safe-interval guide's timed routes under acceleration and turn-rate limits.

:class:`~mawdo.planning.guide.sipp.guide.SafeIntervalGuide` with a ``profile`` searches with
:func:`~mawdo.planning.guide.sipp.search.search_limited` and writes each edge of the route
found as its rest-to-rest profile (:func:`profile_points`;
:mod:`mawdo.planning.guide.sipp.profile`): one point per piece boundary, at whole steps, so
that the route's straight uniform pieces between its points are the motion the run drives
(:func:`~mawdo.planning.guide.timeguide.position_at` at whole steps gives the profile's
positions). A robot moving when the guide is asked first brakes along its heading (the
``lead``), each step checked as an edge is (:func:`lead_clear`).
"""

from __future__ import annotations

import numpy as np

from mawdo.planning.guide.sipp.intervals import segment_free
from mawdo.planning.guide.sipp.search import search_limited

__all__ = ["lead_clear", "profile_points", "profiled_search"]


def _heading(lead: np.ndarray) -> np.ndarray:
    """Unit heading of the lead's last move that is not a rest (zeros: the robot was at
    rest, no heading)."""
    for i in range(len(lead) - 1, 0, -1):
        d = lead[i] - lead[i - 1]
        n = float(np.hypot(*d))
        if n > 0.0:
            return d / n
    return np.zeros(2)


def lead_clear(guide) -> bool:
    """Every step of the guide's lead (braking, one step per time step from ``t0``) keeps
    clear of the movers (exact) and of the inflated statics and the map's border."""
    lead, t0 = guide.lead, guide.t0
    for i in range(len(lead) - 1):
        a, b = lead[i], lead[i + 1]
        if not guide.roadmap.segment_clear(a, b):
            return False
        if not segment_free(a[0], a[1], b[0], b[1], t0 + i, t0 + i + 1.0, guide._mv):
            return False
    return True


def profiled_search(guide, banned: np.ndarray):
    """The guide's search under its profile (as :func:`~mawdo.planning.guide.sipp.search.search`
    returns, but the table: the guide keeps it)."""
    graph = (guide.nodes, guide.indptr, guide.indices, guide.weights, guide.to_goal)
    t_start = guide.t0 + float(len(guide.lead) - 1)
    *res, guide.safe = search_limited(
        graph, guide._table, guide._lim, guide.start, 0, t_start, _heading(guide.lead),
        guide.t_end, guide.safe, banned, guide._mv,
    )  # fmt: skip
    return tuple(res)


def _edge_index(guide, u: int, v: int) -> int:
    lo, hi = guide.indptr[u], guide.indptr[u + 1]
    return int(lo + np.flatnonzero(guide.indices[lo:hi] == v)[0])


def profile_points(guide, u: int, v: int, tau: float):
    """The inner piece boundaries of the profile of edge ``u -> v`` departing at ``tau``:
    ``(points, times)`` lists (pixels, time steps; empty for an edge of one piece)."""
    e = _edge_index(guide, u, v)
    tptr, k0, c0, dur, w, _ = guide._table
    pu, pv, L = guide.nodes[u], guide.nodes[v], guide.weights[e]
    d = (pv - pu) / L if L > 0 else np.zeros(2)
    idx = range(tptr[e], tptr[e + 1] - 1)
    return [pu + d * (c0[i] + w[i] * dur[i]) for i in idx], [tau + k0[i] + dur[i] for i in idx]
