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


def update_leaders_reference(lead_f, lead_x, F, X):
    """Leader update of ``GWO.m``, exactly, vectorised over runs and wolves.

    ``GWO.m`` scans the wolves in order with strict comparisons::

        if f < alpha: alpha = f
        if f > alpha and f < beta: beta = f
        if f > alpha and f > beta and f < delta: delta = f

    Since alpha is the running minimum, beta can only take an ``f_i`` greater than the running
    minimum before wolf ``i``, and it keeps the smallest such value; delta likewise takes the
    smallest ``f_i`` greater than beta before wolf ``i``. Both are prefix computations.

    Parameters
    ----------
    lead_f : numpy.ndarray
        Scores of alpha, beta, delta before this iteration, shape ``(R, 3)``.
    lead_x : numpy.ndarray
        Their positions, shape ``(R, 3, D)``.
    F, X : numpy.ndarray
        This iteration's scores ``(R, N)`` and positions ``(R, N, D)``.
    """
    R, N = F.shape
    rows = np.arange(R)
    a0, b0, d0 = lead_f[:, 0:1], lead_f[:, 1:2], lead_f[:, 2:3]
    # alpha before wolf i: min(alpha0, f_0..f_{i-1})
    run_min = np.minimum.accumulate(np.concatenate([a0, F], axis=1), axis=1)
    alpha_before = run_min[:, :-1]
    beta_ok = F > alpha_before  # and f < beta_before, which the running min below takes care of
    beta_cand = np.where(beta_ok, F, np.inf)
    beta_run = np.minimum.accumulate(np.concatenate([b0, beta_cand], axis=1), axis=1)
    beta_before = beta_run[:, :-1]
    delta_ok = (F > alpha_before) & (F > beta_before)
    delta_cand = np.where(delta_ok, F, np.inf)

    new_f = lead_f.copy()
    new_x = lead_x.copy()
    for k, (cand, old) in enumerate(((F, a0), (beta_cand, b0), (delta_cand, d0))):
        j = np.argmin(cand, axis=1)  # first index of the minimum = the wolf that set it
        cj = cand[rows, j]
        take = cj < old[:, 0]
        new_f[take, k] = cj[take]
        new_x[take, k] = X[take, j[take]]
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
        update = update_leaders_demoting if self.params.demote_leaders else update_leaders_reference
        state.lead_f, state.lead_x = update(state.lead_f, state.lead_x, F, X)
        state.t += 1
        return state
