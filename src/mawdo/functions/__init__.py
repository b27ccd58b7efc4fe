"""Benchmark functions F1-F16 of the paper's Table 2, the alternates, and the shift wrapper.

>>> from mawdo.functions import get_function
>>> f = get_function("F7", preset="standard")
>>> float(f(f.x_star)) == f.f_star
True
"""

from .base import BenchmarkFunction
from .registry import ALTERNATES, FUNCTIONS, PAPER_SUITE, get_function
from .shift import shifted

__all__ = ["ALTERNATES", "FUNCTIONS", "PAPER_SUITE", "BenchmarkFunction", "get_function", "shifted"]
