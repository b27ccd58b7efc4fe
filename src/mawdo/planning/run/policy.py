"""Planners as policies: what the stepped world drives one step at a time.

:class:`PlannerPolicy` is our planner with a ``knowledge`` setting:

``oracle``
    Told every obstacle's future at reset (the scenario's closed-form motions, or the recorded
    futures of people who do not see the robot), it plans the whole run once with
    :func:`~mawdo.planning.run.planner.plan`, exactly as without a world, and replays it step by
    step. The upper bound, and today's behaviour.
``observed``
    Told only the static map. Each step the reading goes through a tracker
    (:mod:`mawdo.planning.sense.tracker`) and a predictor (:mod:`mawdo.planning.sense.predict`);
    the predicted motions become circle obstacles of a prediction scenario, and one step of the
    planner's own loop (guide, refinement, guard, inevitable-collision rule) runs on it from the
    robot's position. Every stage consumes predictions through the interface it uses for
    scripted motions; nothing has a second code path.

:class:`StraightLine` drives straight to the goal at full speed, blind: the floor of any table.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from mawdo.planning.run.carried import CarriedMotion
from mawdo.planning.sense.predict import K_SD
from mawdo.planning.sense.reading import Reading
from mawdo.planning.world.stepped import Move, static_part, with_movers
from mawdo.streams import step_seed_sequence

__all__ = [
    "KNOWLEDGE",
    "PlannerPolicy",
    "StraightLine",
    "closes_in_reach",
    "dodge_ratio",
    "step_move",
]

#: The planner without an optimizer (the guides' best seed), a choice beside the optimizers.
GUIDE_ONLY = "guide_only"

#: How far short of the robot (px) a predicted disc's uncertainty margin stops when it would
#: otherwise cover the robot (see PlannerPolicy._held_margin).
MARGIN_SLACK = 1e-6

#: A last remainder warms the next step's search only if it begins this close (px) to the robot.
WARM_TOL = 1e-9

#: What a planner may know about the moving agents.
KNOWLEDGE = ("oracle", "observed")


def step_move(route, stamps, step: int) -> Move:
    """The part of a time-stamped route driven during ``step`` (``stamps`` in time steps,
    non-decreasing): every corner with ``step < stamp < step + 1``, then where the route is at
    ``step + 1`` (linear between points; at its end once it is over)."""
    route, stamps = np.asarray(route, float), np.asarray(stamps, float)
    inside = (stamps > step) & (stamps < step + 1)
    end = np.array([np.interp(step + 1.0, stamps, route[:, k]) for k in (0, 1)])
    pts = np.vstack([route[inside], end[None, :]])
    return Move(pts, np.append(stamps[inside] - step, 1.0))


class StraightLine:
    """Straight to the goal at full speed, seeing nothing."""

    name = "straight"

    def reset(self, scenario, seed) -> None:
        self.speed = scenario.robot_speed

    def act(self, reading: Reading) -> np.ndarray:
        d = reading.goal - reading.position
        n = float(np.hypot(*d))
        return d if n <= self.speed else d * (self.speed / n)


def closes_in_reach(position, points, fracs, centres, contact, top, samples: int = 16) -> bool:
    """Whether a robot driving ``position -> points`` over one step (corners reached at
    ``fracs`` of it) heads, at some moment, toward an agent that could touch it then.

    At each moment ``f`` of the step (fraction, ``samples`` per leg) an agent can be in
    contact only if the robot is within its contact distance ``contact`` plus ``f`` times its
    reach per step ``top`` of its centre now; the robot heads toward it if its velocity has
    a positive component toward that centre: a contact the judge would put down to the robot
    (:func:`~mawdo.planning.judge.fault.blame`). Standing, or moving away, never does.
    All lengths in pixels; ``centres`` shape (n, 2), ``contact`` and ``top`` shape (n,).
    """
    pts = np.vstack([position, points])
    legs = np.diff(pts, axis=0)
    if not len(centres) or not np.any(legs):
        return False
    fr = np.concatenate(([0.0], fracs))
    legs_f = zip(fr[:-1], fr[1:], strict=True)
    f = np.concatenate([np.linspace(a, b, samples + 1) for a, b in legs_f])
    leg = np.repeat(np.arange(len(legs)), samples + 1)
    p = np.stack([np.interp(f, fr, pts[:, k]) for k in (0, 1)], axis=1)
    to_agent = centres[None, :, :] - p[:, None, :]
    toward = np.einsum("sk,sak->sa", legs[leg], to_agent) > 0.0
    within = np.hypot(to_agent[..., 0], to_agent[..., 1]) <= contact + f[:, None] * top
    return bool(np.any(toward & within))


def dodge_ratio(u: float, v: float) -> float:
    """Closest approach, over the starting centre distance, that a robot of speed ``v`` can
    keep from an agent walking straight at it at speed ``u`` (any units, both >= 0).

    The robot moving at angle ``phi`` from the agent's heading passes it at
    ``D v sin(phi) / sqrt(u^2 - 2 u v cos(phi) + v^2)`` (the closest approach of two straight
    motions); the best ``phi`` has ``cos(phi) = v / u`` and gives ``v / u``. A robot at least
    as fast as the agent outruns it: the distance never shrinks (ratio 1).

    Returns
    -------
    float
        In (0, 1]; 1 where ``u <= v``.
    """
    return 1.0 if u <= v else v / u


class PlannerPolicy:
    """Our planner as a policy (see the module docstring).

    Parameters
    ----------
    algorithm : str
        Any registered optimizer, or ``"guide_only"`` (the guides' best seed, no optimizer).
    config : PlannerConfig or str, optional
        Settings or a preset name (``"realtime"`` by default).
    knowledge : {"observed", "oracle"}
        What the planner is told (module docstring).
    predictor : str
        A registered predictor (``constant_velocity``, ``stop``; ``observed`` only).
    tracker : object, optional
        ``reset()`` and ``update(reading) -> Tracks``; default a constant-velocity Kalman tracker
        (:class:`mawdo.planning.sense.tracker.Tracker`) for an exact sensor.
    horizon : int
        How far ahead (time steps, >= 1) predictions reach; beyond it a prediction stands still.
    predictor_options : dict, optional
        Keyword options of the predictor (e.g. ``k_sd``, ``tube_horizon``:
        :func:`~mawdo.planning.sense.predict.constant_velocity`).
    look_first : int
        Steps (>= 0) the robot stands and watches at the start of an episode when it sees
        anyone (``observed`` only): a tracker knows no velocity before its second reading, and
        a first plan around people of unknown velocity (discs grown by the tracker's whole
        speed uncertainty) is a detour the following steps inherit. It watches only while no
        agent could come so close meanwhile that the robot could not step out of its way
        (:meth:`may_watch`).
    warm : bool
        Start each step's search from the last step's plan (a replan: cheaper, about 9 ms
        against 20 ms per step with 5 people) instead of afresh from the guides on a
        replan's budget (default: its routes were about 9 % shorter in time on CrowdNav's
        circle crossing, as the last plan keeps the detours of the steps before).
    keep_off : bool
        Refuse steps toward anyone who could reach the robot within the step (default;
        :meth:`_keep_off`). Off only to measure what the rule costs: without it, a person who
        turns round within a step can meet a robot still closing in, and the contact is the
        robot's.
    **overrides
        Fields of :class:`~mawdo.planning.run.config.PlannerConfig`.
    """

    def __init__(
        self, algorithm: str = "mawdo", config=None, knowledge: str = "observed",
        predictor: str = "constant_velocity", tracker=None, horizon: int = 200,
        predictor_options=None, look_first: int = 1, warm: bool = False, keep_off: bool = True,
        **overrides,
    ):  # fmt: skip
        from mawdo.planning.run.config import resolve_config

        if knowledge not in KNOWLEDGE:
            raise ValueError(f"knowledge must be one of {KNOWLEDGE}, got {knowledge!r}")
        if int(horizon) < 1:
            raise ValueError(f"horizon must be >= 1 time step, got {horizon!r}")
        self.algorithm, self.knowledge, self.horizon = algorithm, knowledge, int(horizon)
        self.config = resolve_config(config, overrides)
        if knowledge == "observed":
            from mawdo.optimizers import OPTIMIZERS
            from mawdo.planning.sense.predict import PREDICTORS

            if algorithm != GUIDE_ONLY:
                OPTIMIZERS[algorithm]  # an unknown name fails here, listing the known ones
            spec = PREDICTORS[predictor]  # likewise
            if spec.needs_truth:
                raise ValueError(
                    f"predictor {predictor!r} needs the world's true future, which an observing "
                    "planner does not have; use knowledge='oracle' for the upper bound"
                )
            self.predict = spec.predict
        self.predictor, self.tracker = predictor, tracker
        self.predictor_options = dict(predictor_options or {})
        if int(look_first) < 0:
            raise ValueError(f"look_first must be >= 0 steps, got {look_first!r}")
        self.look_first, self.warm = int(look_first), bool(warm)
        self.keep_off = bool(keep_off)
        self.name = f"{algorithm}-{knowledge}"

    def reset(self, scenario, seed) -> None:
        from mawdo.planning.safety.kinematics import Limits

        self.seed = seed
        # what the episode's judge holds the driven trajectory to (None: no limits)
        self.limits = Limits.of(self.config, scenario.robot_speed)
        if self.knowledge == "oracle":
            from mawdo.planning.run.planner import plan

            self.result = plan(scenario, self.algorithm, seed, self.config)
            return
        from mawdo.planning.guide.passage import fit_config

        self.known = static_part(scenario)
        # the margin fitted once, to the passages between start and goal: a step's run starts
        # where the robot is, but fitting it again each step would cost more than the step
        self.fitted = fit_config(self.known, self.config)
        self.motion = CarriedMotion.of(self.fitted, self.known.robot_speed)
        if self.tracker is None:
            from mawdo.planning.sense.tracker import Tracker

            self.tracker = Tracker(noise=0.0)
        self.tracker.reset()
        self.last = self._remainder = None

    @property
    def waypoints(self):
        """The last step's plan (pixels, ``(m, 2)``), or None before the first step."""
        last = getattr(self, "last", None)
        return None if last is None or not last.replans else last.replans[-1].waypoints

    def act(self, reading: Reading):
        if self.knowledge == "oracle":
            return step_move(self.result.route, self.result.route_times, reading.step)
        if self.may_watch(reading):
            self.tracker.update(reading)  # a velocity needs two readings: look, then plan
            if self.motion is not None:
                self.motion.stand()
            return np.zeros(2)
        return self._decide(reading)

    def may_watch(self, reading: Reading) -> bool:
        """Whether the robot stands and watches at this reading: within the first
        ``look_first`` steps, someone in sight, and nobody close enough that after the watch
        the robot could no longer step out of their way.

        Standing still is safe only against an agent that cannot close in so far that, once
        the watch ends, no move avoids it. Its speed is not known yet (one reading), so the
        bound is the one the prediction would carry: ``u`` = ``k_sd`` standard deviations of
        the tracker's speed prior (``birth_speed_sd``, pixels per time step; the robot's speed
        for a tracker without one). The worst agent walks straight at the robot at ``u``
        through the remaining watch steps and on (:func:`dodge_ratio`); the robot watches only
        where, from the centre distance left when the watch ends, its best escape still passes
        every agent in sight at more than the two radii plus the planner's clearance. An agent
        that steers after a slower robot catches it whether or not it watched, and a wall
        beside the robot is the planner's to mind, not this test's.
        """
        left = self.look_first - reading.step
        if left <= 0 or not len(reading.centers):
            return False
        speed_sd = getattr(self.tracker, "birth_speed_sd", self.known.robot_speed)
        u = self.predictor_options.get("k_sd", K_SD) * speed_sd
        v = self.known.robot_speed
        after = np.hypot(*(reading.centers - reading.position).T) - u * left
        reach = reading.radii + self.known.robot_radius + self.fitted.clearance
        return bool(np.all(after * dodge_ratio(u, v) > reach))

    def prediction(self, reading: Reading):
        """The prediction scenario of a reading: the known map plus one circle per track,
        moving as the predictor says (times from 0 = now), the robot starting where it is."""
        self._tracks = tracks = self.tracker.update(reading)
        sc = self.known
        preds = self.predict(tracks, 0.0, float(self.horizon), sc.bounds, **self.predictor_options)
        rows = {int(i): k for k, i in enumerate(tracks.ids)}
        k = np.array([rows[int(p.id)] for p in preds], dtype=np.int64)
        centres = tracks.centers[k] if len(k) else np.zeros((0, 2))
        pairs = zip(preds, centres, strict=True)
        movers = [(p.motion.times, c + p.motion.offsets) for p, c in pairs]
        grown = np.array([p.radius for p in preds])
        radii = self._held_margin(reading.position, centres, grown, tracks.radii[k])
        ids = [f"track-{int(p.id)}" for p in preds]
        spreads = [p.spread for p in preds]
        spreads = None if any(s is None for s in spreads) else spreads
        return with_movers(sc, radii, movers, ids, start=reading.position, spreads=spreads)

    def _held_margin(self, position, centres, radii, own) -> np.ndarray:
        """Predicted radii whose uncertainty margin stops short of the robot: a margin that
        already covers the robot (with the planner's clearance) would leave it no route at all,
        not even away from the agent; the agent's own radius is never cut."""
        if not len(radii):
            return radii
        gap = np.hypot(*(np.asarray(position) - centres).T)
        room = gap - self.known.robot_radius - self.fitted.clearance - MARGIN_SLACK
        return np.where(radii > room, np.maximum(own, room), radii)

    def _step_config(self):
        """The settings of one step's run: one step long (the guide-only planner with its
        safe-interval guide on), the episode's first plan on a first plan's budget and every
        later one a fresh search on a replan's budget (whether or not the robot watched
        first: a decision is due every step)."""
        cfg = replace(self.fitted, max_steps=1)
        if self.algorithm == GUIDE_ONLY:
            cfg = replace(cfg, time_guide=True)
        if self.last is not None and not self.warm:
            cfg = replace(cfg, first_iters=cfg.replan_iters, first_pop_size=None)
        return cfg

    def _decide(self, reading: Reading) -> Move:
        from mawdo.planning.run.execute import Run, share_guide
        from mawdo.planning.run.timed_planners import GuideOnlyRun

        sc = self.prediction(reading)
        share_guide(self.known, sc)
        seed = step_seed_sequence(self.seed, reading.step)
        kind = GuideOnlyRun if self.algorithm == GUIDE_ONLY else Run
        run = kind(sc, self.algorithm, seed, self._step_config(), True)
        run.warm_start = self._warm(reading.position) if self.warm else None
        run.judge = False  # the episode is judged as a whole, on the realised world
        share_guide(sc, self.known)  # built on the first step, kept for the episode
        if self.motion is not None:
            self.motion.hand_to(run, reading.position)
        self.last = res = run.execute()
        self._remainder = run.remainder
        if self.motion is not None:
            self.motion.take_from(run)
        return self._keep_off(step_move(res.route, res.route_times, 0), reading.position, run)

    def _keep_off(self, move: Move, position, run) -> Move:
        """``move``, unless it heads toward someone who could touch the robot meanwhile
        (:func:`closes_in_reach`); then the guard's safe move nearest its end that does not,
        where there is one.

        The prediction vouches for a person's future only within its margin, and a person
        who slows ahead of the robot may turn round at full speed within a step (CrowdNav's
        people pick a new goal when they reach theirs): a robot still closing in then causes
        the contact. Each agent is taken to cover at most ``top`` px in a step: the robot's
        speed, or its tracked speed plus ``k_sd`` s.d.s where that is more; and to be in
        contact from ``k_sd`` s.d.s of the sensor's noise farther than the two radii (a noisy
        reading may place it that much too far). Without kinematic limits only (a move of the
        guard's ignores them).
        """
        if not self.keep_off or self.motion is not None or self.fitted.max_speed is not None:
            return move
        reach = self._reach(self._tracks)
        position = np.asarray(position, float)
        if not closes_in_reach(position, move.points, move.fracs, *reach):
            return move
        to, _, safe = run.guard.evasive_move(
            position, move.points[-1], 0.0, 1.0,
            admit=lambda m: not closes_in_reach(position, np.asarray(m)[None, :], np.ones(1),
                                                *reach),
        )  # fmt: skip
        return Move(np.asarray(to)[None, :], np.ones(1)) if safe else move

    def _reach(self, tracks):
        """``(centres, contact, top)`` of :func:`closes_in_reach` for the tracks (pixels).

        A track missed for ``m`` steps is taken from where it was last detected, its contact
        distance grown by ``m`` steps of its reach: its reported centre is a constant-velocity
        guess, and a person who turned round meanwhile is anywhere within that reach of where
        the sensor last saw them."""
        k_sd = self.predictor_options.get("k_sd", K_SD)
        speed = np.hypot(*tracks.velocities.T)
        top = np.maximum(self.known.robot_speed, speed + k_sd * tracks.velocity_sd)
        # a centre read through noise may be off by k_sd of the sensor's s.d. (0 for an exact one)
        near = self.known.robot_radius + k_sd * getattr(self.tracker, "noise", 0.0)
        # the tracker predicts a missed track at constant velocity, one step at a time (a
        # track detected now, missed 0, is taken exactly as reported)
        missed = tracks.missed
        seen = tracks.centers - missed[:, None] * tracks.velocities
        return seen, tracks.radii + near + missed * top, top

    def _warm(self, position):
        """The last step's remainder, when the robot stands where it begins: the step's search
        then starts from it with a replan's budget instead of a first plan's."""
        rem = getattr(self, "_remainder", None)
        if rem is None or len(rem) < 2 or np.hypot(*(rem[0] - position)) > WARM_TOL:
            return None
        return rem


def run_as_planner(scenario, seed, config, policy, name: str):
    """``policy`` driven through the stepped world of ``scenario`` (its people included) under
    the planners' one step limit (:func:`~mawdo.planning.run.config.step_limit`): a
    :class:`~mawdo.planning.run.result.PlanResult` like every planner's, named ``name``."""
    from mawdo.planning.run.episode import run_episode
    from mawdo.planning.run.planner import prepare
    from mawdo.planning.world.stepped import SteppedWorld

    steps = prepare(scenario, "mawdo", 0, replace(config, time_guide=False)).step_limit()[0]
    world = SteppedWorld.of(scenario, seed)
    return run_episode(world, policy, steps, seed, name=name, config=config)


def observed_run(scenario, seed, config, algorithm: str = "mawdo"):
    """A scenario run with ``observed`` knowledge: the planner policy in a stepped world
    (:func:`run_as_planner`)."""
    policy = PlannerPolicy(algorithm, config, "observed")
    return run_as_planner(scenario, seed, config, policy, f"{algorithm}_observed")
