"""Planner settings: :class:`PlannerConfig`, the named presets, :func:`with_settings` and the
one step-limit rule every planner obeys (:func:`step_limit`).

The result types live in :mod:`mawdo.planning.run.result`; the planners in
:mod:`mawdo.planning.run.planners`."""

from dataclasses import dataclass, field, replace

import numpy as np

from mawdo.planning.refine.cost import CostWeights
from mawdo.planning.world.scenario import MAX_RUN_STEPS, Scenario, get_scenario
from mawdo.util.validate import check_int


@dataclass(frozen=True)
class PlannerConfig:
    """Planner settings.

    Parameters
    ----------
    pop_size : int
        Candidates per optimizer iteration of a replan (the paper: 8 groups x 170 = 1360).
    first_pop_size : int or None
        Candidates per iteration of the first plan (default ``pop_size``).
    first_iters : int
        Iterations of the first plan, made before the robot moves (not part of replan latency).
    first_patience : int or None
        Stop the first plan's optimisation once its best cost has not fallen for this many
        iterations (>= 1; a stagnation stop, as ``tolfun`` in CMA-ES). The optimizer's
        schedules stay planned over ``first_iters``. None (default): all ``first_iters``.
    replan_iters : int
        Iterations per replan.
    replan_time : float or None
        Wall-clock budget per replan (seconds); when set, a replan stops at whichever of
        ``replan_iters`` and ``replan_time`` comes first.
    replan_every : int
        Steps between replans, >= 1.
    mode : {"spacetime", "snapshot"}
        Cost mode (see :class:`~mawdo.planning.refine.cost.PathCost`).
    weights : CostWeights
        Eqs. 24-27 weights.
    n_waypoints : int
        Waypoints per candidate (20 -> 40-D).
    max_steps : int or None
        Step limit, in [1, 1 000 000] (:data:`~mawdo.planning.world.scenario.MAX_RUN_STEPS`).
        Default (None): ``max(4 x straight line, 2 x static optimum) / v + 10``, at most
        :data:`AUTO_STEP_CAP` (20 000) so that a slow robot on a large map cannot set a run of
        days; give ``max_steps`` (CLI ``--max-steps``) to allow more (:func:`step_limit`).
    seed_fraction : float
        Share of the first plan's population seeded with path-like candidates (the straight line
        and routes through random via points), in [0, 1]; the rest is uniform in the map.
    warm_copies : int
        Perturbed copies of the re-spread previous best in each warm start (plus the path itself).
    warm_sigma : float
        Standard deviation of those perturbations (pixels).
    options : dict
        Extra options for the optimizer (e.g. ``{"groups": 8}``).
    clearance : float
        Safety margin (px, >= 0) added to the robot radius in the cost, the guide and the guard;
        the checker reports steps closer than this as near misses. A run uses at most half the
        scene's narrowest-passage slack (:func:`mawdo.planning.guide.passage.fitted_clearance`).
    comfort : float
        Room (px, >= 0) beyond the robot radius and ``clearance`` that the refinement tries to
        leave moving agents: each (segment, mover) pair of a candidate that comes closer costs
        ``comfort_weight`` px of route length (:mod:`mawdo.planning.refine.comfort`). 0 (every
        preset): the paper's cost.
    comfort_weight : float
        What one such near pair costs, in pixels of route length (>= 0).
    risk : float
        What one expected contact with a predicted agent costs the refinement, in pixels of
        route length (>= 0): the collision-risk term under the predictor's uncertainty
        (:mod:`mawdo.planning.refine.risk`), for an observing planner. 0 (every preset): off.
    risk_reach : int
        Time steps ahead (>= 1) over which the risk is summed.
    elite_size : int
        Distinct candidates kept from each optimisation for the guard to fall back on, >= 1.
    give_up_steps : int
        Consecutive steps of waiting or evading after which the run stops with an honest
        failure (time steps), >= 1.
    guide_routes : int
        Routes in distinct homotopy classes from the exact visibility graph used as seeds
        (0: no guidance).
    guide_copies : int
        Perturbed copies (N(0, ``warm_sigma``)) of each guide route among the seeds.
    auto_waypoints : bool
        Raise ``n_waypoints`` when the first guide routes need more (1.5 waypoints per route
        vertex, at most ``max_waypoints``); never lowers it.
    max_waypoints : int
        Upper limit of that raise.
    hold_straight : bool
        Receding horizon, space-time mode: skip the optimisation while the plan runs straight
        to the goal and the guard verifies it collision-free to its end, since no candidate
        can cost less (C1 at its lower bound, the straight-line distance; C2 = C3 = 0). Those
        skipped replans count as ``holds`` in the result and have no latency. The verdict
        rests on the scenario's obstacle motion being the prediction at every step, as it is
        for the cost and the guard. Off in the ``paper`` and ``study`` presets, which replan
        every step as the paper does.
    hold_gap : float
        Receding horizon, space-time mode: after a replan whose search returned its warm start
        unchanged (the previous plan's remainder, bit for bit: nothing better was found), skip
        the following replans while the plan is at most ``hold_gap`` (relative, >= 0; 0 turns
        it off) longer than the guide's shortest static route from the robot and the guard
        verifies it collision-free to its end. With the predictions fixed, every route open
        at a later step was open to that search (follow the plan, then deviate), so a held
        replan gives up search, not information, on a plan already within ``hold_gap`` of the
        guide's shortest route (its rounded corners are drawn as octagons, so that length is
        a close upper estimate of the true optimum). Skipped replans count as ``holds``. Off
        in the ``paper`` and ``study`` presets.
    guide_gate : bool
        Receding horizon, space-time mode: before each (re)plan's search, rank the guides' own
        answers (``guide_only``'s candidates) by the cost; when the best is at most
        ``hold_gap`` (relative) longer than the static shortest route from the robot and the
        guard finds it collision-free to the goal at full speed, take it without consulting the
        optimizer: no search could make the route shorter or arrive earlier by more than
        ``hold_gap`` (:mod:`mawdo.planning.run.gate`; counted in ``PlanResult.gated``). The
        swarm then searches only where movers make the guides' answer a detour or a
        collision. Not applied under acceleration or turn-rate limits, where the shortest
        route need not arrive first. Off (default): every (re)plan searches.
    polish_rounds : int
        Rounds of greedy local descent on each (re)plan's best candidate, >= 0 (0: off):
        single waypoints moved toward their neighbours' midpoint, kept only when the plan's own
        cost falls (:mod:`mawdo.planning.refine.polish`). Each round costs
        ``len(polish_steps) x n_waypoints`` evaluations, counted in the replan's ``nfev`` and
        latency. Off in the ``paper`` and ``study`` presets.
    polish_steps : tuple of float
        Step lengths of a polish move, as fractions of the way to the midpoint, each in (0, 1].
    threads : int
        Threads the cost of a population may use, >= 1
        (:class:`~mawdo.planning.refine.cost.PathCost`); the result is the same whatever the count,
        except that a ``replan_time`` budget fits more iterations. Calls under 1 ms of CPU stay
        on one thread. Leave it at 1 where several planners share the cores (a study with
        several workers).
    time_guide : bool
        Receding horizon: consult the safe-interval guide (:mod:`mawdo.planning.guide.timeguide`).
        Its timed routes from the robot's position and time join the seeds at the first plan
        and while the robot follows one; at each replan whose chosen candidate is not
        collision-free to the goal (driven at full speed from now), the robot follows the
        earliest-arrival timed route instead, waits included (it holds its position for the
        steps the route waits). On by default; off in the ``paper`` and ``study`` presets,
        which measure the optimizers as the paper runs them. Consulted only in scenarios with
        moving obstacles: without them the earliest arrival is the static guide's shortest
        route driven at full speed, which is already a seed.
    time_routes : int
        Timed routes per query of that guide (>= 1): the earliest arrival and up to
        ``time_routes - 1`` time-diverse alternatives, all seeds.
    lookahead : float or None
        Time steps (> ``ics_horizon`` and >= ``replan_every``) over which the planner trusts
        the movers' predicted motion at each replan. The safe-interval guide tests them only
        that far (beyond, its routes are timed on the static map, and a followed route is asked
        again before the robot comes within ``ics_horizon`` steps of that end), and so does
        the refinement's cost (a segment the robot begins later is tested against the static
        map only). None (default): the whole prediction. Large worlds plan far faster with it
        (the search's and the cost's work grow with the time they look ahead, not with the
        route), at the price of routes that may meet a conflict not yet looked at; every step
        is still checked by the guard and the rule with the whole prediction.
    ics_horizon : int
        Receding horizon: prediction horizon (time steps, >= 0; 0 turns the rule off) of the
        rule that never drives into an inevitable collision (:mod:`mawdo.planning.safety.ics`): a
        stretch, a wait or an evasive move is taken only when the robot keeps a safe
        continuation after it until that many steps from now (drive on to the goal, wait, or
        reach a spot where waiting is safe), obstacles moving as predicted and random walkers
        grown by their reachable set. When no option keeps one the run drives the least bad
        and counts it (``PlanResult.inevitable``); a run that gives up first moves to where
        waiting is safe.
    refine_trajectory : bool
        With an acceleration or turn-rate limit (looked at only then), the run drives a timed
        route it follows as the swarm's refinement of its trajectory finds faster: corners
        rounded, speed carried through them (:mod:`mawdo.planning.refine.trajectory_search`),
        when that drive is verified safe and strictly earlier; else the guide's own stops and
        turns in place. On by default; off in the ``paper`` and ``study`` presets (which set no
        limits).
    max_speed, max_accel, max_turn : float or None
        Opt-in kinematic limits of the executed motion (None: free, the default and the
        paper's set-up; :mod:`mawdo.planning.safety.kinematics`): most distance per step (px per
        step, > 0), most change of velocity per step (px per step squared, > 0; the robot
        starts at rest) and most change of heading per step between two moves (radians per
        step, in (0, pi]). Every executed step is projected onto them and checked by the
        guard as driven; a turn-rate limit adds a penalty on each corner's excess turn to the
        refinement's cost; the checker reports violations and success needs none.
    """

    pop_size: int = 240
    first_pop_size: int | None = None
    first_iters: int = 300
    first_patience: int | None = None
    replan_iters: int = 15
    replan_time: float | None = None
    replan_every: int = 1
    mode: str = "spacetime"
    weights: CostWeights = field(default_factory=CostWeights)
    n_waypoints: int = 20
    max_steps: int | None = None
    seed_fraction: float = 0.5
    warm_copies: int = 23
    warm_sigma: float = 6.0
    options: dict = field(default_factory=dict)
    clearance: float = 0.5
    comfort: float = 0.0
    comfort_weight: float = 8.0
    risk: float = 0.0
    risk_reach: int = 40
    elite_size: int = 8
    give_up_steps: int = 60
    guide_routes: int = 6
    guide_copies: int = 3
    auto_waypoints: bool = True
    max_waypoints: int = 48
    hold_straight: bool = True
    hold_gap: float = 0.002
    guide_gate: bool = False
    polish_rounds: int = 5
    polish_steps: tuple = (0.5, 1.0)
    threads: int = 1
    time_guide: bool = True
    time_routes: int = 2
    lookahead: float | None = None
    ics_horizon: int = 30
    refine_trajectory: bool = True
    max_speed: float | None = None
    max_accel: float | None = None
    max_turn: float | None = None

    def __post_init__(self) -> None:
        # every optimizer needs two candidates; checked first, so pop_size=1 is named for itself
        check_int("PlannerConfig.pop_size", self.pop_size, 2)
        for name in ("first_iters", "replan_iters", "replan_every", "n_waypoints"):
            v = getattr(self, name)
            if not isinstance(v, int | np.integer) or v < 1:
                raise ValueError(f"PlannerConfig.{name}={v!r} must be a positive integer")
        if self.first_patience is not None:
            check_int("PlannerConfig.first_patience", self.first_patience, 1)
        if self.first_pop_size is not None and self.first_pop_size < 2:
            raise ValueError(f"PlannerConfig.first_pop_size={self.first_pop_size!r} must be >= 2")
        if self.replan_time is not None and not self.replan_time > 0:
            raise ValueError(f"PlannerConfig.replan_time={self.replan_time!r} must be > 0 s")
        if not 0.0 <= self.seed_fraction <= 1.0:
            raise ValueError(
                f"PlannerConfig.seed_fraction={self.seed_fraction!r} must be in [0, 1]"
            )
        if self.warm_copies + 1 > self.pop_size:
            raise ValueError(
                f"PlannerConfig.warm_copies={self.warm_copies!r} + 1 must not exceed "
                f"pop_size={self.pop_size!r}: lower warm_copies or raise pop_size"
            )
        if self.max_steps is not None:
            check_int("PlannerConfig.max_steps", self.max_steps, 1, MAX_RUN_STEPS)
        for name in ("clearance", "comfort", "comfort_weight", "risk"):
            v = getattr(self, name)
            if not (np.isfinite(v) and v >= 0):
                raise ValueError(f"PlannerConfig.{name}={v!r} must be finite and >= 0 px")
        for name in ("elite_size", "give_up_steps", "max_waypoints"):
            if getattr(self, name) < 1:
                raise ValueError(f"PlannerConfig.{name}={getattr(self, name)!r} must be >= 1")
        if not (np.isfinite(self.hold_gap) and self.hold_gap >= 0):
            raise ValueError(f"PlannerConfig.hold_gap={self.hold_gap!r} must be finite and >= 0")
        check_int("PlannerConfig.risk_reach", self.risk_reach, 1)
        check_int("PlannerConfig.polish_rounds", self.polish_rounds, 0)
        check_int("PlannerConfig.threads", self.threads, 1)
        check_int("PlannerConfig.time_routes", self.time_routes, 1)
        check_int("PlannerConfig.ics_horizon", self.ics_horizon, 0)
        _check_lookahead(self)
        _check_limits(self)
        for name in ("time_guide", "refine_trajectory", "guide_gate"):
            if not isinstance(getattr(self, name), bool | np.bool_):
                raise ValueError(
                    f"PlannerConfig.{name}={getattr(self, name)!r} must be True or False"
                )
        steps = np.asarray(self.polish_steps, float)
        if steps.ndim != 1 or steps.size == 0 or not np.all((steps > 0) & (steps <= 1)):
            raise ValueError(
                f"PlannerConfig.polish_steps={self.polish_steps!r} must be a non-empty sequence "
                "of fractions in (0, 1]"
            )
        object.__setattr__(self, "polish_steps", tuple(float(v) for v in steps))
        for name in ("guide_routes", "guide_copies"):
            if getattr(self, name) < 0:
                raise ValueError(f"PlannerConfig.{name}={getattr(self, name)!r} must be >= 0")


