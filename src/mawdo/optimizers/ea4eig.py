"""EA4eig (Bujok & Kolenovsky, CEC 2022): four cooperating algorithms with eigen crossover.

Batched over runs and individuals, following the authors' MATLAB code as distributed by Kudela
(``alg_EA4eig.m``, a function wrapper around Bujok's CEC 2022 script). Each generation a
roulette picks, per run, one of four algorithms with probability proportional to its successes
``n_k`` (each starts at 2; all are reset to 2 when the smallest share falls under 1/20), and that
algorithm makes one generation of ``N`` trials:

1. **CoBiDE**: rand/1 with each member's bimodal ``(F_i, CR_i)`` (Cauchy at 0.65 or 1; at 0.1 or
   0.95), drawn again for a member whose trial fails.
2. **IDE** (individual-dependent DE): the population ranked, ``F`` and ``CR`` drawn around the
   member's rank ``i / N``, the superior share ``0.1 + 0.9 x 10^(5 (g / g_max - 1))``, a
   perturbed third donor, and a two-stage switch driven by the success rate.
3. **CMA-ES**: one generation of ``N`` samples around the weighted mean of the best half; each
   sample replaces the population's worst member when it is better.
4. **jSO**: current-to-pBest-w/1 with the success-history memories and an archive.

CoBiDE, IDE and jSO cross over in the eigenvector basis of the best half's covariance with
probability 0.4 per generation. The population shrinks linearly from 100 to 10 over the budget.
Every algorithm makes ``N`` evaluations per generation, so every run counts the same
evaluations and the runs shrink in lock-step. Departures (the boundary reflection, the draws'
laws, a negative CMA-ES eigenvalue): docs/deviations.md#d-ea4eig.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass

import numpy as np

from mawdo.optimizers import ea4eig_heuristics as heur
from mawdo.optimizers import ea4eig_ops as ops
from mawdo.optimizers.base import Space, option
from mawdo.optimizers.lshade import ShrinkingDE, ShrinkingParams
from mawdo.optimizers.shade_ops import c_round, lpsr_size
from mawdo.streams import RunStreams

N_MIN = 10  # Nmin
N_ZERO = 2  # n0, each algorithm's success count after a reset
HEURISTICS = ("cobide", "ide", "cmaes", "jso")


@dataclass(frozen=True)
class EA4eigParams(ShrinkingParams):
    """EA4eig's settings (the authors'); ``pop_size`` and ``auto_pop_size`` (the authors' 100
    in every dimension): :class:`~mawdo.optimizers.lshade.ShrinkingParams`.

    Parameters
    ----------
    p_eig : float
        Probability that a CoBiDE, IDE or jSO generation crosses over in the eigenvector
        basis, in [0, 1] (0.4).
    eig_share : float
        Share of the population (the best) whose covariance gives the basis, in (0, 1] (0.5).
    memory_size : int
        jSO's memory entries H, >= 2 (5; the last stays at 0.9, 0.9).
    arc_rate : float
        jSO's archive size as a multiple of the population size, >= 0 (2.6).
    """

    p_eig: float = option(0.4, lo=0, hi=1)
    eig_share: float = option(0.5, lo=0, hi=1, lo_open=True)
    memory_size: int = option(5, lo=2)
    arc_rate: float = option(2.6, lo=0)


def next_size(nfes: int, max_nfes: int, n: int, n_init: int) -> int:
    """The population size after a generation that ended at ``nfes`` (sizes only fall)."""
    return min(n, lpsr_size(nfes, max_nfes, n_init, N_MIN))


@dataclass
class EA4eigState:
    """Every run's arrays (``R`` runs, ``N`` members, ``D``); scalars shared by the batch."""

    X: np.ndarray  # (R, N, D) population
    F: np.ndarray  # (R, N)
    CBF: np.ndarray  # (R, N) CoBiDE's F and CR of each member (kept in member order)
    CBCR: np.ndarray
    ni: np.ndarray  # (R, 4) success counts of the roulette
    g: np.ndarray  # (R,) IDE: its generations so far, the stage switch gt, the failure streak
    gt: np.ndarray
    t_fail: np.ndarray
    sigma: np.ndarray  # (R,) CMA-ES
    B: np.ndarray  # (R, D, D)
    Dd: np.ndarray  # (R, D)
    C: np.ndarray  # (R, D, D)
    inv_sqrt_c: np.ndarray  # (R, D, D)
    pc: np.ndarray  # (R, D)
    ps: np.ndarray
    eigeneval: np.ndarray  # (R,)
    old_pop: np.ndarray  # (R, N_old, D) the last CMA-ES samples (mirroring's reference)
    MF: np.ndarray  # (R, H) jSO
    MCR: np.ndarray
    k: np.ndarray  # (R,)
    archive: np.ndarray  # (R, cap, D)
    n_arc: np.ndarray  # (R,)
    arc_size: int
    mu: int  # CMA-ES recombination, shared (N is)
    weights: np.ndarray
    mueff: float
    cma: dict  # CMA-ES constants, set once
    nfes: int
    max_nfes: int
    n_init: int
    gmax: int  # IDE's generation scale and streak threshold
    t_limit: float
    space: Space
    streams: RunStreams
    gen: dict = dataclasses.field(default_factory=dict)  # this generation's choice and draws


