"""Whale Optimization Algorithm (Mirjalili & Lewis, Adv. Eng. Softw. 95, 2016; ``WOA.m``).

Iteration ``t = 1..T``: evaluate, update the leader ``X*`` (best-so-far), then for every whale
with its own scalars ``r1, r2, p ~ U(0,1)`` and ``l``:

    a = 2 - 2 (t - 1) / T,  A = 2 a r1 - a,  C = 2 r2                      (Eqs. 2.3-2.4)
    p <  0.5, |A| <  1:  X <- X* - A |C X* - X|                            (Eqs. 2.1-2.2, encircle)
    p <  0.5, |A| >= 1:  X <- X_rand - A |C X_rand - X|                    (Eqs. 2.7-2.8, search)
    p >= 0.5:            X <- |X* - X| e^{b l} cos(2 pi l) + X*,  b = 1     (Eq. 2.5, spiral)

then clipped to the box. ``l ~ U(-1, 1)`` as in the paper, or ``l = (a2 - 1) r + 1`` with
``a2 = -1 - (t - 1)/T`` as in ``WOA.m`` (``l_range="matlab"``).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from mawdo.optimizers.base import Optimizer, Params, Space, check_choice, initial_population
from mawdo.streams import RunStreams


@dataclass(frozen=True)
class WOAParams(Params):
    """WOA coefficients.

    Parameters
    ----------
    pop_size : int
        Whales per run, >= 2.
    b : float
        Spiral shape constant (1 in the paper).
    l_range : {"paper", "matlab"}
        ``"paper"``: ``l ~ U(-1, 1)``. ``"matlab"``: ``l ~ U(a2, 1)`` with ``a2`` falling from -1 to
        -2 over the run, as in ``WOA.m``.
    """

    b: float = 1.0
    l_range: str = "paper"

    def __post_init__(self) -> None:
        super().__post_init__()
        check_choice("l_range", self.l_range, ("paper", "matlab"))


def woa_move(X, leader, X_rand, a, r1, r2, p, l, b):
    """Eqs. 2.1-2.8 for all whales at once.

    Shapes: ``X (R, N, D)``, ``leader (R, D)``, ``X_rand (R, N, D)`` (the random whale of each
    whale), ``r1, r2, p, l`` per whale ``(R, N)``; ``a`` scalar.
    """
    A = (2.0 * a * r1 - a)[..., None]
    C = (2.0 * r2)[..., None]
    Ls = leader[:, None, :]
    encircle = Ls - A * np.abs(C * Ls - X)
    search = X_rand - A * np.abs(C * X_rand - X)
    lw = l[..., None]
    spiral = np.abs(Ls - X) * np.exp(b * lw) * np.cos(2.0 * np.pi * lw) + Ls
    shrink = np.where(np.abs(A) < 1.0, encircle, search)
    return np.where((p < 0.5)[..., None], shrink, spiral)


@dataclass
class WOAState:
    X: np.ndarray
    leader_f: np.ndarray
    leader_x: np.ndarray
    t: int
    T: int
    space: Space
    streams: RunStreams


class WOA(Optimizer):
    """Whale Optimization Algorithm, vectorised over runs and whales; see the module docstring."""

    name = "woa"
    params_class = WOAParams

    def init(self, space: Space, streams: RunStreams, max_iter: int, x0=None) -> WOAState:
        N, D, R = self.params.pop_size, space.dim, streams.runs
        X = initial_population(streams, N, space.lb, space.ub, x0)
        return WOAState(
            X=X,
            leader_f=np.full(R, np.inf),
            leader_x=np.zeros((R, D)),
            t=0,
            T=max_iter,
            space=space,
            streams=streams,
        )

    def ask(self, state: WOAState) -> np.ndarray:
        if state.t > 0:
            N = state.X.shape[1]
            frac = (state.t - 1) / state.T
            a = 2.0 - 2.0 * frac
            u = state.streams.random((5, N))  # r1, r2, p, l, rand-whale
            r1, r2, p, ul, ur = (u[:, k] for k in range(5))
            if self.params.l_range == "paper":
                l = 2.0 * ul - 1.0
            else:
                a2 = -1.0 - frac
                l = (a2 - 1.0) * ul + 1.0
            idx = np.minimum((ur * N).astype(np.int64), N - 1)
            X_rand = np.take_along_axis(state.X, idx[..., None], axis=1)
            X = woa_move(state.X, state.leader_x, X_rand, a, r1, r2, p, l, self.params.b)
            state.X = np.clip(X, state.space.lb, state.space.ub)
        return state.X

    def tell(self, state: WOAState, X: np.ndarray, F: np.ndarray) -> WOAState:
        j = np.argmin(F, axis=1)
        fj = F[np.arange(F.shape[0]), j]
        better = fj < state.leader_f
        state.leader_f = np.where(better, fj, state.leader_f)
        state.leader_x[better] = X[better, j[better]]
        state.t += 1
        return state
