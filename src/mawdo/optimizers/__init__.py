"""Optimizers: WDO family, GWO, WOA, MEWDO (reconstructed), all behind one registry."""

from mawdo.optimizers import catalog as _catalog  # noqa: F401  (registers every algorithm)
from mawdo.optimizers.base import Optimizer, Params, Space
from mawdo.optimizers.catalog import (
    ABLATION_ALGORITHMS,
    CEC_WINNERS,
    HOLDOUT_ALGORITHMS,
    OFFICIAL_ALGORITHMS,
    PAPER_ALGORITHMS,
)
from mawdo.optimizers.registry import OPTIMIZERS, AlgorithmSpec, make_optimizer

__all__ = [
    "ABLATION_ALGORITHMS",
    "CEC_WINNERS",
    "HOLDOUT_ALGORITHMS",
    "OFFICIAL_ALGORITHMS",
    "OPTIMIZERS",
    "PAPER_ALGORITHMS",
    "AlgorithmSpec",
    "Optimizer",
    "Params",
    "Space",
    "make_optimizer",
]
