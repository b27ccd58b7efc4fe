"""Single-shot and receding-horizon (dynamic) path planning with any registered optimizer.

Receding horizon (SPEC 4.3): every ``replan_every`` steps the robot observes the obstacles, the
optimizer is warm-started from the previous best path (reached waypoints dropped, the rest
re-spread along the remaining route, plus perturbed copies and fresh random candidates) and runs
for an iteration or wall-time budget on the cost of :class:`~mawdo.planning.cost.PathCost`
(``spacetime`` mode by default: each segment is tested against the obstacles' predicted motion
while the robot traverses it). The robot then moves ``v`` pixels along the best path.
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field, replace

import numpy as np

from mawdo.planning.cost import CostWeights, PathCost, assemble_paths
from mawdo.planning.path import advance, densify, polyline_length
from mawdo.planning.scenario import Scenario, get_scenario


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
    replan_iters : int
        Iterations per replan.
    replan_time : float or None
        Wall-clock budget per replan (seconds); when set, a replan stops at whichever of
        ``replan_iters`` and ``replan_time`` comes first.
    replan_every : int
        Steps between replans, >= 1.
    mode : {"spacetime", "snapshot"}
        Cost mode (see :class:`~mawdo.planning.cost.PathCost`).
    weights : CostWeights
        Eq. 17-20 weights.
    n_waypoints : int
        Waypoints per candidate (20 -> 40-D).
    max_steps : int or None
        Step limit; default ``4 x straight-line length / v``.
    seed_fraction : float
        Share of the first plan's population seeded with path-like candidates (the straight line
        and routes through random via points), in [0, 1]; the rest is uniform in the map.
    warm_copies : int
        Perturbed copies of the re-spread previous best in each warm start (plus the path itself).
    warm_sigma : float
        Standard deviation of those perturbations (pixels).
    options : dict
        Extra options for the optimizer (e.g. ``{"groups": 8}``).
    """

    pop_size: int = 240
    first_pop_size: int | None = None
    first_iters: int = 300
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

    def __post_init__(self) -> None:
        for name in ("pop_size", "first_iters", "replan_iters", "replan_every", "n_waypoints"):
            v = getattr(self, name)
            if not isinstance(v, int | np.integer) or v < 1:
                raise ValueError(f"PlannerConfig.{name}={v!r} must be a positive integer")
        if self.first_pop_size is not None and self.first_pop_size < 2:
            raise ValueError(f"PlannerConfig.first_pop_size={self.first_pop_size!r} must be >= 2")
        if self.replan_time is not None and not self.replan_time > 0:
            raise ValueError(f"PlannerConfig.replan_time={self.replan_time!r} must be > 0 s")
        if not 0.0 <= self.seed_fraction <= 1.0:
            raise ValueError(
                f"PlannerConfig.seed_fraction={self.seed_fraction!r} must be in [0, 1]"
            )
        if self.warm_copies + 1 > self.pop_size:
            raise ValueError("PlannerConfig.warm_copies + 1 must not exceed pop_size")
        if self.max_steps is not None and self.max_steps < 1:
            raise ValueError(f"PlannerConfig.max_steps={self.max_steps!r} must be >= 1")


# Named settings: the paper's study size, and a real-time setting that meets 20 Hz replanning.
PRESETS = {
    "paper": PlannerConfig(pop_size=1360, first_iters=300, replan_iters=15),
    "realtime": PlannerConfig(pop_size=240, first_iters=300, replan_iters=15),
    # the study: the paper's 1360 particles for the first plan, real-time replans
    "study": PlannerConfig(pop_size=240, first_pop_size=1360, first_iters=300, replan_iters=15),
    "quick": PlannerConfig(pop_size=80, first_iters=60, replan_iters=5),
}


@dataclass
class Replan:
    """One optimisation made during a run."""

    step: int
    position: np.ndarray  # (2,) robot position when planning (pixels)
    waypoints: np.ndarray  # (m, 2) best waypoints
    cost: float
    length: float  # plan length from position to goal (pixels)
    collisions: int  # n of Eq. 20 for the plan, as the cost kernel sees it
    latency: float  # wall seconds
    nfev: int
    history: np.ndarray  # best cost per iteration


@dataclass
class PlanResult:
    """Outcome of one planning run.

    Attributes
    ----------
    trajectory : numpy.ndarray, shape (k, 2)
        Executed robot positions at steps 0, 1, ..., k-1 (pixels).
    route, route_times : numpy.ndarray, shapes (j, 2) and (j,)
        The executed polyline with every waypoint the robot passed between two steps, and the
        time (time steps, fractional) at which it was at each point: the robot follows its plan
        exactly, so this, not the straight lines between step positions, is what it drove.
    success : bool
        The robot reached the goal within the step limit (collisions are judged separately by
        :func:`mawdo.planning.check.check_trajectory`, see :mod:`mawdo.planning.metrics`).
    reason : str
        ``"goal reached"`` or why not.
    replans : list of Replan
        Every optimisation, the first plan included.
    """

    scenario: Scenario
    algorithm: str
    seed: int
    config: PlannerConfig
    trajectory: np.ndarray
    success: bool
    reason: str
    replans: list[Replan]
    route: np.ndarray | None = None
    route_times: np.ndarray | None = None

    @property
    def steps(self) -> int:
        return len(self.trajectory) - 1

    @property
    def latencies(self) -> np.ndarray:
        """Wall seconds of each replan after the first plan."""
        return np.array([r.latency for r in self.replans[1:]])

    @property
    def nfev(self) -> int:
        return int(sum(r.nfev for r in self.replans))


