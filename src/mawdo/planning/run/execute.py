"""One planning run: guide -> seeds -> refine -> polish -> guard -> move, then the checker's
judgement.

:func:`mawdo.planning.run.planner.plan` builds a :class:`Run` and calls :meth:`Run.execute`. The
steps of each (re)plan are those of the planner module's docstring; this module holds the search
and the safety contract (a move is driven only after the guard verified it; the route is judged
by the independent checker at the end). The run's decision of each step and the world's step are
in :mod:`~mawdo.planning.run.decide`, the loop that drives them in
:mod:`~mawdo.planning.run.loop`.
"""

from __future__ import annotations

import time
import weakref

import numpy as np

from mawdo.planning.guide.homotopy import Guide
from mawdo.planning.guide.timeguide import TimedRun, TimeGuide
from mawdo.planning.refine.cost import PathCost, assemble_paths
from mawdo.planning.refine.polish import polish
from mawdo.planning.refine.seeding import RunGuide, via_paths, warm_seeds
from mawdo.planning.refine.terms import cost_class
from mawdo.planning.run.config import PLANNING_OPTIONS, PlannerConfig, step_limit, step_limit_note
from mawdo.planning.run.decide import NO_ROUTE, DecidingRun
from mawdo.planning.run.gate import gated_plan
from mawdo.planning.run.loop import run_loop
from mawdo.planning.run.result import Drive, PlanResult, Replan
from mawdo.planning.safety.guard import Elite, Guard
from mawdo.planning.safety.ics import SafeContinuation
from mawdo.planning.safety.ics_run import SafeRun
from mawdo.planning.safety.kinematics import LimitedRun, Limits, at_speed
from mawdo.planning.world.path import densify
from mawdo.planning.world.scenario import Scenario
from mawdo.streams import replan_seed_sequences

# a replan whose best cost is below its warm start's by less than this (relative) found nothing
STALL_TOL = 1e-9

# one guide per (scenario, clearance, k): the graph and the goal's tree are built once
_GUIDES: weakref.WeakKeyDictionary = weakref.WeakKeyDictionary()


def guide_for(scenario: Scenario, clearance: float, k: int) -> Guide:
    """The cached :class:`Guide` of a scenario (built on first use)."""
    per = _GUIDES.setdefault(scenario, {})
    key = (float(clearance), int(k))
    if key not in per:
        per[key] = RunGuide(scenario, clearance=clearance, k=k)
    return per[key]


def share_guide(source: Scenario, target: Scenario) -> None:
    """Let ``target`` use the guides built for ``source``: for scenarios with the same static
    obstacles and goal (a prediction of the same map), whose visibility graph is the same."""
    if source in _GUIDES:
        _GUIDES[target] = _GUIDES[source]


def _path_cost(sc: Scenario, cfg: PlannerConfig, m: int, dynamic: bool) -> PathCost:
    """The refinement's cost: the paper's, plus the comfort term where ``cfg.comfort`` asks
    for it and the collision-risk term where ``cfg.risk`` does and the scenario's movers are
    predictions with an uncertainty, each only where the run sees time (both are judged
    along the robot's motion); movers tested over ``cfg.lookahead`` where it is set."""
    mode = cfg.mode if dynamic else "snapshot"
    args = (sc, mode, cfg.weights, m, cfg.clearance, cfg.threads)
    ahead = cfg.lookahead if mode == "spacetime" else None
    if mode != "spacetime":
        return PathCost(*args, horizon=ahead)
    terms = {}
    if cfg.comfort > 0:
        terms.update(comfort=cfg.comfort, comfort_weight=cfg.comfort_weight)
    if cfg.risk > 0 and sc.uncertainty is not None:
        terms.update(risk_weight=cfg.risk, risk_reach=cfg.risk_reach)
    return cost_class(**terms)(*args, horizon=ahead, **terms)


def _waypoints_needed(routes, cfg: PlannerConfig) -> int:
    if not (cfg.auto_waypoints and routes):
        return cfg.n_waypoints
    inner = max(len(r) - 2 for r in routes)
    return max(cfg.n_waypoints, min(cfg.max_waypoints, int(np.ceil(1.5 * inner))))


