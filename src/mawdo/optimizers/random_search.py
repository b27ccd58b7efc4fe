"""Uniform random search: the baseline every benchmarking study reports.

Each iteration draws ``pop_size`` points per run uniformly in the box from the run's own stream;
nothing is learned. Warm-start points (``x0``) are the first points of the first iteration.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from mawdo.optimizers.base import Optimizer, Params, Space, initial_population
from mawdo.streams import RunStreams


@dataclass(frozen=True)
class RandomSearchParams(Params):
    """Random-search coefficients.

    Parameters
    ----------
    pop_size : int
        Points per run and iteration, >= 2. It only sets how the budget is cut into batches
        (the result does not depend on it beyond that).
    """


@dataclass
class RandomSearchState:
    X: np.ndarray
    t: int
    space: Space
    streams: RunStreams


class RandomSearch(Optimizer):
    """Uniform random sampling in the box, vectorised over runs."""

    name = "random"
    params_class = RandomSearchParams

    def init(self, space: Space, streams: RunStreams, max_iter: int, x0=None) -> RandomSearchState:
        X = initial_population(streams, self.params.pop_size, space.lb, space.ub, x0)
        return RandomSearchState(X=X, t=0, space=space, streams=streams)

    def ask(self, state: RandomSearchState) -> np.ndarray:
        if state.t > 0:
            state.X = state.streams.uniform(
                state.space.lb, state.space.ub, (self.params.pop_size, state.space.dim)
            )
        return state.X

    def tell(self, state: RandomSearchState, X: np.ndarray, F: np.ndarray) -> RandomSearchState:
        state.t += 1
        return state
