"""What a planning run returns: :class:`Replan`, :class:`PlanResult`, the recorder of the
executed motion (:class:`Drive`) and the ``.npz`` (de)serialisation of a result.

Every planner of :data:`mawdo.planning.run.planners.PLANNERS` returns a :class:`PlanResult`; its
verdict fields (``collision_free``, ``hits``, ``min_clearance``) are the independent checker's
(:func:`mawdo.planning.judge.check.check_trajectory`), computed once when the run ends, so the
metrics (:func:`mawdo.planning.judge.metrics.run_metrics`) read them instead of checking again.
"""

from __future__ import annotations

import io
from dataclasses import dataclass

import numpy as np

from mawdo.planning.run.config import PlannerConfig, resolve_scenario
from mawdo.planning.world.scenario import Scenario

__all__ = ["Drive", "PlanResult", "Replan", "result_from_bytes", "result_to_bytes"]


@dataclass
class Replan:
    """One optimisation made during a run (for a single-shot planner: its one plan)."""

    step: int
    position: np.ndarray  # (2,) robot position when planning (pixels)
    waypoints: np.ndarray  # (m, 2) best waypoints
    cost: float
    length: float  # plan length from position to goal (pixels)
    collisions: int  # n of Eq. 27 for the plan, as the cost kernel sees it
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
        The robot reached the goal within the step limit *and* the independent checker
        (:func:`mawdo.planning.judge.check.check_trajectory`: space, time, robot radius, map border)
        accepts the executed route.
    reason : str
        ``"goal reached"``, or why not: ``"no collision-free route found ..."``,
        ``"step limit reached before the goal"``, ``"goal reached but the route collides ..."``.
    replans : list of Replan
        Every optimisation, the first plan included.
    collision_free : bool
        The checker's verdict on the executed route.
    hits : int
        The checker's hits on the executed route (the map's border included), >= 0.
    min_clearance : float
        Smallest clearance of the executed route (px, true robot radius).
    near_misses : int
        Route segments whose clearance fell below the planner's margin without colliding.
    waits, evasions : int
        Steps the guard waited in place / made an evasive move (no safe candidate).
    holds : int
        Replans skipped, each cleared by the guard to the goal (see
        :attr:`~mawdo.planning.run.config.PlannerConfig.hold_straight` and ``hold_gap``).
    gated : int
        Replans that took the guides' own answer without a search: it was within ``hold_gap``
        of the shortest route and free to the goal
        (:attr:`~mawdo.planning.run.config.PlannerConfig.guide_gate`,
        :mod:`~mawdo.planning.run.gate`; stored since 0.10, 0 when read from older payloads).
    fallbacks : int
        Times the guard drove an elite candidate other than the optimizer's best.
    inevitable : int
        Steps at which no option of the guard kept a safe continuation, so it drove the least
        bad (:mod:`mawdo.planning.safety.ics`), plus one when a run that gave up found no spot where
        waiting is safe (stored in the ``.npz`` payload since 0.8; 0 when read from older ones).
    kinematic_violations : int
        Steps of the executed trajectory that break the opt-in kinematic limits
        (:func:`~mawdo.planning.judge.kincheck.check_kinematics`); 0 without limits. Stored like
        ``inevitable``.
    solved : bool
        False when a single-shot planner returned no route (the route is the start alone and
        the route metrics are None).
    guarded : bool
        True for runs driven step by step (the guard's counts mean something); False for
        single-shot planners, whose route is followed blind (their counts are None in the
        metrics).
    robot_caused, other_collisions : int or None
        The checker's collisions split by fault (:func:`~mawdo.planning.judge.fault.blame`):
        those the robot's own motion produced and the rest; ``None`` for runs that were not
        stepped in a world with reactive agents (their collisions split into active and
        passive instead).
    check : CheckReport or None
        The independent checker's report on the executed route, per piece and obstacle
        (:func:`~mawdo.planning.judge.check.check_trajectory`), kept by stepped runs so that
        their metrics read it instead of checking again; None for the others.
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
    collision_free: bool = False
    min_clearance: float = float("nan")
    near_misses: int = 0
    waits: int = 0
    evasions: int = 0
    fallbacks: int = 0
    holds: int = 0
    gated: int = 0
    inevitable: int = 0
    kinematic_violations: int = 0
    hits: int = 0
    solved: bool = True
    guarded: bool = True
    robot_caused: int | None = None
    other_collisions: int | None = None
    check: object | None = None

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


class Drive:
    """The executed motion: positions at integer steps, and the route with every vertex passed
    between two steps, time-stamped (what the checker and the metrics judge)."""

    def __init__(self, start: np.ndarray) -> None:
        self.traj, self.route, self.stamps = [start.copy()], [start.copy()], [0.0]

    def move(self, step: int, pos: np.ndarray, passed=(), frac=()) -> None:
        """Record the move of ``step`` to ``pos`` through the vertices ``passed`` (reached at
        the fractions ``frac`` of the step)."""
        self.route.extend(passed)
        self.stamps.extend(step + np.asarray(frac, dtype=float))
        self.route.append(pos.copy())
        self.stamps.append(step + 1.0)
        self.traj.append(pos.copy())

    def unjudged(self, reason: str, scenario, algorithm, seed, config, replans, **counts):
        """The moves as a :class:`PlanResult` without the checker's verdict (``success`` and
        ``collision_free`` False): for a part of a run judged as a whole elsewhere."""
        return PlanResult(
            scenario=scenario, algorithm=algorithm, seed=seed, config=config,
            trajectory=np.array(self.traj), success=False, reason=reason, replans=replans,
            route=np.array(self.route), route_times=np.array(self.stamps), **counts,
        )  # fmt: skip

    def result(
        self, reason: str, scenario, margin: float = 0.0, limits=None, **fields
    ) -> PlanResult:
        """The run's outcome; the independent checker judges the route (success needs it).

        ``margin`` (px, >= 0) is the planner's safety margin: segments closer than it without
        colliding count as near misses. ``limits``
        (:class:`~mawdo.planning.safety.kinematics.Limits`, optional): the trajectory must keep them
        too (:func:`~mawdo.planning.judge.kincheck.check_kinematics`).
        """
        from mawdo.planning.judge.check import check_trajectory
        from mawdo.planning.judge.kincheck import check_kinematics

        route, stamps = np.array(self.route), np.array(self.stamps)
        rep = check_trajectory(route, scenario, times=stamps)
        reached = reason == "goal reached"
        kin = None
        if limits is not None:
            kin = check_kinematics(np.array(self.traj), limits.speed, limits.accel, limits.turn)
        if reached and not rep.ok:
            reason = f"goal reached but the route collides ({rep.hits} checker hits: "
            reason += f"{rep.describe()})"
        elif reached and kin is not None and not kin.ok:
            reason = f"goal reached but the motion breaks the kinematic limits ({kin.describe()})"
            reached = False
        per_step = rep.clearance.min(axis=1) if rep.clearance.size else np.zeros(0)
        return PlanResult(
            trajectory=np.array(self.traj),
            success=reached and rep.ok,
            reason=reason,
            route=route,
            route_times=stamps,
            scenario=scenario,
            collision_free=bool(rep.ok),
            hits=int(rep.hits),
            min_clearance=float(rep.min_clearance),
            near_misses=int(np.sum((per_step >= -1e-9) & (per_step < margin))),
            kinematic_violations=0 if kin is None else kin.count,
            **fields,
        )


def result_to_bytes(result: PlanResult) -> bytes:
    """Serialise what figures and metrics need (route, replans, the checker's verdict) to
    ``.npz`` bytes; the scenario is not included (the study stores its plan, which names it)."""
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
            [
                result.waits,
                result.evasions,
                result.fallbacks,
                result.near_misses,
                result.holds,
                result.inevitable,
                result.kinematic_violations,
                # only where a replan was gated: earlier payloads stay byte for byte
                *([result.gated] if result.gated else []),
            ]
        ),
        verdict=np.array([result.hits, result.solved, result.guarded]),
    )
    return buf.getvalue()