class EA4eig(ShrinkingDE):
    """EA4eig, vectorised over runs and individuals; see the module docstring."""

    name = "ea4eig"
    params_class = EA4eigParams
    next_size = staticmethod(next_size)

    def auto_size(self, dim: int) -> int:
        return 100

    def init(self, space: Space, streams: RunStreams, max_iter: int, x0=None) -> EA4eigState:
        """``max_iter`` is the evaluation budget ``M`` from :meth:`horizon`."""
        p, R, D = self.params, streams.runs, space.dim
        X = self.start(space, streams, x0)
        n0 = X.shape[1]
        u_fc, u_fv, u_cc, u_cv = streams.random_parts((n0,), (n0,), (n0,), (n0,))
        mu, w, mueff = ops.cma_weights(n0 / 2)
        H, arc = p.memory_size, c_round(n0 * p.arc_rate)
        gmax = c_round(max(int(max_iter), 1) / n0)
        eye = np.broadcast_to(np.eye(D), (R, D, D))
        MF, MCR = np.full((R, H), 0.3), np.full((R, H), 0.8)
        MF[:, -1] = MCR[:, -1] = 0.9
        return EA4eigState(
            X=X, F=np.full((R, n0), np.inf),
            CBF=ops.cobide_f(u_fc, u_fv), CBCR=ops.cobide_cr(u_cc, u_cv),
            ni=np.full((R, 4), float(N_ZERO)),
            g=np.zeros(R, np.int64), gt=np.full(R, gmax // 2), t_fail=np.zeros(R, np.int64),
            sigma=np.full(R, (space.ub[0] - space.lb[0]) / 2.0), B=eye.copy(),
            Dd=np.ones((R, D)), C=eye.copy(), inv_sqrt_c=eye.copy(),
            pc=np.zeros((R, D)), ps=np.zeros((R, D)), eigeneval=np.zeros(R), old_pop=X.copy(),
            MF=MF, MCR=MCR, k=np.zeros(R, np.int64),
            archive=np.zeros((R, max(arc, 1), D)), n_arc=np.zeros(R, np.int64), arc_size=arc,
            mu=mu, weights=w, mueff=mueff, cma=ops.cma_constants(mueff, D),
            nfes=0, max_nfes=max(int(max_iter), 1), n_init=n0, gmax=gmax, t_limit=gmax / 10.0,
            space=space, streams=streams,
        )  # fmt: skip

    def ask(self, state: EA4eigState) -> np.ndarray:
        """The initial population, then one generation of ``N`` trials per run ``(R, N, D)``,
        each run's from the algorithm its roulette picked."""
        if state.nfes == 0:
            return state.X
        u = state.streams.random(())
        h, p_min = ops.roulette(state.ni, u)
        state.ni[p_min < 1.0 / (5 * len(HEURISTICS))] = N_ZERO  # after the pick, as coded
        trial = np.empty_like(state.X)
        state.gen = {"u_roulette": u, "h": h}
        for k, name in enumerate(HEURISTICS):
            rows = np.flatnonzero(h == k)
            if rows.size:
                sub = state.streams.subset(rows)
                trial[rows], state.gen[name] = getattr(heur, f"{name}_ask")(self, state, rows, sub)
                state.gen[name]["rows"] = rows
        state.gen["trial"] = trial
        return trial

    def tell(self, state: EA4eigState, X: np.ndarray, F: np.ndarray) -> EA4eigState:
        if self.told_initial(state, F):
            return state
        N = state.X.shape[1]
        for name in HEURISTICS:
            gen = state.gen.get(name)
            if gen is not None:
                rows = gen["rows"]
                getattr(heur, f"{name}_tell")(self, state, rows, state.gen["trial"][rows], F[rows])
        state.nfes += N
        self._reduce(state)
        return state

    def _reduce(self, state: EA4eigState) -> None:
        """Linear size reduction toward 10, as coded: whenever the plan is below the size, the
        population is sorted (even when the floor keeps its size), cut, the archive trimmed by
        random removals, and the CMA-ES weights set for ``floor(N / 2)``."""
        N, M = state.X.shape[1], state.max_nfes
        plan = c_round(((N_MIN - state.n_init) / float(M)) * state.nfes + state.n_init)
        if N <= plan:
            return
        new = max(plan, N_MIN)
        order = np.argsort(state.F, axis=1, kind="stable")[:, :new]
        state.X = np.take_along_axis(state.X, order[..., None], 1)
        for name in ("F", "CBF", "CBCR"):
            setattr(state, name, np.take_along_axis(getattr(state, name), order, 1))
        state.arc_size = c_round(new * self.params.arc_rate)
        self._trim_archive(state)
        state.mu, state.weights, state.mueff = ops.cma_weights(math.floor(new / 2))

    @staticmethod
    def _trim_archive(state: EA4eigState) -> None:
        """``while Asize > Asize_max``: remove a uniformly chosen member (the rest keep their
        order); each run draws as many uniforms as it removes members."""
        for r in np.flatnonzero(state.n_arc > state.arc_size):
            n = int(state.n_arc[r])
            u = state.streams.subset([r]).random((n - state.arc_size,))[0]
            members = list(range(n))
            for x in u:
                del members[ops.index_in(x, len(members))]
            state.archive[r, : len(members)] = state.archive[r, members]
            state.n_arc[r] = len(members)
            state.gen.setdefault("trim", {})[int(r)] = u
