"""The swarm's search for a faster drive of a limited timed route (corners rounded, speed kept).

With ``max_accel`` or ``max_turn`` set, the run follows the safe-interval guide's timed route,
which stops and turns in place at every vertex (:mod:`mawdo.planning.guide.sipp.profile`).
:class:`TrajectoryRefiner` searches, with the planner's own optimizer batched over its
population, for per-corner decisions that drive the same vertices sooner
(:mod:`mawdo.planning.refine.trajectory`): per rounded corner, how wide the arc is (``e`` as a
share of what the legs allow; below :data:`STOP_SHARE` the corner stays sharp: a stop) and how
much of the arc's top speed is carried (share of ``c_max``), and per leg its cruise speed
(share of the speed cap: a robot that would reach a door before a mover leaves it slows down
on the way instead of stopping), and per wait of the route whether the drive holds there
(a share ``h >= 1/2``: it stops and leaves no earlier than ``2 h - 1`` of the way from the
route's arrival there to its departure, the route's own departure at ``h = 1``) or drives on (the
faster drive may pass before the mover the route waited for arrives).

Cost of a candidate (time steps): its arrival step, plus :data:`PENALTY` per step that breaks a
limit (a margin-free test of speed, acceleration, move-to-move turn and the run's stopping
speed), meets a mover (the guide's own exact test,
:func:`~mawdo.planning.guide.sipp.intervals.segment_free`, walkers as the guide models them), comes
closer than ``r + clearance`` to a static obstacle
(:func:`~mawdo.planning.judge.check.check_static_path`) or to the map's border.

The best candidate is kept only when it arrives strictly earlier than the route and passes,
step by step, what the run will do with it (:func:`replay`: every step comes out of the run's
own :func:`~mawdo.planning.safety.kinematics.wanted_step` and
:func:`~mawdo.planning.safety.kinematics.project` unchanged, so it meets the limits by
construction), the guard's exact step test (clearance >= the run's margin) and, with the
inevitable-collision rule on, the rule's test of the whole route
(:meth:`~mawdo.planning.safety.ics.SafeContinuation.path_safe`). Otherwise the guide's route is
driven as before: the result is never later than it. The run refines each timed route the guide
returns and follows the verified drive that arrives first
(:meth:`~mawdo.planning.guide.timeguide.TimedRun._refined`).
"""

from __future__ import annotations

import math

import numpy as np

from mawdo.planning.guide.sipp.intervals import segment_free
from mawdo.planning.guide.sipp.profile import rest_steps
from mawdo.planning.judge.check import check_static_path
from mawdo.planning.refine.trajectory import (
    ARC_CENTRIPETAL,
    ARC_TURN,
    MAX_ROUND_TURN,
    SmoothPath,
    route_stops,
    speed_pass,
    turn_angle,
)
from mawdo.planning.safety.kinematics import SLACK, project, turned, wanted_step

__all__ = ["RoutePlan", "TrajectoryRefiner", "replay"]

#: Cost (time steps) of each step that breaks a limit or meets an obstacle.
PENALTY = 1000.0
#: A corner whose arc share is below this stays sharp: the robot stops there.
STOP_SHARE = 0.05
#: Least share of an arc's top speed carried through it.
LEAST_CARRY = 0.1
#: A wait's share at or above which the drive holds there.
HOLD = 0.5
#: Most corners and legs with decision variables (later corners are stops, later legs at the
#: speed cap).
MAX_CORNERS, MAX_LEGS = 16, 24
#: Population and iterations of the swarm's search per refined route.
POP, ITERS = 24, 20
#: Most halvings of the arcs that come too close to a wall, per candidate.
REPAIRS = 4
#: Share of its cruise a leg keeps when a repair slows it (a drive that met a mover).
SLOWER = 0.85
#: Tolerance (px) of :func:`replay`: the run's step must give back the planned position.
REPLAY_TOL = 1e-9


