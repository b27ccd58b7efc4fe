"""Whale Optimization Algorithm (Mirjalili & Lewis, Adv. Eng. Softw. 95, 2016; ``WOA.m``).

Iteration ``t = 1..T`` as in ``WOA.m``: evaluate every whale (after clamping it into the box) and
update the leader ``X*`` (best-so-far, strict ``<``, first whale wins ties), then move every whale
``i`` with its own scalars ``r1, r2, p ~ U(0,1)`` and ``l``:

    a = 2 - 2 (t - 1) / T,  A = 2 a r1 - a,  C = 2 r2                      (Eqs. 2.3-2.4)
    p <  0.5, |A| <  1:  X_ij <- X*_j - A |C X*_j - X_ij|                  (Eqs. 2.1-2.2, encircle)
    p <  0.5, |A| >= 1:  X_ij <- X_kj - A |C X_kj - X_ij|                  (Eqs. 2.7-2.8, search)
    p >= 0.5:            X_ij <- |X*_j - X_ij| e^{b l} cos(2 pi l) + X*_j   (Eq. 2.5, spiral)

``l = (a2 - 1) r + 1`` with ``a2 = -1 - (t - 1)/T`` (``WOA.m``; ``l_range="paper"`` gives the
paper's ``l ~ U(-1, 1)``), ``b = 1``.

Two details of ``WOA.m`` that the paper's vector notation hides, both defaults here:

* ``random_whale="per_dimension"``: ``WOA.m`` draws ``rand_leader_index`` inside the ``for j``
  loop, so every coordinate of the search move has its own random whale ``k = k_ij``
  (``"per_whale"``: one ``k`` per whale, the paper's single ``X_rand`` vector).
* ``update="in_place"``: ``WOA.m`` overwrites ``Positions`` while it loops over whales, so
  ``X_kj`` is the *new* (not yet clamped) coordinate when ``k < i`` and the old one when
  ``k >= i`` (``"snapshot"``: always the old one). Only the search move reads other whales.

The in-place rule makes whale ``i`` depend on whales ``k < i``, so :func:`woa_step` (Numba) runs
``WOA.m``'s loops literally: for each run, each whale in order, each coordinate. It takes the
random numbers drawn by :meth:`WOA._draws` from the runs' own streams, and ``e^{b l}``,
``cos(2 pi l)`` from NumPy, and does the rest of the arithmetic in ``WOA.m``'s order without
fastmath, so it gives the numbers of the earlier vectorised NumPy code bit for bit. See
``docs/deviations.md#d-woa``.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numba import njit

from mawdo.optimizers.base import Optimizer, Params, Space, initial_population, option
from mawdo.streams import RunStreams
from mawdo.util import libm


@dataclass(frozen=True)
class WOAParams(Params):
    """WOA coefficients.

    Parameters
    ----------
    pop_size : int
        Whales per run, >= 2.
    b : float
        Spiral shape constant (1 in the paper and ``WOA.m``).
    l_range : {"matlab", "paper"}
        ``"matlab"`` (default): ``l = (a2 - 1) r + 1 ~ U(a2, 1)`` with ``a2`` falling from -1 to -2
        over the run, as in ``WOA.m``. ``"paper"``: ``l ~ U(-1, 1)``.
    random_whale : {"per_dimension", "per_whale"}
        ``"per_dimension"`` (default, ``WOA.m``): a new random whale for every coordinate of the
        search move. ``"per_whale"``: one random whale per whale.
    update : {"in_place", "snapshot"}
        ``"in_place"`` (default, ``WOA.m``): the search move reads the new positions of whales
        already moved in this iteration. ``"snapshot"``: every whale moves from the positions the
        iteration started with.
    """

    b: float = option(1.0)
    l_range: str = option("matlab", choices=("matlab", "paper"))
    random_whale: str = option("per_dimension", choices=("per_dimension", "per_whale"))
    update: str = option("in_place", choices=("in_place", "snapshot"))


@njit(cache=True, nogil=True, error_model="numpy")
def woa_step(X, leader, a, u, e, c, ur, in_place, lb, ub, out):  # pragma: no cover - compiled
    """``WOA.m``'s move of every whale of every run, written to ``out`` clamped to ``[lb, ub]``.

    Parameters (shapes with ``R`` runs, ``N`` whales, ``D`` dimensions)
    ----------
    X : (R, N, D)
        Positions the iteration started with (clamped); read only.
    leader : (R, D)
        Best-so-far whale ``X*`` of each run.
    a : float
        ``a = 2 - 2 (t - 1) / T`` in ``[0, 2]``.
    u : (R, 4, N)
        ``r1, r2``, the ``l`` draw (unused here) and ``p`` of each whale, each in ``[0, 1)``:
        ``A = 2 a r1 - a``, ``C = 2 r2`` (Eqs. 2.3-2.4), spiral when ``p >= 0.5``.
    e, c : (R, N)
        ``e^{b l}`` and ``cos(2 pi l)`` of each whale (Eq. 2.5), from NumPy's ``exp``/``cos``.
    ur : (R, N, D) or (R, N, 1)
        Random-whale draws in ``[0, 1)``: whale ``k = floor(N ur)`` (``WOA.m``'s
        ``floor(N rand + 1)``, 0-based); one per coordinate, or one per whale when the last axis
        has length 1.
    in_place : bool
        ``WOA.m``'s order: whale ``i``'s search move reads the new, not yet clamped, coordinate
        of a whale ``k < i`` (and the old one for ``k >= i``). False: every whale reads ``X``.
    lb, ub : (D,)
        The box; each run is clamped after all its whales moved (``WOA.m`` clamps at the next
        evaluation), with ``numpy.clip``'s comparisons.
    out : (R, N, D)
        The new positions.
    """
    R, N, D = X.shape
    per_dim = ur.shape[2] > 1
    for r in range(R):
        # in place, the run's positions are copied to ``out`` first: out[k] is then the new
        # coordinate for k < i and still the old one for k >= i, with no branch on k
        src = out[r] if in_place else X[r]
        if in_place:
            out[r] = X[r]
        for i in range(N):
            A = 2.0 * a * u[r, 0, i] - a  # Eq. 2.3
            C = 2.0 * u[r, 1, i]  # Eq. 2.4
            if u[r, 3, i] >= 0.5:  # Eq. 2.5, spiral
                ei, ci = e[r, i], c[r, i]
                for j in range(D):
                    L = leader[r, j]
                    out[r, i, j] = abs(L - X[r, i, j]) * ei * ci + L
            elif abs(A) < 1.0:  # Eqs. 2.1-2.2, encircle the leader
                for j in range(D):
                    L = leader[r, j]
                    out[r, i, j] = L - A * abs(C * L - X[r, i, j])
            else:  # Eqs. 2.7-2.8, search around random whales
                for j in range(D):
                    k = min(int(ur[r, i, j if per_dim else 0] * N), N - 1)
                    xk = src[k, j]
                    out[r, i, j] = xk - A * abs(C * xk - X[r, i, j])
        for i in range(N):
            for j in range(D):
                v = out[r, i, j]
                if v == v:  # NaN stays NaN, as in numpy.clip
                    v = v if v > lb[j] else lb[j]
                    v = v if v < ub[j] else ub[j]
                out[r, i, j] = v


@njit(cache=True, nogil=True)
def update_leader(X, F, leader_x, leader_f):  # pragma: no cover - compiled
    """``WOA.m``'s leader update, in place: per run, the first whale with the least ``F`` (as
    ``numpy.argmin``) replaces the leader when strictly better. ``X (R, N, D)``, ``F (R, N)``
    without NaN, ``leader_x (R, D)``, ``leader_f (R,)``."""
    R, N, D = X.shape
    for r in range(R):
        j = 0
        for i in range(1, N):
            if F[r, i] < F[r, j]:
                j = i
        if F[r, j] < leader_f[r]:
            leader_f[r] = F[r, j]
            for d in range(D):
                leader_x[r, d] = X[r, j, d]


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

    def _draws(self, state: WOAState):
        """``a``; per whale ``r1, r2``, the ``l`` draw and ``p`` as ``u (R, 4, N)`` (WOA.m's order)
        with ``l (R, N)``; the random-whale draw of each entry ``ur``."""
        N, D = state.X.shape[1:]
        frac = (state.t - 1) / state.T
        per_dim = self.params.random_whale == "per_dimension"
        u, ur = state.streams.random_parts((4, N), (N, D) if per_dim else (N, 1))
        ul = u[:, 2]
        if self.params.l_range == "paper":
            l = 2.0 * ul - 1.0
        else:
            a2 = -1.0 - frac
            l = (a2 - 1.0) * ul + 1.0
        return 2.0 - 2.0 * frac, u, l, ur

    def ask(self, state: WOAState) -> np.ndarray:
        """Move every whale (one kernel pass, :func:`woa_step`); returns a new array each call."""
        if state.t > 0:
            a, u, l, ur = self._draws(state)
            e, c = libm.exp(self.params.b * l), libm.cos(2.0 * np.pi * l)  # Eq. 2.5
            X = np.empty_like(state.X)
            in_place = self.params.update == "in_place"
            sp = state.space
            lb, ub = np.asarray(sp.lb, float), np.asarray(sp.ub, float)
            woa_step(state.X, state.leader_x, a, u, e, c, ur, in_place, lb, ub, X)
            state.X = X
        return state.X

    def tell(self, state: WOAState, X: np.ndarray, F: np.ndarray) -> WOAState:
        update_leader(X, F, state.leader_x, state.leader_f)
        state.t += 1
        return state