def _optimizers(algorithm: str, cfg: PlannerConfig) -> dict:
    """The run's optimizers, built once: one per population size (first plan, replans), with
    the planner's options for the algorithm (:data:`~mawdo.planning.run.config.PLANNING_OPTIONS`)
    under the config's own."""
    from mawdo.optimizers import make_optimizer

    opts = {**PLANNING_OPTIONS.get(algorithm, {}), **cfg.options}
    sizes = {cfg.first_pop_size or cfg.pop_size, cfg.pop_size}
    return {p: make_optimizer(algorithm, pop_size=p, **opts) for p in sizes}


def _stagnated(patience: int):
    """A :func:`~mawdo.minimize.minimize` callback: stop once the best cost has not fallen
    for ``patience`` iterations (the planner runs one run per optimisation)."""

    def stop(res) -> bool:
        h = res.history[0]
        return len(h) > patience and not h[-1] < h[-1 - patience]

    return stop


class _Watched:
    """The cost from ``start`` at ``t0`` as the optimizer sees it (``pure``: it only reads the
    candidates, :func:`mawdo.minimize.make_problem`); the elite sees every batch it evaluates.

    A candidate outside the cost's box is costed, and kept by the elite, as its projection
    onto the box (:func:`in_box`): not every optimizer keeps its trials inside (EA4eig's jSO
    step, as its authors coded it, leaves its eigen-crossover trials unrepaired), and the
    cost refuses coordinates far outside the map."""

    pure = True

    def __init__(self, cost: PathCost, elite: Elite, extra, start, t0: float) -> None:
        self.cost, self.elite, self.extra, self.start, self.t0 = cost, elite, extra, start, t0
        self.lb, self.ub = cost.bounds  # once: the property hands out copies

    def __call__(self, X):
        X = in_box(X, self.lb, self.ub)
        f = self.cost(X, start=self.start, t0=self.t0)
        f = f if self.extra is None else f + self.extra(X, self.start)  # kinematic limits
        return self.elite.add(X, f)


def in_box(X: np.ndarray, lb: np.ndarray, ub: np.ndarray) -> np.ndarray:
    """``X`` (candidates, pixels) with every coordinate clipped to ``[lb, ub]``: ``X`` itself
    when all are inside (the common case, no copy), else a clipped copy (a NaN stays NaN,
    which the cost prices as NaN)."""
    return X if np.all(X >= lb) and np.all(X <= ub) else np.clip(X, lb, ub)


