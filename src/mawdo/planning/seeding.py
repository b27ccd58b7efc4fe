"""Seeds and one optimizer call of a (re)plan: guide/warm-start copies, via-point paths.

Kept apart from :mod:`mawdo.planning.planner` so that the run loop
(:mod:`mawdo.planning.execute`) imports them without a cycle."""

from __future__ import annotations

import numpy as np

from mawdo.planning.config import PLANNING_OPTIONS, PlannerConfig
from mawdo.planning.cost import PathCost
from mawdo.planning.path import densify


def _optimise(
    cost: PathCost,
    pos,
    t,
    algorithm,
    config: PlannerConfig,
    iters,
    seed_seq,
    x0,
    max_time,
    pop_size,
):
    from mawdo.minimize import minimize

    lb, ub = cost.bounds
    opts = {**PLANNING_OPTIONS.get(algorithm, {}), **config.options}
    res = minimize(
        lambda X: cost(X, start=pos, t0=t),
        lb=lb,
        ub=ub,
        algorithm=algorithm,
        runs=1,
        seed=seed_seq,
        max_iter=iters,
        max_time=max_time,
        x0=x0,
        pop_size=pop_size,
        **opts,
    )
    return res


def _seeds(route, m, config, rng, lb, ub):
    """A route's ``m`` waypoints (geometry kept) plus ``warm_copies`` perturbed copies."""
    base = densify(route, m).reshape(-1)
    noise = rng.normal(0.0, config.warm_sigma, (config.warm_copies, base.size))
    return np.clip(np.vstack([base, base + noise]), lb, ub)


def _via_paths(start, goal, m, n, rng, lb, ub, width, height):
    """``n`` path-like candidates: start -> one or two random via points -> goal, densified.

    Uniform random waypoints make zig-zags that cross every obstacle; routes through random via
    points are short, diverse, and often collision-free, the usual way to seed a waypoint planner.
    """
    out = np.empty((n, 2 * m))
    for i in range(n):
        k = 1 + int(rng.random() < 0.5)
        via = rng.random((k, 2)) * [width, height]
        out[i] = densify(np.vstack([start, via, goal]), m).reshape(-1)
    return np.clip(out, lb, ub)