class RoutePlan:
    """A timed route's vertices, waits and corners, and the trajectories of decisions ``x``.

    Parameters
    ----------
    route : TimedRoute
        The guide's route from ``pos`` at ``t0`` (pixels, time steps).
    pos : numpy.ndarray
        The robot's position (pixels).
    t0 : int
        The step the route starts (time steps).
    state : tuple
        The robot's ``(velocity, heading, still)`` (px per step; unit vector or None; steps).
    limits : Limits
        The run's limits (an acceleration or a turn-rate limit set).
    speed : float
        The robot's speed within the cap (px per step).
    """

    def __init__(self, route, pos, t0: int, state, limits, speed: float) -> None:
        V, arrive, depart = route_stops(route.points, route.times)
        V[0] = pos
        self.V, self.t0, self.limits, self.v = V, int(t0), limits, float(speed)
        self.vel, self.heading, self.still = np.asarray(state[0], float), state[1], int(state[2])
        self.a = math.inf if limits.accel is None else limits.accel * (1.0 - 4.0 * SLACK)
        self.turn = math.inf if limits.turn is None else limits.turn * (1.0 - 4.0 * SLACK)
        self.seed_steps = int(round(route.times[-1])) - self.t0
        n = len(V)
        d = np.diff(V, axis=0)
        self.u = d / np.hypot(d[:, 0], d[:, 1])[:, None]
        self.theta = np.array([turn_angle(self.u[i - 1], self.u[i]) for i in range(1, n - 1)])
        accel_on, free = limits.accel is not None, limits.turn is None
        # each leg's mean speed on the route, as a share of the speed cap
        self.leg_share = np.hypot(d[:, 0], d[:, 1]) / np.maximum(arrive[1:] - depart[:-1], 1e-9)
        self.leg_share /= self.v
        self.wait = np.full(n, np.nan)  # departure times of the route's waits
        self.arrive = arrive
        for i in range(n - 1):
            h = self.u[i - 1] if i > 0 else np.zeros(2)
            need = rest_steps(h[0], h[1], self.u[i][0], self.u[i][1], accel_on,
                              math.inf if free else float(limits.turn))  # fmt: skip
            if depart[i] - arrive[i] > need + 1e-6:
                self.wait[i] = depart[i]
        inner = range(1, n - 1)
        self.corners = [i for i in inner if self.theta[i - 1] <= MAX_ROUND_TURN][:MAX_CORNERS]
        self.waits = np.flatnonzero(~np.isnan(self.wait))
        self.dim = 2 * len(self.corners) + len(self.waits) + min(n - 1, MAX_LEGS)

    def split(self, x):
        """Decisions ``x`` as ``(per corner (e share, carried share), {held wait: departure
        time}, per leg cruise share)``."""
        x = np.asarray(x, float)
        nc, nw = 2 * len(self.corners), len(self.waits)
        held = {}
        for i, h in zip(self.waits, x[nc : nc + nw], strict=True):
            if h >= HOLD:
                late = (h - HOLD) / (1.0 - HOLD)
                held[int(i)] = self.arrive[i] + late * (self.wait[i] - self.arrive[i])
        cruise = np.ones(len(self.V) - 1)
        cruise[: len(x) - nc - nw] = np.maximum(x[nc + nw :], LEAST_CARRY)
        return x[:nc].reshape(-1, 2), held, cruise

    def trajectory(self, x) -> np.ndarray | None:
        """Positions (pixels) at steps ``t0, t0 + 1, ...`` to the goal for decisions ``x`` (in
        [0, 1]; :meth:`split`), or None where they cannot be driven."""
        x, self._held, self._cruise = self.split(x)
        rounded = {
            i: r for i, r in zip(self.corners, x, strict=True)
            if r[0] >= STOP_SHARE and i not in self._held
        }  # fmt: skip
        stops = [0] + [i for i in range(1, len(self.V) - 1) if i not in rounded]
        stops.append(len(self.V) - 1)
        pts, heading, still = [self.V[0]], self.heading, self.still
        w0 = float(np.hypot(*self.vel))
        for a, b in zip(stops[:-1], stops[1:], strict=True):
            if w0 > 0.0:  # a moving start: the route's first leg goes on along the velocity
                if turn_angle(self.vel, self.u[a]) > 1e-6:
                    return None
            else:
                k = self._stand(a, len(pts) - 1, heading, still)
                pts.extend([pts[-1]] * k)
                still += k
            s, path = self._stretch(a, b, rounded, w0)
            if s is None:
                return None
            seg = path.at(s)
            seg[-1] = self.V[b]
            pts.extend(seg)
            heading, still, w0 = self.u[b - 1], 0, 0.0
        return np.array(pts)

    def _stand(self, i: int, t: int, heading, still: int) -> int:
        """Steps to stand at stop ``i`` (reached at step ``t`` after ``t0``) before leaving."""
        k = 0
        if heading is not None and math.isfinite(self.turn):
            k = math.ceil(turn_angle(heading, self.u[i]) / self.turn - 1e-12) - 1 - still
        if math.isfinite(self.a) and i > 0:
            k = max(k, 1 - still)  # a step at rest between the last move in and the first out
        if i in self._held:
            k = max(k, int(math.ceil(self._held[i] - 1e-9)) - self.t0 - t)
        return max(k, 0)

    def _stretch(self, a: int, b: int, rounded: dict, w0: float):
        """The speed pass over the path from stop ``a`` to stop ``b``: ``(s, path)``."""
        V = self.V[a : b + 1]
        lens = np.hypot(*np.diff(V, axis=0).T)
        e = np.zeros(max(len(V) - 2, 0))
        for j in range(1, len(V) - 1):
            share = lambda k: 0.5 if (a + k) in rounded else 1.0 - 1e-9  # noqa: E731
            room = min(lens[j - 1] * share(j - 1), lens[j] * share(j + 1))
            e[j - 1] = rounded[a + j][0] * room
        path = SmoothPath(V, e)
        caps = []
        for (_, _, R), j in zip(path.regions, path.leg, strict=True):
            if R == math.inf:  # leg j of the stretch: its cruise
                caps.append(self._cruise[a + j] * self.v)
                continue
            top = min(self.v, ARC_TURN * R * self.turn, math.sqrt(ARC_CENTRIPETAL * self.a * R))
            caps.append(max(rounded[a + j][1], LEAST_CARRY) * top)
        s = speed_pass(path.length, path.regions, caps, w0, self.v, self.a,
                       2 * self.seed_steps + 16)  # fmt: skip
        return s, path


