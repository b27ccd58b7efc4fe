"""A collision-risk term for the refinement: under predicted motion a route's danger is a
probability, not a yes/no.

An observing planner (:mod:`mawdo.planning.sense`) plans among predicted agents whose discs are
grown by an uncertainty margin held over a short look-ahead
(:func:`~mawdo.planning.sense.predict.tube_radius`). The hit test of Eq. 27 says whether a route
enters those discs; it cannot say that passing a person two seconds from now, where the
prediction is vague, is riskier than passing one who stands still, nor weigh that risk against
arrival time. An exact graph search minimises length; a cost that trades length against a
probability is where a population optimizer is the right tool. The added term is

``C' = C + w E``,  ``E = sum_k sum_a P(|x(t_k) - c_a(t_k)| < r + r_a)``          (risk)

* ``x(t_k)``: the robot's centre at the time steps ``t_k = t0 + k``, ``k = 1 .. K``, while it
  drives the path (it leaves ``start`` at ``t0`` and moves at its speed ``v``, as in the
  spacetime cost); ``K`` is the term's reach (and the cost's horizon where one is set);
* ``c_a(t_k) ~ N(mu_a(t_k), s_a(t_k)^2 I)``: agent ``a``'s centre, ``mu`` its predicted centre,
  ``s`` the per-axis s.d. bound of :func:`~mawdo.planning.world.uncertainty.centre_sd` at the
  look-ahead ``t_k`` (the scenario's :class:`~mawdo.planning.world.uncertainty.Uncertainty`);
* ``r + r_a``: the robot's radius and the agent's own (not the margin-grown disc's).

The probability that an isotropic 2-D Gaussian point of s.d. ``s`` whose mean lies ``d`` from
the robot's centre falls within ``R`` of it is the Rice distribution's CDF,
``P = 1 - Q_1(d / s, R / s)``, i.e. the non-central chi-square CDF with 2 degrees of freedom
and non-centrality ``(d / s)^2`` at ``(R / s)^2`` (:func:`overlap_probability`). ``E`` is the
expected number of (step, agent) contacts while the robot drives, and ``w = alpha *
risk_weight``: ``risk_weight`` pixels of route length per expected contact.

The planner evaluates ``E`` for whole populations in a compiled kernel
(:mod:`mawdo.planning.refine.kernel.risk`), which reads the CDF from a table made once from
scipy's exact one (within 4e-4 of it; the tests compare the two), so that a call for 240
candidates, 40 steps and 5 people costs about 0.6 ms.
"""

from __future__ import annotations

import functools
import math

import numpy as np
from scipy.special import chndtr

from mawdo.planning.refine.cost import PathCost
from mawdo.planning.refine.kernel.risk import X_HI, expected_contacts, rice_table

__all__ = ["RISK_REACH", "RiskPathCost", "overlap_probability"]

#: Time steps ahead (default) over which the risk is summed: beyond them the predicted spread
#: is so wide that the probabilities are small and nearly the same for every route.
RISK_REACH = 40
#: Standard deviations beyond the contact distance at which a probability is taken as 0
#: (the Rice CDF there is below 1e-7): the compiled table's own edge.
TAIL = X_HI


def overlap_probability(distance, reach, sd) -> np.ndarray:
    """Probability that a point with isotropic Gaussian uncertainty lies within ``reach``.

    Parameters
    ----------
    distance : array_like
        Distance (pixels, >= 0) from the point's mean to the centre of the disc.
    reach : array_like
        Radius of the disc (pixels, > 0): the robot's and the agent's radii together.
    sd : array_like
        Per-axis s.d. of the point (pixels, >= 0); 0 is certainty (1 inside, 0 outside).

    Returns
    -------
    numpy.ndarray
        ``P`` in [0, 1], the arrays broadcast together: the Rice CDF ``1 - Q_1(d / s, R / s)``
        (0 where ``d > R + 6 s``).
    """
    d, r, s = np.broadcast_arrays(*(np.asarray(a, dtype=float) for a in (distance, reach, sd)))
    out = np.zeros(d.shape)
    exact = s <= 0.0
    out[exact] = d[exact] < r[exact]
    near = ~exact & (d < r + TAIL * s)
    if near.any():
        sn = s[near]
        out[near] = chndtr((r[near] / sn) ** 2, 2.0, (d[near] / sn) ** 2)
    return np.clip(out, 0.0, 1.0)


@functools.cache
def _table() -> np.ndarray:
    """The Rice CDF table of the compiled sum, made once per process (about 0.05 s)."""
    return rice_table()


def _point(p) -> np.ndarray:
    return np.ascontiguousarray(np.asarray(p, dtype=np.float64).reshape(2))