# Per-algorithm options the planner uses unless the config overrides them. MAWDO runs with its
# stabilisation (centroid gravity, per-group coefficients, vmax/4) on at D = 40: with the paper's
# D <= 3 threshold, AWDO's gravity toward the box centre pulls every waypoint to the map centre
# and MAWDO never refines its initial population (docs/deviations.md, "MAWDO in path planning").
PLANNING_OPTIONS = {"mawdo": {"low_dim": 10_000}}


class _Drive:
    """The executed motion: positions at integer steps, and the route with every vertex passed
    between two steps, time-stamped (what the checker and the metrics judge)."""

    def __init__(self, start: np.ndarray) -> None:
        self.traj, self.route, self.stamps = [start.copy()], [start.copy()], [0.0]

    def move(self, step: int, pos: np.ndarray, passed=(), frac=()) -> None:
        self.route.extend(passed)
        self.stamps.extend(step + np.asarray(frac, dtype=float))
        self.route.append(pos.copy())
        self.stamps.append(step + 1.0)
        self.traj.append(pos.copy())

    def result(self, reason: str, **fields) -> PlanResult:
        return PlanResult(
            trajectory=np.array(self.traj),
            success=reason == "goal reached",
            reason=reason,
            route=np.array(self.route),
            route_times=np.array(self.stamps),
            **fields,
        )


def _resolve(scenario) -> Scenario:
    return get_scenario(scenario) if isinstance(scenario, str) else scenario


def _config(config, overrides) -> PlannerConfig:
    if config is None:
        config = PRESETS["realtime"]
    elif isinstance(config, str):
        if config not in PRESETS:
            raise ValueError(f"unknown planner preset {config!r}; choose one of {list(PRESETS)}")
        config = PRESETS[config]
    return replace(config, **overrides) if overrides else config


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
        Never raises for an unreachable goal: ``success=False`` with a reason.
    """
    sc = _resolve(scenario)
    cfg = _config(config, overrides)
    v = sc.robot_speed
    max_steps = cfg.max_steps or int(np.ceil(4 * sc.straight_line_length() / v)) + 10
    cost = PathCost(
        sc,
        mode=cfg.mode if dynamic else "snapshot",
        weights=cfg.weights,
        n_waypoints=cfg.n_waypoints,
    )
    lb, ub = cost.bounds
    master = seed if isinstance(seed, np.random.SeedSequence) else np.random.SeedSequence(seed)
    goal = sc.goal
    pos = sc.start.copy()
    drive = _Drive(pos)
    replans: list[Replan] = []
    remainder = None
    reason = "step limit reached before the goal"
    for step in range(max_steps + 1):
        if progress is not None:
            progress(step, max_steps, len(replans))
        if np.hypot(*(goal - pos)) <= 1e-9:
            reason = "goal reached"
            break
        if step == max_steps:
            break
        if remainder is None or (dynamic and step % cfg.replan_every == 0):
            k = len(replans)
            key = tuple(master.spawn_key)
            ss = np.random.SeedSequence(master.entropy, spawn_key=(*key, k))
            rng = np.random.default_rng(
                np.random.SeedSequence(master.entropy, spawn_key=(*key, k, 1))
            )
            if remainder is None:
                n_via = max(0, int(cfg.seed_fraction * (cfg.first_pop_size or cfg.pop_size)) - 1)
                x0 = np.vstack(
                    [
                        densify(np.array([pos, goal]), cfg.n_waypoints).reshape(1, -1),
                        _via_paths(
                            pos, goal, cfg.n_waypoints, n_via, rng, lb, ub, sc.width, sc.height
                        ),
                    ]
                )
            else:
                x0 = _seeds(remainder, cfg.n_waypoints, cfg, rng, lb, ub)
            first = remainder is None
            iters = cfg.first_iters if first else cfg.replan_iters
            t0 = time.perf_counter()
            res = _optimise(
                cost,
                pos,
                float(step),
                algorithm,
                cfg,
                iters,
                ss,
                x0,
                None if first else cfg.replan_time,
                (cfg.first_pop_size or cfg.pop_size) if first else cfg.pop_size,
            )
            latency = time.perf_counter() - t0
            best = res.x[0]
            length, ncol, _ = cost.parts(best[None, :], start=pos, t0=float(step))
            replans.append(
                Replan(
                    step=step,
                    position=pos.copy(),
                    waypoints=best.reshape(-1, 2).copy(),
                    cost=float(res.fun[0]),
                    length=float(length[0]),
                    collisions=int(ncol[0]),
                    latency=latency,
                    nfev=int(res.nfev[0]),
                    history=res.history[0].copy(),
                )
            )
            remainder = assemble_paths(best[None, :], pos, goal)[0]
        pos, remainder, passed, frac = advance(remainder, v)
        drive.move(step, pos, passed, frac)
    return drive.result(
        reason, scenario=sc, algorithm=algorithm, seed=seed, config=cfg, replans=replans
    )


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
    max_steps = max_steps or int(np.ceil(4 * sc.straight_line_length() / v)) + 10
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
    )