def replay(P, state, limits) -> bool:
    """True when the run, following the trajectory ``P`` (positions at consecutive steps,
    pixels) from the robot's ``(velocity, heading, still)`` state, drives every step as planned:
    the run's :func:`~mawdo.planning.safety.kinematics.wanted_step` (with the plan left to go)
    and :func:`~mawdo.planning.safety.kinematics.project` give it back within
    :data:`REPLAY_TOL` px, so each step meets the limits exactly as the projection does."""
    P = np.asarray(P, float)
    u_all = np.diff(P, axis=0)
    left = np.cumsum(np.hypot(u_all[:, 0], u_all[:, 1])[::-1])[::-1]
    vel, heading, still = np.asarray(state[0], float), state[1], int(state[2])
    for want, rest in zip(u_all, left, strict=True):
        u = project(wanted_step(want, float(rest), vel, limits), vel, limits, heading, still)
        if np.max(np.abs(u - want)) > REPLAY_TOL:
            return False
        vel = u
        heading, still = turned(u, heading, still)
    return True


def _limit_breaks(P, vel, limits, v: float) -> int:
    """Steps of ``P`` (pixels) over a limit, without margins: speed above ``v``, change of
    velocity above ``max_accel``, turn between consecutive moves above ``max_turn``, speed
    above the run's stopping speed for the plan left (the standing turns are checked by
    :func:`replay`)."""
    u = np.diff(P, axis=0)
    n = np.hypot(u[:, 0], u[:, 1])
    bad = n > v * (1.0 + 1e-12)
    if limits.accel is not None:
        a = limits.accel * (1.0 - SLACK)
        du = u - np.vstack([vel, u[:-1]])
        bad |= np.hypot(du[:, 0], du[:, 1]) > a
        left = np.cumsum(n[::-1])[::-1]  # kinematics.stopping_speed, per step
        bad |= n > limits.accel * (np.sqrt(2.0 * left / limits.accel + 0.25) - 0.5) + 1e-10
    if limits.turn is not None and len(u) > 1:
        a, b = u[:-1], u[1:]
        both = (n[:-1] > 0) & (n[1:] > 0)
        ang = np.abs(np.arctan2(a[:, 0] * b[:, 1] - a[:, 1] * b[:, 0], np.sum(a * b, axis=1)))
        bad[1:] |= both & (ang > limits.turn * (1.0 - SLACK))
    return int(bad.sum())