def result_from_bytes(data: bytes, scenario) -> PlanResult:
    """Inverse of :func:`result_to_bytes` (the config is not stored: defaults are filled in).

    Payloads written before the checker's hit count was stored (mawdo < 0.8) get it from the
    checker, once, here."""
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
    sc = resolve_scenario(scenario)
    extra = {}
    if "events" in z.files:  # payloads written since the guard
        # holds: written since 0.3; inevitable steps and kinematic violations since 0.8;
        # gated replans since 0.10
        w, e, f, nm, *later = (int(x) for x in z["events"])
        later += [0] * (4 - len(later))
        extra = dict(
            holds=later[0],
            inevitable=later[1],
            kinematic_violations=later[2],
            gated=later[3],
            collision_free=bool(z["collision_free"]),
            min_clearance=float(z["min_clearance"]),
            waits=w,
            evasions=e,
            fallbacks=f,
            near_misses=nm,
        )
    if "verdict" in z.files:
        hits, solved, guarded = (int(x) for x in z["verdict"])
        extra |= dict(hits=hits, solved=bool(solved), guarded=bool(guarded))
    else:
        from mawdo.planning.judge.check import check_trajectory

        extra["hits"] = int(check_trajectory(z["route"], sc, times=z["route_times"]).hits)
    return PlanResult(
        scenario=sc,
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