def _check_lookahead(cfg: PlannerConfig) -> None:
    """``lookahead``: None, or a number past the rule's horizon and a replan's period
    (a followed route must be checked for every step driven before the guide is asked again)."""
    v = cfg.lookahead
    if v is None:
        return
    least = max(cfg.ics_horizon, cfg.replan_every - 1)
    ok = isinstance(v, int | float | np.integer | np.floating) and not isinstance(v, bool)
    if not (ok and v > least):
        raise ValueError(
            f"PlannerConfig.lookahead={v!r} must be None or a number of time steps > "
            f"{least} (more than ics_horizon and at least replan_every); e.g. 180"
        )


def _check_limits(cfg: PlannerConfig) -> None:
    """The kinematic limits: None or a finite positive number (a turn rate at most pi)."""
    for name, unit, top in (
        ("max_speed", "px per step", np.inf),
        ("max_accel", "px per step squared", np.inf),
        ("max_turn", "radians per step", np.pi),
    ):
        v = getattr(cfg, name)
        if v is None:
            continue
        ok = isinstance(v, int | float | np.integer | np.floating) and not isinstance(v, bool)
        if not (ok and np.isfinite(v) and 0 < v <= top):
            bound = f"in (0, {top:.6g}]" if np.isfinite(top) else "> 0"
            raise ValueError(
                f"PlannerConfig.{name}={v!r} must be None (no limit) or a number {bound} ({unit})"
            )


