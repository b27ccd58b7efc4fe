"""Why a safe-interval query found no route, in words a user can act on.

:meth:`~mawdo.planning.guide.sipp.guide.SafeIntervalGuide.routes` returns an empty list when
no timed route of the roadmap reaches the goal within the horizon. The causes, tested in this
order (the first that holds is the answer):

1. the goal is cut off on the static map (no roadmap path from the start);
2. the horizon ends before the static shortest route could arrive;
3. with kinematic limits, the robot's braking lead meets a mover or a wall; the start is
   inside a mover at ``t0`` (the search's own error); or a route exists after all (then the
   sentence says so, with its arrival);
4. the goal is covered by movers (grown by robot radius + clearance) from the earliest
   arrival on the static map to the horizon's end: the movers are named, with when each
   covers it; a random walker taken as a reachable set (``walkers="reachable"``) grows
   without end, so it covers every point near it sooner or later;
5. otherwise the goal is free at some time the robot could be there, and the movers bar
   every way to it in time.

Everything is in the guide's units: pixels and time steps.
"""

from __future__ import annotations

import numpy as np

from mawdo.planning.guide.sipp.intervals import safe_intervals
from mawdo.planning.guide.sipp.profiled import lead_clear

__all__ = ["covering_movers", "why_no_route"]

#: Movers named at most in an explanation (the earliest first).
NAMED = 3


def covering_movers(guide, point, t_from: float) -> list[tuple[str, float, float, bool]]:
    """The movers that cover ``point`` at some time in ``[t_from, guide.t_end]``.

    Parameters
    ----------
    guide : SafeIntervalGuide
        The query (its movers, walkers mode, lookahead and horizon).
    point : array_like, shape (2,)
        A point (pixels).
    t_from : float
        Earliest time of interest (time steps).

    Returns
    -------
    list of (str, float, float, bool)
        Per covering mover ``(id, first, last, reachable)``: its obstacle id, the start and end
        (time steps) of its first covering window after ``t_from`` (``last`` is the horizon's
        end where it covers the point to the end), and whether it is a random walker taken as
        a reachable set; by the window's start.
    """
    p = np.reshape(np.asarray(point, dtype=float), (1, 2))
    road, t0, t_end = guide.roadmap, guide.t0, guide.t_end
    out = []
    cut = guide.checked_until < t_end  # (a lookahead, as the guide tabulated its movers)
    for j, obstacle in enumerate(road.moving):
        one = road.movers(t0, guide.checked_until, guide.walkers, cut, only=[j])
        _, lo, hi = safe_intervals(p, t0, t_end, one.arrays())
        # the covered windows are the gaps between the safe ones (open intervals)
        edges = np.concatenate(([t0], np.column_stack([lo, hi]).ravel(), [t_end]))
        gaps = edges.reshape(-1, 2)
        gaps = gaps[(gaps[:, 1] > gaps[:, 0]) & (gaps[:, 1] > t_from)]
        if len(gaps):
            reachable = bool(one.kind[0] == 1)  # (Movers' kind 1: a growing reachable set)
            first = max(float(gaps[0, 0]), t0)
            out.append((obstacle.id, first, float(gaps[0, 1]), reachable))
    return sorted(out, key=lambda m: m[1])


def why_no_route(guide) -> str:
    """A sentence on why ``guide`` has no route to the goal (see the module docstring).

    Runs the guide's search (:meth:`routes` with ``k = 1``) where the static tests pass, so
    it may be asked before or after :meth:`routes`.
    """
    v = float(guide.scenario.robot_speed)
    dist = float(guide.to_goal[guide.start])
    if not np.isfinite(dist):
        return (
            "the goal cannot be reached on the static map: no roadmap path joins the start "
            "to the goal keeping the robot radius plus clearance "
            f"({guide.scenario.robot_radius:g} + {guide.roadmap.clearance:g} px) from every "
            "wall; a narrow passage may need a smaller clearance"
        )
    arrive = guide.t0 + dist / v
    if arrive >= guide.t_end:
        return (
            f"the horizon is too short: the static shortest route ({dist:.1f} px) arrives at "
            f"t = {arrive:.1f} at the earliest, after the horizon's end t = {guide.t_end:.1f}; "
            f"give horizon > {arrive - guide.t0:.1f} time steps"
        )
    if guide.profile is not None and not lead_clear(guide):
        return (
            "the robot cannot brake clear: a step of its braking lead (from its current "
            "motion to rest) meets a mover, a wall or the map's border, so no timed route can "
            "start from it"
        )
    try:
        found = guide.routes(1)
    except ValueError as exc:  # the start inside a mover at t0
        return str(exc)
    if found:
        return f"nothing stops the robot: the earliest route arrives at t = {found[0].arrival:.1f}"
    free = guide.intervals(0)  # the goal is the roadmap's vertex 0
    later = free[free[:, 1] > arrive]
    if len(later):
        spans = ", ".join(f"({max(a, arrive):.1f}, {b:.1f})" for a, b in later[:NAMED])
        spans += ", ..." if len(later) > NAMED else ""
        return (
            f"the goal is free at times the robot could be there ({spans}), but the movers "
            f"bar every way to it in time on this roadmap; a longer horizon (now to t = "
            f"{guide.t_end:.1f}), waiting spots (spots=) or a smaller clearance may help"
        )
    movers = covering_movers(guide, guide.nodes[0], arrive)
    named = "; ".join(
        f"{name!r} from t = {a:.1f} to " + (f"{b:.1f}" if b < guide.t_end else "the end")
        + (" (a random walker taken as a reachable set, which grows without end)" if r else "")
        for name, a, b, r in movers[:NAMED]
    )  # fmt: skip
    more = f" and {len(movers) - NAMED} more" if len(movers) > NAMED else ""
    if any(r for *_, r in movers):
        hint = "; walkers='known' plans around the walkers' seeded walk instead"
    else:
        hint = "; a longer horizon may find it free later"
    return (
        f"the goal is covered from the earliest arrival on the static map (t = {arrive:.1f}) "
        f"to the horizon's end (t = {guide.t_end:.1f}): {named}{more}{hint}"
    )