class Run(DecidingRun, TimedRun, SafeRun, LimitedRun):
    """State of one run (see :func:`mawdo.planning.run.planner.plan` for the parameters)."""

    def __init__(self, sc: Scenario, algorithm: str, seed, cfg: PlannerConfig, dynamic: bool):
        # a lower speed limit times every path of the run (kinematics.at_speed)
        self.given, sc = sc, (at_speed(sc, cfg.max_speed) if dynamic else sc)
        self.sc, self.algorithm, self.seed, self.cfg = sc, algorithm, seed, cfg
        self.dynamic = dynamic
        self.guide = guide_for(sc, cfg.clearance, cfg.guide_routes) if cfg.guide_routes else None
        self.routes = self.guide.routes(sc.start) if self.guide else []
        self.m = _waypoints_needed(self.routes, cfg)
        self.cost = _path_cost(sc, cfg, self.m, dynamic)
        self.guard = Guard(sc, cfg.clearance)
        self.optimizers = self._make_optimizers()
        self.replans: list[Replan] = []
        self.counts = {"waits": 0, "evasions": 0, "fallbacks": 0, "holds": 0, "gated": 0,
                       "inevitable": 0}  # fmt: skip
        on = dynamic and cfg.ics_horizon > 0  # no inevitable collisions
        self.ics = SafeContinuation(sc, cfg.clearance, cfg.ics_horizon) if on else None
        self.limits = limits = Limits.of(cfg, self.given.robot_speed) if dynamic else None
        if self.ics is not None and limits is not None:  # stops and turns take time
            self.ics.limits = limits if (limits.accel, limits.turn) != (None, None) else None
        self.stalled = False  # the last search found nothing cheaper than its warm start
        self.chosen_index = 0  # which candidate the guard accepted at the last replan
        self._reach = None  # the oracle's answer, when the guide found no route
        self._per_pop = None  # seconds of one population's cost (estimate_seconds)
        # the safe-interval guide (time_guide): the timed route being followed, and the last
        # query's (step, routes), asked at most once per replan. Without moving obstacles the
        # earliest arrival is the static guide's shortest route at full speed, already a seed
        timed = cfg.time_guide and dynamic and bool(sc.moving_indices)
        args = (sc, cfg.clearance, cfg.time_routes, self.routes, limits)  # limits: as driven
        self.timer = TimeGuide(*args, cfg.lookahead) if timed else None
        self.refiner = self._make_refiner()
        self.following = None
        self.timed_follows = 0  # replans at which the guard chose a timed route
        self._timed = (-1, [])
        # a plan to start from instead of a first plan (a route from sc.start to the goal): a
        # policy that runs one step per Run hands each step the last one's remainder
        self.warm_start = None
        self.remainder = None
        self.judge = True  # the checker judges the run at its end (a stepped policy: no)

    def _make_optimizers(self) -> dict:
        return _optimizers(self.algorithm, self.cfg)

    def _make_refiner(self):
        """The swarm's refiner of limited timed routes (``cfg.refine_trajectory``), or None: off,
        or no route timed within acceleration or turn-rate limits to refine."""
        if not (self.cfg.refine_trajectory and self.timer is not None and self._profiled()):
            return None
        from mawdo.optimizers import make_optimizer
        from mawdo.planning.refine.trajectory_search import POP, TrajectoryRefiner

        opts = {**PLANNING_OPTIONS.get(self.algorithm, {}), **self.cfg.options}
        opt = make_optimizer(self.algorithm, pop_size=POP, **opts)
        return TrajectoryRefiner(self.sc, self.cfg.clearance, self.limits, opt, self.guard,
                                 self.ics)  # fmt: skip

    # -- seeds ---------------------------------------------------------------------------------

    def _guide_seeds(self, pos, rng, lb, ub) -> np.ndarray:
        if self.guide is None:
            return np.empty((0, 2 * self.m))
        rows = []
        for base in self.guide.seed_rows(pos, self.m):
            noise = rng.normal(0.0, self.cfg.warm_sigma, (self.cfg.guide_copies, base.size))
            rows.append(np.vstack([base, base + noise]))
        return np.clip(np.vstack(rows), lb, ub) if rows else np.empty((0, 2 * self.m))

    def _x0(self, pos, remainder, rng, pop, step: int = 0) -> np.ndarray:
        cfg, lb, ub = self.cfg, *self.cost.bounds
        guide = self._guide_seeds(pos, rng, lb, ub)
        if self.timer is not None:
            timed = np.clip(self._timed_seeds(pos, step, remainder is None), lb, ub)
            guide = np.vstack([timed, guide])
        if remainder is None:
            n_via = max(0, int(cfg.seed_fraction * pop) - 1 - len(guide))
            line = densify(np.array([pos, self.sc.goal]), self.m).reshape(1, -1)
            via = via_paths(pos, self.sc.goal, self.m, n_via, rng, lb, ub, *self.sc.bounds[2:])
            x0 = np.vstack([guide, line, via])
        else:
            x0 = np.vstack([warm_seeds(remainder, self.m, cfg, rng, lb, ub), guide])
        # the straight line to a goal on the map's edge may pass it by an ulp; minimize
        # refuses warm starts outside the box
        return np.clip(x0[:pop], lb, ub)

    # -- one optimisation ----------------------------------------------------------------------

    def optimise(self, pos, step: int, remainder) -> tuple[np.ndarray, Elite]:
        """Run the optimizer from ``pos`` at time ``step``; the best candidates, best first."""
        from mawdo.minimize import minimize

        cfg, k = self.cfg, len(self.replans)
        t_start = time.perf_counter()
        if cfg.guide_gate:  # the guides' answer, when they certify it (module gate)
            gated = gated_plan(self, pos, step, remainder, self._turn_cost())
            if gated is not None:
                return gated, self.replans[-1].latency
        ss, own = replan_seed_sequences(self.seed, k)
        rng = np.random.default_rng(own)
        first = remainder is None
        pop = (cfg.first_pop_size or cfg.pop_size) if first else cfg.pop_size
        x0 = self._x0(pos, remainder, rng, pop, step)
        elite = Elite(cfg.elite_size)
        t = float(step)
        watched = _Watched(self.cost, elite, self._turn_cost(), pos, t)
        res = minimize(
            watched,
            lb=self.cost.bounds[0],
            ub=self.cost.bounds[1],
            algorithm=self.optimizers[pop],
            seed=ss,
            max_iter=cfg.first_iters if first else cfg.replan_iters,
            max_time=None if first else cfg.replan_time,
            callback=_stagnated(cfg.first_patience) if first and cfg.first_patience else None,
            x0=x0,
        )
        # only where it can matter: the extra cost call then changes nothing in other presets
        self.stalled = not first and cfg.hold_gap > 0 and self._stalled(res.fun[0], x0[:1], pos, t)
        best, fun, nfev = self._polish(res, watched, pos, t)
        other = elite.X[np.abs(elite.X - best).max(axis=1) > 1e-12] if len(elite.X) else []
        cands = [best, *other]  # (a NaN difference is not distinct)
        latency = time.perf_counter() - t_start
        length, ncol, _ = self.cost.parts(best[None, :], start=pos, t0=t)
        self.replans.append(
            Replan(
                step=step,
                position=np.array(pos, dtype=float),
                waypoints=best.reshape(-1, 2).copy(),
                cost=fun,
                length=float(length[0]),
                collisions=int(ncol[0]),
                latency=latency,
                nfev=nfev,
                history=res.history[0].copy(),
            )
        )
        return np.array(cands), latency

    def _polish(self, res, watched: _Watched, pos, t: float):
        """The search's best after :func:`~mawdo.planning.refine.polish.polish` (its cost and the
        evaluations of both); the elite sees every variant. The stall flag stays the search's:
        a polished plan was still one the search could not improve."""
        # the point the objective costed (and the elite kept): an optimizer's best may lie
        # outside the box (_Watched)
        lb, ub = watched.lb, watched.ub
        x, fx, nfev = in_box(res.x[0], lb, ub), float(res.fun[0]), int(res.nfev[0])
        if self.cfg.polish_rounds == 0:
            return x, fx, nfev
        cfg = self.cfg
        rounds, steps = cfg.polish_rounds, cfg.polish_steps
        x, fx, extra = polish(watched, x, fx, pos, self.sc.goal, rounds, steps, lb, ub)
        return x, fx, nfev + extra

    def _stalled(self, best: float, warm, pos, t: float) -> bool:
        """True when the search found nothing better than its warm start (the previous
        plan's remainder): rounding may make a collinear variant an ulp cheaper, which is not
        a better route, hence the relative tolerance."""
        cost = float(self.cost(warm, start=pos, t0=t)[0])
        return bool(best >= cost - STALL_TOL * abs(cost))

    # -- the guard -----------------------------------------------------------------------------

    def choose(self, cands, pos, step: int, horizon: float):
        """First candidate whose next ``horizon`` px are safe and keep a safe continuation
        (route), or ``None``; the least bad when no option keeps one (:class:`SafeRun`)."""
        least = None
        for i, x in enumerate(cands):
            route = assemble_paths(x[None, :], pos, self.sc.goal)[0]
            if self.dynamic:
                safe = self.guard.stretch_hits(route, float(step), horizon) == 0
            else:  # single-shot: the whole plan on the frozen map at t = 0
                safe = int(self.cost.parts(x[None, :], start=pos, t0=0.0)[1][0]) == 0
            if safe and least is None:  # the least bad, should no option keep a continuation
                least = (i, route)
            if safe and self._continues(route, step, horizon):
                self.counts["fallbacks"] += i > 0
                self.chosen_index = i
                return route
        return self._least_bad(least, pos, step, self._target(pos, cands))

    def execute(self, progress=None) -> PlanResult:
        """Drive the run; ``progress(step, max_steps, replans)`` is called before each step.

        The run loop is :func:`~mawdo.planning.run.loop.run_loop` over the run's decision
        (:meth:`~mawdo.planning.run.decide.DecidingRun.decide`) and the world's step
        (:meth:`~mawdo.planning.run.decide.DecidingRun.step`); ``drive`` holds the moves so
        far, and after the run ``remainder`` the plan's rest (a stepped policy's next warm
        start)."""
        reach, start = self._reachable(), self.sc.start
        if isinstance(reach, str):
            return self._finish(Drive(start.copy()), f"{NO_ROUTE}: static obstacles: {reach}")
        max_steps, rule = self.step_limit()
        self.begin()
        limit = step_limit_note(self.cfg.max_steps, max_steps, rule)
        replans = self.replans
        reason = run_loop(max_steps, self.at_goal, self.decide, self.step, limit, progress,
                          lambda: len(replans))  # fmt: skip
        self.remainder = self.state.remainder
        return self._finish(self.drive, reason)

    def step_limit(self) -> tuple[int, int]:
        """The run's step limit and the uncapped automatic one
        (:func:`~mawdo.planning.run.config.step_limit`)."""
        reach = self._reachable()
        reach = 0.0 if isinstance(reach, str) else reach
        sc = self.sc
        return step_limit(self.cfg.max_steps, sc.straight_line_length(), reach, sc.robot_speed)

    def estimate_seconds(self, steps: int) -> float:
        """An upper estimate of the run's wall time (s) if it uses ``steps`` steps: the time of
        one population's cost (measured now: the median of 3 calls after a warm-up call of the
        same size) times the iterations of the first plan and of a replan at every
        ``replan_every`` steps (held replans cost less)."""
        cfg = self.cfg
        if self._per_pop is None:  # measured once: estimates of one run stay comparable
            X = np.random.default_rng(0).uniform(*self.cost.bounds, (cfg.pop_size, self.cost.dim))
            self.cost(X, start=self.sc.start)  # compiles; with threads, starts the pool (100x)
            times = []
            for _ in range(3):
                t0 = time.perf_counter()
                self.cost(X, start=self.sc.start)
                times.append(time.perf_counter() - t0)
            self._per_pop = float(np.median(times))
        per_pop = self._per_pop
        first = cfg.first_iters * (cfg.first_pop_size or cfg.pop_size) / cfg.pop_size
        return per_pop * (first + cfg.replan_iters * steps / cfg.replan_every)

    def _reachable(self):
        """Length (px) of a route around the static obstacles, or why there is none.

        The guide's shortest route answers when there is one; only when it finds none (the
        margin may close a narrow passage) does the exact oracle at the true radius decide.
        """
        if self.routes:
            return float(np.hypot(*np.diff(self.routes[0], axis=0).T).sum())
        if self._reach is None:
            from mawdo.planning.guide.oracle import scenario_optimum

            opt = scenario_optimum(self.sc, static_only=True)
            self._reach = opt.length if opt.reachable else opt.reason
        return self._reach

    def _finish(self, drive, reason: str) -> PlanResult:
        if not self.judge:  # a stepped policy's one step: the episode is judged as a whole
            return drive.unjudged(reason, self.given, self.algorithm, self.seed, self.cfg,
                                  self.replans, **self.counts)  # fmt: skip
        return drive.result(
            reason,
            self.given,
            margin=self.cfg.clearance,
            limits=self.limits,
            algorithm=self.algorithm,
            seed=self.seed,
            config=self.cfg,
            replans=self.replans,
            **self.counts,
        )
