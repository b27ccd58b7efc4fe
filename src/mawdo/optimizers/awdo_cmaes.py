"""AWDO with CMA-ES-adapted coefficients (Bayraktar & Komurcu 2015; authors' ``AWDO_v03.m``).

Each parcel carries its own coefficient vector ``(alpha, g, RT, c)``, one sample of a 4-D CMA-ES
per run whose population is the air population (``lambda = N``). The CMA-ES fitness of a sample is
the pressure of the parcel that used it, after it moved, so no extra evaluations are spent.

As in ``AWDO_v03.m``, the first move uses coefficients drawn from ``U[0, 1]`` (``rec.arx =
rand(4, popsize)``), and those draws, with the pressures they produced, are the first generation
the CMA-ES is told (``purecmaes_wdo`` is first called after the first move, with ``xmean =
rand(4, 1)``, ``sigma = 0.5``). From the second move on the coefficients are CMA-ES samples, which
can be negative or above 1: the reference does not bound them.

The velocity is WDO's (``|1 - 1/i|`` pressure weight, ``c/i`` Coriolis) with the true ranks; the
reference code indexes with the sort permutation instead (docs/deviations.md#d-awdo-cmaes). The
CMA-ES is the reference's own, ``purecmaes_wdo.m``, ported and batched over runs
(:mod:`mawdo.optimizers.purecmaes`); each run draws its samples from its own stream.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from mawdo.optimizers.base import Space, finite_last, option
from mawdo.optimizers.purecmaes import PureCMAES
from mawdo.optimizers.wdo import Wind, WindParams, WindState
from mawdo.streams import RunStreams


@dataclass(frozen=True)
class AWDOCMAParams(WindParams):
    """AWDO-CMA coefficients: WindParams plus the CMA-ES step size.

    Parameters
    ----------
    cma_sigma : float
        Initial CMA-ES step size over the coefficient vector (0.5 in ``AWDO_v03.m``).
    """

    cma_sigma: float = option(0.5, lo=0, lo_open=True)


@dataclass
class AWDOCMAState(WindState):
    es: PureCMAES | None = None  # one CMA-ES per run
    arx: np.ndarray | None = None  # (R, N, 4) coefficients in use


class AWDOCMA(Wind):
    """AWDO, ``variant="cmaes"``: per-parcel coefficients from a CMA-ES per run."""

    name = "awdo_cmaes"
    params_class = AWDOCMAParams

    def init(self, space: Space, streams: RunStreams, max_iter: int, x0=None) -> AWDOCMAState:
        base = super().init(space, streams, max_iter, x0)
        N = self.params.pop_size
        # AWDO_v03.m: rec.arx = rand(4, popsize) moves the parcels once before the CMA-ES starts;
        # the CMA-ES's own initial mean is a separate U[0,1]^4 draw (rec.xmean = rand(4, 1)).
        arx = streams.random((N, 4))
        es = PureCMAES.start(streams.random((4,)), self.params.cma_sigma, N)
        return AWDOCMAState(**base.__dict__, es=es, arx=arx)

    def _coefficients(self, s: AWDOCMAState):
        return tuple(s.arx[..., k : k + 1] for k in range(4))

    def tell(self, state: AWDOCMAState, X: np.ndarray, F: np.ndarray) -> AWDOCMAState:
        first = state.t == 0
        state = super().tell(state, X, F)
        if first:  # the initial population used no coefficients: the U[0,1] arx moves it first
            return state
        # The pressures of the move just made score the coefficient samples that made it (for the
        # first CMA-ES update these are the U[0,1] draws, as in AWDO_v03.m), then new samples.
        # (the source's counteval: the WDO iteration number, 2 after the first move)
        state.es.tell(state.arx, finite_last(state.f), counteval=state.t)
        state.arx = state.es.sample(state.streams.normal(state.arx.shape[1:]))
        return state