def _starts(plan: RoutePlan) -> np.ndarray:
    """Deterministic starts (:data:`STARTS` rows): wide arcs at full speed, less carried,
    narrower arcs, the guide's stops at every corner; each with the legs at the speed cap or at
    the route's own mean speed over them (so the drive meets the movers when the route does)."""
    nc, nw = len(plan.corners), len(plan.waits)
    nl = plan.dim - 2 * nc - nw
    own = np.minimum(plan.leg_share[:nl], 1.0)
    rows = []
    for e, c, h, legs in (
        (1.0, 1.0, 1.0, 1.0), (1.0, 1.0, 1.0, own), (1.0, 1.0, 0.0, 1.0), (1.0, 0.7, 1.0, own),
        (0.6, 1.0, 1.0, own), (0.6, 1.0, 0.0, 1.0), (1.0, 1.0, 1.0, np.minimum(1.15 * own, 1.0)),
        (0.3, 1.0, 1.0, own), (0.0, 0.0, 1.0, own), (0.0, 0.0, 1.0, 1.0),
    ):  # fmt: skip
        rows.append(
            np.concatenate([np.tile([e, c], nc), np.full(nw, h), np.broadcast_to(legs, (nl,))])
        )
    return np.array(rows)


def _legs_of(Q, V) -> np.ndarray:
    """Per point of ``Q`` (pixels), the leg of the polyline ``V`` nearest it."""
    A, B = V[:-1], V[1:]
    AB = B - A
    t = np.einsum("mkd,kd->mk", Q[:, None] - A[None], AB) / np.maximum(np.sum(AB * AB, 1), 1e-300)
    foot = A[None] + np.clip(t, 0.0, 1.0)[..., None] * AB[None]
    return np.argmin(np.hypot(*(foot - Q[:, None]).transpose(2, 0, 1)), axis=1)


class _Cost:
    """The swarm's cost of a batch of decisions (module docstring); ``pure``: it never writes
    into them."""

    pure = True

    def __init__(self, plan: RoutePlan, refiner, mv) -> None:
        self.plan, self.refiner, self.mv = plan, refiner, mv

    def __call__(self, X):
        f = np.empty(len(X))
        for j, x in enumerate(X):
            _, P, n = self.refiner.repaired(x, self.plan, self.mv)
            f[j] = PENALTY * PENALTY if P is None else len(P) - 1 + PENALTY * n
        return f