class RiskPathCost(PathCost):
    """:class:`~mawdo.planning.refine.cost.PathCost` plus ``alpha * risk_weight * E``.

    Parameters
    ----------
    scenario, mode, weights, n_waypoints, clearance, threads, horizon
        As for :class:`~mawdo.planning.refine.cost.PathCost`; ``mode`` must be
        ``"spacetime"`` (a risk needs the robot's timing). The horizon, where set, also bounds
        the steps the risk is summed over.
    risk_weight : float
        What one expected contact costs, in pixels of route length (>= 0).
    risk_reach : int
        Time steps ahead the risk is summed over (>= 1; default :data:`RISK_REACH`).
    **others
        Passed on (another term's options when combined with one, e.g. the comfort term's).

    Notes
    -----
    The term needs the scenario's ``uncertainty`` (a prediction scenario of an observing
    planner); without it the cost is the parent's. ``parts`` still returns the paper's three
    terms; only the total cost carries the risk.
    """

    def __init__(
        self, scenario, mode: str = "spacetime", weights=None, n_waypoints: int = 20,
        clearance: float = 0.0, threads: int = 1, *, risk_weight: float,
        risk_reach: int = RISK_REACH, horizon: float | None = None, **others,
    ) -> None:  # fmt: skip
        if mode != "spacetime":
            raise ValueError(
                f"the risk term needs mode='spacetime' (the robot's timing), got {mode!r}"
            )
        super().__init__(
            scenario, mode, weights, n_waypoints, clearance, threads, horizon=horizon, **others
        )  # fmt: skip
        if not (math.isfinite(risk_weight) and risk_weight >= 0):
            raise ValueError(f"risk_weight must be finite and >= 0 px, got {risk_weight!r}")
        if not (isinstance(risk_reach, int | np.integer) and risk_reach >= 1):
            raise ValueError(f"risk_reach must be an integer >= 1 time step, got {risk_reach!r}")
        self.risk_weight = float(risk_weight)
        steps = int(risk_reach)
        if horizon is not None:
            steps = max(1, min(steps, math.ceil(horizon)))
        self._ahead = np.arange(1.0, steps + 1.0)
        self._spread = scenario.uncertainty
        self._per_contact = float(self.weights.alpha) * self.risk_weight
        self._agents: tuple | None = None  # (t0, centres (k, a, 2), sd (k, a), reach (a,))

    def expected_contacts(self, X, start=None, t0: float = 0.0, goal=None):
        """``E`` of each candidate (shape ``(n,)``; a float for one candidate): the expected
        number of (step, agent) contacts while the robot drives the path."""
        X = np.asarray(X, dtype=float)
        X2 = np.atleast_2d(X)
        e = self._contacts(X2, start, float(t0), goal)
        return float(e[0]) if X.ndim == 1 else e

    def _contacts(self, X2, start, t0: float, goal) -> np.ndarray:
        out = np.zeros(len(X2))
        if self._spread is None or not len(self._spread) or not len(X2):
            return out
        start = _point(self.scenario.start if start is None else start)
        goal = _point(self.scenario.goal if goal is None else goal)
        centres, sd, reach = self._agents_at(t0)
        X2 = np.ascontiguousarray(X2, dtype=np.float64)
        expected_contacts(X2, start, goal, self._speed, centres, reach, sd, _table(), out)
        return out

    def _agents_at(self, t0: float) -> tuple:
        """The agents' predicted centres, s.d.s and contact distances at ``t0 + ahead``,
        kept for the next call with the same ``t0`` (an optimizer calls many times)."""
        if self._agents is None or self._agents[0] != t0:
            spread = self._spread
            times = t0 + self._ahead
            obstacles = [self.scenario.obstacles[i] for i in spread.index]
            centres = np.stack(
                [np.asarray(o.shape.center) + o.offset(times) for o in obstacles], axis=1
            )
            reach = spread.radius + float(self.scenario.robot_radius)
            sd = np.ascontiguousarray(spread.sd(times))
            self._agents = (t0, np.ascontiguousarray(centres, dtype=np.float64), sd, reach)
        return self._agents[1:]

    def _evaluate(self, X, start, t0, goal=None):
        cost, length, ncol, turn = super()._evaluate(X, start, t0, goal)
        if self._per_contact > 0.0 and self._spread is not None and len(self._spread):
            X = np.asarray(X, dtype=float)
            e = self._contacts(np.atleast_2d(X), start, float(t0), goal)
            cost = cost + self._per_contact * (e[0] if X.ndim == 1 else e)
        return cost, length, ncol, turn
