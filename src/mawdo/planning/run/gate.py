"""The guide gate: a (re)plan whose answer the exact guides already vouch for needs no swarm.

The seeds a (re)plan starts from hold the guides' own answers: the static guide's shortest routes
in distinct homotopy classes from the robot, the timed routes at the first plan and while one is
followed, the previous plan's remainder and the straight line (:func:`plain_seeds`). Ranked by
the planner's cost they are ``guide_only``'s candidates.

No route from the robot to the goal is shorter than the static shortest route ``L_s``, and none
arrives before ``L_s / v``. When the best seed is at most ``hold_gap`` (relative) longer than
``L_s`` and the guard finds it collision-free to the goal driven at full speed, no search can
shorten it or make it arrive earlier by more than ``hold_gap``: :func:`gated_plan` takes it
without consulting the optimizer (:attr:`~mawdo.planning.run.config.PlannerConfig.guide_gate`).
This is the rule by which a plan is held once a search could not improve it
(:meth:`~mawdo.planning.run.decide.DecidingRun._holds`), applied before the search instead of
after it. What a search could still change is the turning term C3 of Eq. 24 (Eq. 28): the seed
is the guide's taut route, whose corners the swarm may round at some cost in length.

A gated plan counts as a replan (its latency is the ranking's and the guard's) and in
:attr:`~mawdo.planning.run.result.PlanResult.gated`; the plan is then held by the ``hold_gap``
rule while it stays collision-free, as a stalled search's plan is. Where movers make the guides'
answer a detour or a collision the swarm searches as before, and the gate's time is part of
that replan's latency.
"""

from __future__ import annotations

import time

import numpy as np

from mawdo.planning.refine.cost import assemble_paths
from mawdo.planning.run.result import Replan
from mawdo.planning.world.path import densify, polyline_length

__all__ = ["gated_plan", "near_shortest", "plain_seeds", "rank_seeds"]


def plain_seeds(run, pos, step: int, remainder) -> np.ndarray:
    """The guides' answers from ``pos`` at ``step`` as candidates ``(n, 2 m)``, unperturbed:
    the timed routes' paths (where the run asks them), the static guide's routes, the previous
    plan's remainder and the straight line to the goal, clipped to the cost's box."""
    m = run.m
    rows = list(run.guide.seed_rows(pos, m)) if run.guide else []
    if remainder is not None:
        rows.append(densify(remainder, m).reshape(-1))
    rows.append(densify(np.array([pos, run.sc.goal]), m).reshape(-1))
    X = np.vstack([run._timed_seeds(pos, step, remainder is None), np.array(rows)])
    return np.clip(X, *run.cost.bounds)


def rank_seeds(run, pos, step: int, remainder, extra=None):
    """:func:`plain_seeds` ranked by the run's cost from ``pos`` at time ``step`` (plus
    ``extra(X, pos)``, the turn-rate penalty, where given): ``(X, f)``, cheapest first."""
    X = plain_seeds(run, pos, step, remainder)
    f = np.asarray(run.cost(X, start=pos, t0=float(step)), dtype=float)
    if extra is not None:
        f = f + extra(X, pos)
    order = np.argsort(f, kind="stable")
    return X[order], f[order]


def record(run, pos, step: int, best, cost: float, nfev: int, latency: float) -> Replan:
    """Append the :class:`~mawdo.planning.run.result.Replan` of a plan made without a search."""
    length, ncol, _ = run.cost.parts(best[None, :], start=pos, t0=float(step))
    rep = Replan(step=step, position=np.array(pos, dtype=float),
                 waypoints=best.reshape(-1, 2).copy(), cost=cost, length=float(length[0]),
                 collisions=int(ncol[0]), latency=latency, nfev=nfev,
                 history=np.array([cost]))  # fmt: skip
    run.replans.append(rep)
    return rep


def near_shortest(run, route, length: float) -> bool:
    """``route`` (of ``length`` px) is at most ``hold_gap`` (relative, > 0) longer than the
    static shortest route from its first point: the test of a held plan and of a gated one."""
    gap = run.cfg.hold_gap
    return gap > 0 and length <= (1.0 + gap) * run.guide.shortest(route[0])


def certifies(run, pos, step: int, best) -> bool:
    """True when ``best`` (a candidate from ``pos`` at ``step``) is at most ``hold_gap``
    (relative) longer than the static shortest route from ``pos`` and the guard finds it
    collision-free to the goal, driven at full speed from ``step``."""
    route = assemble_paths(best[None, :], pos, run.sc.goal)[0]
    length = polyline_length(route)
    if not near_shortest(run, route, length):
        return False
    return run.guard.stretch_hits(route, float(step), length) == 0


def gated_plan(run, pos, step: int, remainder, extra=None):
    """The (re)plan without a search when the guides certify it (:func:`certifies`): the
    ranked seeds, best first, for the guard to choose from; ``None`` when the swarm must search
    (or the gate does not apply: a frozen-map run, another cost mode, no static guide, or
    acceleration or turn-rate limits, under which the shortest route is not the fastest)."""
    if not (run.dynamic and run.cfg.mode == "spacetime" and run.guide is not None):
        return None
    lim = run.limits
    if lim is not None and (lim.accel, lim.turn) != (None, None):
        return None  # stops and turns take time: the shortest route need not arrive first
    t_start = time.perf_counter()
    X, f = rank_seeds(run, pos, step, remainder, extra)
    if not certifies(run, pos, step, X[0]):
        return None
    record(run, pos, step, X[0], float(f[0]), len(X), time.perf_counter() - t_start)
    run.counts["gated"] += 1
    run.stalled = True  # held from now on by the hold_gap rule while it stays collision-free
    return X
