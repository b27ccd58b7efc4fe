"""Display labels of algorithms and functions in benchmark tables and figures."""

from __future__ import annotations

from mawdo.functions import FUNCTIONS
from mawdo.optimizers import OPTIMIZERS


def label(algorithm: str) -> str:
    """Display label of an algorithm ("MEWDO (reconstructed)" for reconstructions)."""
    try:
        return OPTIMIZERS[algorithm].display
    except KeyError:
        return algorithm


def function_label(function: str) -> str:
    """Paper id (``F7``) of a suite function, else its name."""
    try:
        pid = FUNCTIONS[function].paper_id
    except KeyError:
        pid = None
    return pid or function
