"""Single-shot and receding-horizon (dynamic) path planning with any registered optimizer.

Receding horizon (docs/deviations.md#d-replan-budget): every ``replan_every`` steps the robot
observes the obstacles, the
optimizer is seeded with the guide's routes (exact visibility graph, distinct homotopy classes,
re-rooted at the robot), the previous best path (reached waypoints dropped, the rest re-spread)
and perturbed copies, and runs for an iteration or wall-time budget on the cost of
:class:`~mawdo.planning.cost.PathCost` (``spacetime`` mode by default); its best is polished by
a greedy local descent (:mod:`mawdo.planning.polish`). The guard verifies the
stretch to be driven before the next replan and falls back to the elite, to waiting or to an
evasive move; the independent checker judges the executed route (:mod:`mawdo.planning.execute`).
This module holds the public entry points (``plan``, the oracle-following baseline) and the
serialisation; settings and result types live in :mod:`mawdo.planning.config` and are
re-exported here."""

from __future__ import annotations

import time

import numpy as np

from mawdo.planning.config import (  # noqa: F401  (public names re-exported)
    PLANNING_OPTIONS,
    PRESETS,
    PlannerConfig,
    PlanResult,
    Replan,
    _config,
    _Drive,
    _resolve,
    step_limit,
)
from mawdo.planning.execute import Run
from mawdo.planning.path import advance, polyline_length
from mawdo.planning.seeding import _optimise, _seeds, _via_paths  # noqa: F401


def plan(
    scenario,
    algorithm: str = "mawdo",
    seed: int = 0,
    config=None,
    dynamic: bool = True,
    progress=None,
    **overrides,
) -> PlanResult:
    """Plan (and, if ``dynamic``, execute with replanning) a path through a scenario.

    Parameters
    ----------
    scenario : Scenario or str
        A scenario or the name of a built-in one (``"paper"``).
    algorithm : str
        Any registered optimizer (``mawdo list algorithms``).
    seed : int or numpy.random.SeedSequence
        Seed of the run; replan ``k`` uses the ``k``-th child of ``SeedSequence(seed)``.
    config : PlannerConfig or str, optional
        Settings or a preset name (``"realtime"`` default, ``"paper"``, ``"quick"``).
    dynamic : bool
        True: receding horizon, the robot moves and replans. False: one plan on the map frozen
        at t = 0 (single-shot static mode), executed without replanning.
    progress : callable, optional
        Called as ``progress(step, max_steps, replans)`` before each step (a progress bar for
        long runs); it must not raise. No effect on the result.
    **overrides
        Fields of :class:`PlannerConfig` to change.

    Returns
    -------
    PlanResult
        Never raises for an unreachable goal: ``success=False`` with a reason. ``success`` is
        true only if the goal is reached and the independent checker accepts the route.

    Notes
    -----
    Pipeline per (re)plan: guide routes from the exact visibility graph (re-rooted at the
    robot), seeds (guide routes, perturbed copies, the warm start), refinement by the optimizer
    under the paper's cost, a polish of its best (``polish_rounds``), then the guard
    (:mod:`mawdo.planning.guard`) before every move.
    """
    return prepare(scenario, algorithm, seed, config, dynamic, **overrides).execute(progress)


def prepare(
    scenario, algorithm: str = "mawdo", seed: int = 0, config=None, dynamic: bool = True,
    **overrides,
) -> Run:  # fmt: skip
    """Check the arguments of :func:`plan` and set the run up (guide, cost) without running:
    ``run.step_limit()`` and ``run.estimate_seconds(steps)`` tell what it will cost, and
    ``run.execute(progress)`` runs it.

    Raises
    ------
    ValueError
        An unknown algorithm, preset or setting, a setting out of its range, a bad seed, or a
        map the guide cannot handle (too many obstacle corners).
    """
    from mawdo.optimizers import OPTIMIZERS
    from mawdo.validate import check_seed

    sc = _resolve(scenario)
    OPTIMIZERS[algorithm]  # an unknown name fails here, listing the known ones
    check_seed(seed)
    cfg = _config(config, overrides)
    return Run(sc, algorithm, seed, cfg, dynamic)


def executed_length(result: PlanResult) -> float:
    """Length of the executed route (pixels)."""
    return polyline_length(result.route)


ORACLE_FOLLOWER = "oracle_follower"


