"""A lookahead for the moving obstacles: the part of a block the pass over them sees.

With a horizon ``H`` (time steps), moving obstacles are tested only against the path the robot
travels before ``t0 + H``; standing obstacles and the map's border against all of it. A planner
that trusts its predictions only so far ahead (the safe-interval guide's lookahead) spares the
kernel the tests it would not believe: on a large world most of a random candidate's points
lie past the lookahead.

:func:`horizon_path` lays out, per candidate of the block, its points from the start up to the
last one reached before ``t0 + H``, then the point of the segment that straddles the cut where
the robot is at ``t0 + H`` (the segment's own point where it ends at the cut), end to end, with
the candidate each point belongs to; the last point of each candidate starts no real segment.
The pass over moving obstacles runs on that layout as on a block of one path (the centres'
walk restarts where time goes back: :func:`~mawdo.planning.refine.kernel.centres.centres`):
every segment begun and ended before the cut gets the numbers it gets in the whole block, so
its count is the one it would have there; the cut segment is tested over its part before the
cut. Cutting it, rather than testing it whole, keeps every tested part within ``H`` times the
robot's speed of the start: among thousands of movers the index then skips those far from it
(a random waypoint across the map would otherwise stretch one segment over all of them).
"""

from __future__ import annotations

from numba import njit


@njit(cache=True, fastmath=False, error_model="numpy")
def horizon_path(bn, npts, t_cut, path, hpath, hreal, hcand, hhits):
    """Lay out the block's path up to ``t_cut`` (see the module docstring) into ``hpath``
    (its ``px, py, tt, rvx, rvy``), ``hreal`` and ``hcand``, zeroing ``hhits``.

    Returns ``(npt, tmax)``: points laid out and their latest time (time steps; NaN times left
    out). A point whose time is NaN is never past the cut: such a candidate keeps all of its
    points.
    """
    px, py, tt, rvx, rvy = path[0], path[1], path[2], path[6], path[7]
    hpx, hpy, htt, hrvx, hrvy = hpath[0], hpath[1], hpath[2], hpath[6], hpath[7]
    n = 0
    tmax = 0.0
    for b in range(bn):
        q = b * npts
        j = npts - 1  # the last point kept
        for k in range(1, npts):
            if tt[q + k] >= t_cut:
                j = k
                break
        for k in range(j + 1):
            p = q + k
            t = tt[p]
            if k == j and t > t_cut:  # where the robot is at the cut (tt[p - 1] < t_cut)
                f = (t_cut - tt[p - 1]) / (t - tt[p - 1])
                hpx[n] = px[p - 1] + f * (px[p] - px[p - 1])
                hpy[n] = py[p - 1] + f * (py[p] - py[p - 1])
                t = t_cut
            else:
                hpx[n] = px[p]
                hpy[n] = py[p]
            htt[n] = t
            hrvx[n] = rvx[p]
            hrvy[n] = rvy[p]
            hreal[n] = k < j
            hcand[n] = b
            hhits[n] = 0
            if t > tmax:
                tmax = t
            n += 1
    return n, tmax