# The paper's planner: it replans every step and executes the optimizer's best as it is (no
# kept plans, no polish, no safe-interval guide), so Table 6 measures the optimizers alone.
_AS_PUBLISHED = {
    "hold_straight": False, "hold_gap": 0.0, "polish_rounds": 0, "time_guide": False,
    "refine_trajectory": False,
}  # fmt: skip

# Named settings: the paper's study size, and a real-time setting that meets 20 Hz replanning.
# The real-time preset searches only where the guides cannot vouch for their own route (the guide
# gate): on static maps and free stretches the swarm's search was measured to change the route by
# under 3e-4 of its length while costing seconds (docs/deviations.md#d-guide-gate). Not in
# `large`: among hundreds of movers it took none of 1500 plans and its check cost a tenth of a
# replan (benchmarks/log/latency.md).
PRESETS = {
    "paper": PlannerConfig(pop_size=1360, first_iters=300, replan_iters=15, **_AS_PUBLISHED),
    "realtime": PlannerConfig(pop_size=240, first_iters=300, replan_iters=15, guide_gate=True),
    # the study: the paper's 1360 particles for the first plan, real-time replans
    "study": PlannerConfig(
        pop_size=240, first_pop_size=1360, first_iters=300, replan_iters=15, **_AS_PUBLISHED
    ),
    "quick": PlannerConfig(pop_size=80, first_iters=60, replan_iters=5),
    # real time on large worlds: the safe-interval guide and the cost trust the predictions
    # 180 steps ahead (its search then grows with that time, not with the route's; 120 and 60 steps
    # saw a warehouse's conflict too late: benchmarks/log/scaling.md); the first plan stops
    # once the swarm stagnates (on most large worlds it never improves on the guide's seeds)
    "large": PlannerConfig(
        pop_size=240, first_iters=300, first_patience=50, replan_iters=15, lookahead=180.0
    ),
    # single-shot queries in tens of milliseconds: the guide's routes do the topology, a short
    # refinement smooths them
    "fast": PlannerConfig(pop_size=40, first_iters=25, replan_iters=5, warm_copies=15),
}


