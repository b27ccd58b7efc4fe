"""A comfort term for the refinement: passing close to a moving agent costs, not only hitting it.

The paper's cost (Eq. 24, :mod:`mawdo.planning.refine.cost`) ranks every collision-free path by
length and turning alone: a path that brushes past a person at the planner's clearance costs
the same as one that leaves them room. People mind how close a robot passes (CrowdNav counts a
step within 0.2 m of a person as discomfort). An exact graph search minimises length; a cost
that weighs length against room is where a population optimizer is the right tool. The added
term is

``C' = C + w n_near``

where ``n_near`` counts the (segment, moving agent) pairs whose segment comes within
``r + clearance + comfort`` of the agent while the robot drives it (the hit test of Eq. 27,
exact in space and time, with the margin widened by ``comfort``; the map's border and the
static obstacles do not count), and ``w`` is the weight of one such pair in the cost's own
units: ``w = alpha * comfort_weight``, i.e. ``comfort_weight`` pixels of route length. A
collision still outweighs any number of near passes on the maps the default weights are made
for (``beta k`` against ``alpha (C1 + comfort_weight * n_near)``, see
:class:`~mawdo.planning.refine.cost.CostWeights`).
"""

from __future__ import annotations

import math

import numpy as np

from mawdo.planning.refine.cost import PathCost

__all__ = ["ComfortPathCost"]


class ComfortPathCost(PathCost):
    """:class:`~mawdo.planning.refine.cost.PathCost` plus ``alpha * comfort_weight * n_near``.

    Parameters
    ----------
    scenario, mode, weights, n_waypoints, clearance, threads, horizon
        As for :class:`~mawdo.planning.refine.cost.PathCost` (the horizon bounds the near
        passes too).
    comfort : float
        Room (px, > 0) beyond the robot radius and the clearance that a passing robot should
        leave a moving agent.
    comfort_weight : float
        What one near (segment, agent) pair costs, in pixels of route length (>= 0).

    Notes
    -----
    ``parts`` still returns the paper's three terms; only the total cost (what the optimizer
    minimises and the planner ranks by) carries the comfort term.
    """

    def __init__(
        self, scenario, mode: str = "spacetime", weights=None, n_waypoints: int = 20,
        clearance: float = 0.0, threads: int = 1, *, comfort: float, comfort_weight: float,
        horizon: float | None = None,
    ) -> None:  # fmt: skip
        super().__init__(scenario, mode, weights, n_waypoints, clearance, threads, horizon=horizon)
        if not (math.isfinite(comfort) and comfort > 0):
            raise ValueError(f"comfort must be finite and > 0 px, got {comfort!r}")
        if not (math.isfinite(comfort_weight) and comfort_weight >= 0):
            raise ValueError(f"comfort_weight must be finite and >= 0 px, got {comfort_weight!r}")
        self.comfort, self.comfort_weight = float(comfort), float(comfort_weight)
        movers = [scenario.obstacles[i] for i in scenario.moving_indices]
        self._near = None
        if movers:
            self._near = PathCost(
                scenario, mode, weights, n_waypoints, clearance + self.comfort, threads,
                obstacles=movers, border=False, horizon=horizon,
            )  # fmt: skip
        self._per_pair = float(self.weights.alpha) * self.comfort_weight

    def near_pairs(self, X, start=None, t0: float = 0.0):
        """``n_near`` of each candidate (int64, shape ``(n,)``; an int for one candidate)."""
        if self._near is None:  # no movers: nothing to pass near
            n = np.zeros(len(np.atleast_2d(X)), dtype=np.int64)
            return n[0] if np.ndim(X) == 1 else n
        return self._near.parts(X, start, t0)[1]

    def _evaluate(self, X, start, t0, goal=None):
        cost, length, ncol, turn = super()._evaluate(X, start, t0, goal)
        if self._near is not None and self._per_pair > 0.0:
            near = self._near._evaluate(X, start, t0, goal)[2]
            cost = cost + self._per_pair * near
        return cost, length, ncol, turn
