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
CMA-ES is the maintained ``cmaes`` library (CyberAgentAILab), not our own.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from mawdo.optimizers.base import Space
from mawdo.optimizers.cmaes_ref import ask_generation
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

    cma_sigma: float = 0.5


@dataclass
class AWDOCMAState(WindState):
    cmas: list | None = None
    arx: np.ndarray | None = None  # (R, N, 4) coefficients in use


class AWDOCMA(Wind):
    """AWDO, ``variant="cmaes"``: per-parcel coefficients from a CMA-ES per run."""

    name = "awdo_cmaes"
    params_class = AWDOCMAParams

    def init(self, space: Space, streams: RunStreams, max_iter: int, x0=None) -> AWDOCMAState:
        try:
            from cmaes import CMA
        except ImportError as exc:  # pragma: no cover - cmaes is a hard dependency
            raise ImportError("AWDO variant 'cmaes' needs the 'cmaes' package") from exc
        base = super().init(space, streams, max_iter, x0)
        N = self.params.pop_size
        # AWDO_v03.m: rec.arx = rand(4, popsize) moves the parcels once before the CMA-ES starts;
        # the CMA-ES's own initial mean is a separate U[0,1]^4 draw (rec.xmean = rand(4, 1)).
        arx = streams.random((N, 4))
        means = streams.random((4,))
        seeds = streams.integers(2**31 - 1)
        cmas = [
            CMA(mean=means[r], sigma=self.params.cma_sigma, population_size=N, seed=int(seeds[r]))
            for r in range(streams.runs)
        ]
        return AWDOCMAState(**base.__dict__, cmas=cmas, arx=arx)

    def _coefficients(self, s: AWDOCMAState):
        return tuple(s.arx[..., k : k + 1] for k in range(4))

    def tell(self, state: AWDOCMAState, X: np.ndarray, F: np.ndarray) -> AWDOCMAState:
        first = state.t == 0
        state = super().tell(state, X, F)
        if first:  # the initial population used no coefficients: the U[0,1] arx moves it first
            return state
        # The pressures of the move just made score the coefficient samples that made it (for the
        # first CMA-ES update these are the U[0,1] draws, as in AWDO_v03.m), then new samples.
        f = state.f
        for r, cma in enumerate(state.cmas):
            fr = f[r]
            finite = np.isfinite(fr)
            if not finite.all():
                worst = fr[finite].max() + 1.0 if finite.any() else 1.0
                fr = np.where(finite, fr, worst)
            cma.tell(list(zip(state.arx[r], fr.tolist(), strict=True)))
        # the same samples as N calls of cma.ask(), drawn as one generation
        state.arx = np.stack([ask_generation(cma, state.arx.shape[1]) for cma in state.cmas])
        return state