# Per-algorithm options the planner uses unless the config overrides them. MAWDO runs with its
# stabilisation (centroid gravity, per-group coefficients, vmax/4) on at D = 40: with the paper's
# D <= 3 threshold, AWDO's gravity toward the box centre pulls every waypoint to the map centre
# and MAWDO never refines its initial population (docs/deviations.md, "MAWDO in path planning").
PLANNING_OPTIONS = {"mawdo": {"low_dim": 10_000}}


def resolve_scenario(scenario) -> Scenario:
    """A scenario, or the built-in one of that name."""
    return get_scenario(scenario) if isinstance(scenario, str) else scenario


def resolve_config(config, overrides=None) -> PlannerConfig:
    """A :class:`PlannerConfig`, a preset's name (default ``"realtime"``) or None, with
    ``overrides`` applied (:func:`with_settings`)."""
    if config is None:
        config = PRESETS["realtime"]
    elif isinstance(config, str):
        if config not in PRESETS:
            raise ValueError(f"unknown planner preset {config!r}; choose one of {list(PRESETS)}")
        config = PRESETS[config]
    return with_settings(config, overrides) if overrides else config


def with_settings(config: PlannerConfig, settings: dict) -> PlannerConfig:
    """``config`` with some fields changed; an unknown name is a ``ValueError`` naming it,
    the closest setting and every setting (not ``__init__``'s keyword-argument error)."""
    import difflib
    from dataclasses import fields

    names = [f.name for f in fields(PlannerConfig)]
    for key in settings:
        if key not in names:
            close = difflib.get_close_matches(str(key), names, n=1)
            hint = f" Did you mean {close[0]!r}?" if close else ""
            raise ValueError(f"unknown planner setting {key!r}.{hint} Settings: {', '.join(names)}")
    return replace(config, **settings)


