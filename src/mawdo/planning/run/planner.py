"""Single-shot and receding-horizon (dynamic) path planning with any registered optimizer.

Receding horizon (docs/deviations.md#d-replan-budget): every ``replan_every`` steps the robot
observes the obstacles, the
optimizer is seeded with the guide's routes (exact visibility graph, distinct homotopy classes,
re-rooted at the robot), the previous best path (reached waypoints dropped, the rest re-spread)
and perturbed copies, and runs for an iteration or wall-time budget on the cost of
:class:`~mawdo.planning.refine.cost.PathCost` (``spacetime`` mode by default); its best is polished
by a greedy local descent (:mod:`mawdo.planning.refine.polish`). The guard verifies the
stretch to be driven before the next replan and falls back to the elite, to waiting or to an
evasive move; the independent checker judges the executed route (:mod:`mawdo.planning.run.execute`).
This module holds the public entry point :func:`plan`; settings live in
:mod:`mawdo.planning.run.config`, result types and their serialisation in
:mod:`mawdo.planning.run.result`, the oracle follower in :mod:`mawdo.planning.run.follower` (all
re-exported here), and every planner by name in :data:`mawdo.planning.run.planners.PLANNERS`."""

from __future__ import annotations

from mawdo.planning.guide.passage import fit_config
from mawdo.planning.run.config import (  # noqa: F401  (public names re-exported)
    PLANNING_OPTIONS,
    PRESETS,
    PlannerConfig,
    resolve_config,
    resolve_scenario,
    step_limit,
)
from mawdo.planning.run.execute import Run
from mawdo.planning.run.follower import ORACLE_FOLLOWER, follow_oracle  # noqa: F401
from mawdo.planning.run.result import (  # noqa: F401  (public names re-exported)
    PlanResult,
    Replan,
    result_from_bytes,
    result_to_bytes,
)
from mawdo.planning.safety.kinematics import limits_refusal
from mawdo.planning.world.path import polyline_length


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
        Settings or a preset name (``"realtime"`` default, ``"large"``, ``"paper"``, ``"quick"``).
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
    (:mod:`mawdo.planning.safety.guard`) before every move.
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
        An unknown algorithm, preset or setting, a setting out of its range, a bad seed, a
        map the guide cannot handle (too many obstacle corners), or kinematic limits that cannot
        reach the goal within the step limit (:func:`~mawdo.planning.safety.kinematics
        .limits_refusal`).
    """
    from mawdo.optimizers import OPTIMIZERS
    from mawdo.util.validate import check_seed

    sc = resolve_scenario(scenario)
    OPTIMIZERS[algorithm]  # an unknown name fails here, listing the known ones
    check_seed(seed)
    cfg = fit_config(sc, resolve_config(config, overrides))
    run = Run(sc, algorithm, seed, cfg, dynamic)
    if run.limits is not None:  # limits that cannot reach the goal are refused, not run
        refusal = limits_refusal(run.limits, sc.straight_line_length(), run.step_limit()[0])
        if refusal is not None:
            raise ValueError(refusal)
    return run


def executed_length(result: PlanResult) -> float:
    """Length of the executed route (pixels)."""
    return polyline_length(result.route)