def follow_oracle(scenario, max_steps: int | None = None) -> PlanResult:
    """The baseline a robotics engineer would pick: follow the exact shortest path on the
    obstacles frozen at each instant, ignoring their motion (replanned every step).

    Deterministic (no seed). When the frozen map leaves no path (a moving obstacle covers the
    robot's inflated position or blocks every route) the robot waits for a step.
    """
    from mawdo.planning.oracle import scenario_optimum

    sc = _resolve(scenario)
    v = sc.robot_speed
    max_steps = step_limit(max_steps, sc.straight_line_length(), 0.0, v)[0]
    pos = sc.start.copy()
    drive = _Drive(pos)
    replans: list[Replan] = []
    reason = "step limit reached before the goal"
    for step in range(max_steps + 1):
        if np.hypot(*(sc.goal - pos)) <= 1e-9:
            reason = "goal reached"
            break
        if step == max_steps:
            break
        t0 = time.perf_counter()
        opt = scenario_optimum(sc, t=float(step), static_only=False, start=pos)
        latency = time.perf_counter() - t0
        here = pos.copy()
        passed, frac = (), ()
        if opt.reachable:
            pos, _, passed, frac = advance(opt.path, v)
            waypoints = opt.path[1:-1]
        else:
            waypoints = np.zeros((0, 2))
        replans.append(
            Replan(
                step=step,
                position=here,
                waypoints=waypoints,
                cost=float("nan"),
                length=float(opt.length),
                collisions=0,
                latency=latency,
                nfev=0,
                history=np.zeros(0),
            )
        )
        drive.move(step, pos, passed, frac)
    return drive.result(
        reason,
        scenario=sc,
        algorithm=ORACLE_FOLLOWER,
        seed=0,
        config=PlannerConfig(),
        replans=replans,
    )


def result_to_bytes(result: PlanResult) -> bytes:
    """Serialise what figures need (route, replans) to ``.npz`` bytes; the scenario is not
    included (the study stores its plan, which names it)."""
    import io

    reps = result.replans
    m = max((len(r.waypoints) for r in reps), default=0)
    wp = np.full((len(reps), m, 2), np.nan)
    for i, r in enumerate(reps):
        wp[i, : len(r.waypoints)] = r.waypoints
    h = max((len(r.history) for r in reps), default=0)
    hist = np.full((len(reps), h), np.nan)
    for i, r in enumerate(reps):
        hist[i, : len(r.history)] = r.history
    buf = io.BytesIO()
    np.savez_compressed(
        buf,
        trajectory=result.trajectory,
        route=result.route,
        route_times=result.route_times,
        step=np.array([r.step for r in reps]),
        position=np.array([r.position for r in reps]),
        waypoints=wp,
        cost=np.array([r.cost for r in reps]),
        length=np.array([r.length for r in reps]),
        collisions=np.array([r.collisions for r in reps]),
        latency=np.array([r.latency for r in reps]),
        nfev=np.array([r.nfev for r in reps]),
        history=hist,
        meta=np.array([result.algorithm, str(result.seed), result.reason]),
        success=np.array(result.success),
        collision_free=np.array(result.collision_free),
        min_clearance=np.array(result.min_clearance),
        events=np.array(
            [result.waits, result.evasions, result.fallbacks, result.near_misses, result.holds]
        ),
    )
    return buf.getvalue()


def result_from_bytes(data: bytes, scenario) -> PlanResult:
    """Inverse of :func:`result_to_bytes` (the config is not stored: defaults are filled in)."""
    import io

    z = np.load(io.BytesIO(data), allow_pickle=False)
    reps = []
    for i in range(len(z["step"])):
        w = z["waypoints"][i]
        h = z["history"][i]
        reps.append(
            Replan(
                step=int(z["step"][i]),
                position=z["position"][i],
                waypoints=w[~np.isnan(w[:, 0])],
                cost=float(z["cost"][i]),
                length=float(z["length"][i]),
                collisions=int(z["collisions"][i]),
                latency=float(z["latency"][i]),
                nfev=int(z["nfev"][i]),
                history=h[~np.isnan(h)],
            )
        )
    algorithm, seed, reason = (str(x) for x in z["meta"])
    extra = {}
    if "events" in z.files:  # payloads written since the guard (issue 10)
        w, e, f, nm, *held = (int(x) for x in z["events"])  # holds: written since 0.3
        extra = dict(
            holds=held[0] if held else 0,
            collision_free=bool(z["collision_free"]),
            min_clearance=float(z["min_clearance"]),
            waits=w,
            evasions=e,
            fallbacks=f,
            near_misses=nm,
        )
    return PlanResult(
        scenario=_resolve(scenario),
        algorithm=algorithm,
        seed=int(seed) if seed.lstrip("-").isdigit() else 0,
        config=PlannerConfig(),
        trajectory=z["trajectory"],
        success=bool(z["success"]),
        reason=reason,
        replans=reps,
        route=z["route"],
        route_times=z["route_times"],
        **extra,
    )