class TrajectoryRefiner:
    """A faster drive of limited timed routes (module docstring).

    Parameters
    ----------
    scenario : Scenario
        The run's scenario (its robot at the run's speed).
    clearance : float
        The run's margin (px, >= 0).
    limits : Limits
        The run's limits, with an acceleration or a turn-rate limit.
    optimizer : Optimizer
        The planner's optimizer (population :data:`POP`).
    guard : Guard
        The run's guard (exact step test of the winner).
    ics : SafeContinuation or None
        The run's inevitable-collision rule (its test of the winner), or None.
    """

    def __init__(self, scenario, clearance: float, limits, optimizer, guard, ics=None) -> None:
        self.sc, self.clearance, self.limits = scenario, float(clearance), limits
        self.optimizer, self.guard, self.ics = optimizer, guard, ics
        self.statics = [scenario.obstacles[i].shape for i in scenario.static_indices]
        self.refined = 0  # routes replaced by a faster drive

    def breaks(self, P, plan: RoutePlan, mv):
        """Steps of ``P`` (from step ``plan.t0``) over a limit or meeting an obstacle, and the
        positions (pixels) of those too close to a wall or the border and of those meeting a
        mover."""
        sc, t0 = self.sc, float(plan.t0)
        n = _limit_breaks(P, plan.vel, self.limits, plan.v)
        X, Y = P[:, 0], P[:, 1]
        hit = [
            k for k in range(len(P) - 1)
            if not segment_free(X[k], Y[k], X[k + 1], Y[k + 1], t0 + k, t0 + k + 1.0, mv)
        ]  # fmt: skip
        n += len(hit)
        walls = set()
        if self.statics:
            rep = check_static_path(P, self.statics, sc.robot_radius + self.clearance)
            walls = {s for s, _ in rep.collisions}
        lo = sc.robot_radius + self.clearance
        out = (
            (P[:, 0] < lo) | (P[:, 0] > sc.width - lo) | (P[:, 1] < lo) | (P[:, 1] > sc.height - lo)
        )
        walls |= set(np.flatnonzero(out[1:]).tolist())
        return n + len(walls), P[sorted(walls)], P[hit]

    def repaired(self, x, plan: RoutePlan, mv):
        """``(x, P, breaks)``: the decisions repaired up to :data:`REPAIRS` times (the arc of
        the corner nearest each step too close to a wall narrowed by half; the legs up to each
        step that meets a mover, it and the one before, slowed to :data:`SLOWER` of their
        cruise: such a drive came too early), their trajectory (None: not drivable) and its
        breaks (0 for a trajectory not earlier than the route's: never taken, not judged)."""
        x = np.array(x, float)
        legs0 = 2 * len(plan.corners) + len(plan.waits)
        for attempt in range(REPAIRS + 1):
            P = plan.trajectory(x)
            if P is None or len(P) - 1 >= plan.seed_steps:
                return x, P, 0
            n, walls, movers = self.breaks(P, plan, mv)
            live = [j for j, i in enumerate(plan.corners) if x[2 * j] >= STOP_SHARE]
            if attempt == REPAIRS or not (len(walls) and live or len(movers)):
                return x, P, n
            if len(walls) and live:
                V = plan.V[[plan.corners[j] for j in live]]
                near = np.argmin(np.hypot(*(walls[:, None] - V[None]).transpose(2, 0, 1)), axis=1)
                for j in set(near.tolist()):
                    x[2 * live[j]] *= 0.5
            for leg in set(_legs_of(movers, plan.V).tolist()):
                for j in (legs0 + leg - 1, legs0 + leg):
                    if legs0 <= j < len(x):
                        x[j] *= SLOWER
        return x, P, n

    def refine(self, route, pos, t0: int, state, mv, seeds):
        """The faster drive of ``route`` (a timed route from ``pos`` at step ``t0``; ``state``
        the robot's ``(velocity, heading, still)``; ``mv`` the guide's movers) as a timed route
        with one point per step, or None when none is verified earlier. ``seeds``: the
        optimizer's and the start draws' seed sequences."""
        from mawdo.minimize import minimize

        plan = RoutePlan(route, pos, t0, state, self.limits, self.sc.robot_speed)
        if len(plan.V) < 2 or plan.seed_steps < 2:
            return None
        cost = _Cost(plan, self, mv)
        if plan.dim == 0:
            x = np.zeros(0)
        else:
            rng = np.random.default_rng(seeds[1])
            fixed = _starts(plan)
            x0 = np.vstack([fixed, rng.uniform(0.0, 1.0, (POP - len(fixed), plan.dim))])
            box = (np.zeros(plan.dim), np.ones(plan.dim))
            res = minimize(cost, lb=box[0], ub=box[1], algorithm=self.optimizer,
                           seed=seeds[0], max_iter=ITERS, x0=x0)  # fmt: skip
            x = res.x[0]
        _, P, _ = self.repaired(x, plan, mv)
        if P is None or not self._verified(P, plan, mv):
            return None
        from mawdo.planning.guide.sipp.guide import TimedRoute

        self.refined += 1
        return TimedRoute(
            P, plan.t0 + np.arange(len(P), dtype=float), route.states, route.checked_until
        )

    def _verified(self, P, plan: RoutePlan, mv) -> bool:
        """Strictly earlier than the route, free of every break, driven as planned by the run
        (:func:`replay`), and passed by the guard's step test and the rule's route test."""
        if len(P) - 1 >= plan.seed_steps or self.breaks(P, plan, mv)[0]:
            return False
        if not replay(P, (plan.vel, plan.heading, plan.still), self.limits):
            return False
        t0 = float(plan.t0)
        for k in range(len(P) - 1):
            if self.guard.step_clearance(P[k], P[k + 1], t0 + k, 1.0) < self.clearance:
                return False
        times = t0 + np.arange(len(P), dtype=float)
        return self.ics is None or self.ics.path_safe(P, times, t0)
