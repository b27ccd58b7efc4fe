"""The refinement's cost with the terms a planner asks for: the paper's cost (Eq. 24), plus
the comfort term (:mod:`mawdo.planning.refine.comfort`) and the collision-risk term
(:mod:`mawdo.planning.refine.risk`), alone or together."""

from __future__ import annotations

from mawdo.planning.refine.comfort import ComfortPathCost
from mawdo.planning.refine.cost import PathCost
from mawdo.planning.refine.risk import RiskPathCost

__all__ = ["ComfortRiskPathCost", "cost_class"]


class ComfortRiskPathCost(RiskPathCost, ComfortPathCost):
    """Both added terms: ``C + alpha (comfort_weight n_near + risk_weight E)``; the options of
    :class:`~mawdo.planning.refine.comfort.ComfortPathCost` and
    :class:`~mawdo.planning.refine.risk.RiskPathCost` together."""


def cost_class(**terms) -> type[PathCost]:
    """The cost class whose keyword options are ``terms``: ``comfort`` (and
    ``comfort_weight``) for the comfort term, ``risk_weight`` (and ``risk_reach``) for the
    risk term, neither for the paper's cost."""
    comfort, risk = "comfort" in terms, "risk_weight" in terms
    if comfort and risk:
        return ComfortRiskPathCost
    if risk:
        return RiskPathCost
    return ComfortPathCost if comfort else PathCost
