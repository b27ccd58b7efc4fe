"""Grey Wolf Optimizer (Mirjalili, Mirjalili & Lewis, Adv. Eng. Softw. 69, 2014; ``GWO.m``).

Iteration ``t = 1..T``: evaluate the pack, update the leaders alpha, beta, delta (best-so-far),
then move every wolf:

    a = 2 - 2 (t - 1) / T                  (GWO.m: a = 2 - l*2/Max_iter, l = t - 1)
    A_k = 2 a r1 - a,  C_k = 2 r2           (Eqs. 3.3-3.4; fresh r1, r2 per leader, wolf, dim)
    D_k = |C_k X_k - X|,  X_k' = X_k - A_k D_k      (Eqs. 3.5-3.6, k = alpha, beta, delta)
    X <- (X_alpha' + X_beta' + X_delta') / 3        (Eq. 3.7), then clipped to the box.

No greedy selection: every wolf moves.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numba import njit

from mawdo.optimizers.base import Optimizer, Params, Space, initial_population
from mawdo.optimizers.kernels import gwo_step, seed_xoshiro
from mawdo.streams import RunStreams

_NO_RNG = np.ones((1, 4), np.uint64)
_NO_R = np.zeros((1, 2, 3, 1, 1))


@dataclass(frozen=True)
class GWOParams(Params):
    """GWO coefficients.

    Parameters
    ----------
    pop_size : int
        Wolves per run, >= 2 (30 in the GWO paper, 50 in the MAWDO study).
    demote_leaders : bool
        False (default) keeps ``GWO.m``'s leader update: a new alpha does not push the old alpha
        down to beta. True demotes (alpha -> beta -> delta), as many later codes do.
    """

    demote_leaders: bool = False


@njit(cache=True, nogil=True)
def leaders_in_place(lead_f, lead_x, F, X):  # pragma: no cover - compiled
    """``GWO.m``'s leader update, literally, in place on ``lead_f (R, 3)``, ``lead_x (R, 3, D)``.

    ``GWO.m`` scans the wolves in order with strict comparisons::

        if f < alpha: alpha = f
        if f > alpha and f < beta: beta = f
        if f > alpha and f > beta and f < delta: delta = f

    ``F (R, N)`` (no NaN), ``X (R, N, D)``. Each leader's position is copied once, from the last
    wolf that set it in this scan.
    """
    R, N, D = X.shape
    who = np.empty(3, np.intp)
    for r in range(R):
        a, b, d = lead_f[r, 0], lead_f[r, 1], lead_f[r, 2]
        who[:] = -1
        for i in range(N):
            f = F[r, i]
            if f < a:
                a, who[0] = f, i
            if f > a and f < b:
                b, who[1] = f, i
            if f > a and f > b and f < d:
                d, who[2] = f, i
        lead_f[r, 0], lead_f[r, 1], lead_f[r, 2] = a, b, d
        for k in range(3):
            if who[k] >= 0:
                for j in range(D):
                    lead_x[r, k, j] = X[r, who[k], j]


def update_leaders_reference(lead_f, lead_x, F, X):
    """Leader update of ``GWO.m`` (:func:`leaders_in_place`) on copies: returns the new
    ``(lead_f (R, 3), lead_x (R, 3, D))`` from this iteration's scores ``F (R, N)`` and
    positions ``X (R, N, D)``."""
    new_f, new_x = lead_f.astype(float), lead_x.astype(float)
    leaders_in_place(new_f, new_x, np.asarray(F, float), np.asarray(X, float))
    return new_f, new_x


def update_leaders_demoting(lead_f, lead_x, F, X):
    """Leaders = the three best distinct-by-rank points among old leaders and this pack."""
    allf = np.concatenate([lead_f, F], axis=1)
    allx = np.concatenate([lead_x, X], axis=1)
    order = np.argsort(allf, axis=1, kind="stable")[:, :3]
    return np.take_along_axis(allf, order, 1), np.take_along_axis(allx, order[..., None], 1)


def gwo_move(X, lead_x, a, r1, r2):
    """Eqs. 3.3-3.7: the new pack from the leaders ``lead_x`` ``(R, 3, D)``.

    ``r1, r2`` have shape ``(R, 3, N, D)`` (one draw per leader, wolf and dimension); ``a`` is a
    scalar or ``(R,)``.
    """
    a = np.asarray(a, float).reshape(-1, 1, 1) if np.ndim(a) else a
    out = np.zeros_like(X)
    for k in range(3):  # in-place per leader: avoids (R, 3, N, D) temporaries
        L = lead_x[:, k, None, :]
        A = r1[:, k] * (2.0 * a)
        A -= a  # A = 2 a r1 - a
        Dist = np.multiply(r2[:, k], 2.0 * L)  # C L with C = 2 r2
        Dist -= X
        np.abs(Dist, out=Dist)
        Dist *= A
        out += L
        out -= Dist  # X_k = L - A |C L - X|
    out /= 3.0
    return out


@dataclass
class GWOState:
    X: np.ndarray
    lead_f: np.ndarray
    lead_x: np.ndarray
    t: int
    T: int
    space: Space
    streams: RunStreams
    rng: np.ndarray | None = None  # (R, 4) xoshiro256** state per run, seeded from streams


class GWO(Optimizer):
    """Grey Wolf Optimizer, vectorised over runs and wolves; see the module docstring."""

    name = "gwo"
    params_class = GWOParams

    def init(self, space: Space, streams: RunStreams, max_iter: int, x0=None) -> GWOState:
        N, D, R = self.params.pop_size, space.dim, streams.runs
        X = initial_population(streams, N, space.lb, space.ub, x0)
        return GWOState(
            X=X,
            lead_f=np.full((R, 3), np.inf),
            lead_x=np.zeros((R, 3, D)),
            t=0,
            T=max_iter,
            space=space,
            streams=streams,
        )

    def ask(self, state: GWOState) -> np.ndarray:
        """Move the pack (one kernel pass); returns a new array each call."""
        if state.t > 0:
            R, N, D = state.X.shape
            a = 2.0 - 2.0 * (state.t - 1) / state.T
            lb = np.asarray(state.space.lb, float)
            ub = np.asarray(state.space.ub, float)
            X = np.empty_like(state.X)
            streams = state.streams
            if not hasattr(streams, "raw_words"):  # stand-in streams hand out the uniforms
                r = streams.random((2, 3, N, D))
                gwo_step(state.X, state.lead_x, a, _NO_RNG, False, r, lb, ub, X)
            else:
                if state.rng is None:  # seeded once from each run's own generator
                    state.rng = seed_xoshiro(streams)
                gwo_step(state.X, state.lead_x, a, state.rng, True, _NO_R, lb, ub, X)
            state.X = X
        return state.X

    def tell(self, state: GWOState, X: np.ndarray, F: np.ndarray) -> GWOState:
        if self.params.demote_leaders:
            state.lead_f, state.lead_x = update_leaders_demoting(state.lead_f, state.lead_x, F, X)
        else:
            leaders_in_place(state.lead_f, state.lead_x, F, X)
        state.t += 1
        return state