def check_overrides(overrides: dict, preset: str) -> dict:
    """``overrides`` as a dict after checking them on the preset they change (a study plan's
    validator: ``ValueError`` naming the bad setting)."""
    try:
        with_settings(PRESETS[preset], overrides)
    except TypeError as exc:  # a value of the wrong type met a comparison
        raise ValueError(str(exc)) from None
    return dict(overrides)


#: Most steps the automatic step limit may set (see ``PlannerConfig.max_steps``).
AUTO_STEP_CAP = 20_000


def step_limit(max_steps: int | None, straight: float, reach: float, speed: float):
    """The step limit of a run and the automatic rule's value.

    Parameters
    ----------
    max_steps : int or None
        ``PlannerConfig.max_steps``: the limit when given.
    straight, reach : float
        Straight start-goal distance and the length of a route around the static obstacles
        (pixels); long detours (mazes) need more than 4 straight lines, hence 2 x ``reach``.
    speed : float
        Robot speed (pixels per step), > 0.

    Returns
    -------
    limit : int
        ``max_steps``, else ``ceil(max(4 straight, 2 reach) / speed) + 10`` capped at
        :data:`AUTO_STEP_CAP`.
    rule : int
        The uncapped automatic value (above ``limit`` when the cap applied).
    """
    rule = int(np.ceil(max(4.0 * straight, 2.0 * reach) / speed)) + 10
    if max_steps is not None:
        return int(max_steps), rule
    return min(rule, AUTO_STEP_CAP), rule


STEP_LIMIT_REACHED = "step limit reached before the goal"


def step_limit_note(max_steps: int | None, limit: int, rule: int) -> str:
    """The reason a run stopped by its step limit gives: :data:`STEP_LIMIT_REACHED`, plus how to
    allow more when the automatic ``rule`` was capped (``max_steps`` is None and ``rule >
    limit``)."""
    if rule > limit and max_steps is None:
        return STEP_LIMIT_REACHED + (
            f" (the automatic limit of {rule} steps was capped at {limit}: "
            "set max_steps, CLI --max-steps, to allow more)"
        )
    return STEP_LIMIT_REACHED
