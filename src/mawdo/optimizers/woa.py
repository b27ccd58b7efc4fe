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

The in-place rule makes whale ``i`` depend on whales ``k < i``, a chain through the search moves
only. We solve that chain without a loop over whales: each sweep recomputes every search entry
from the current estimate (:func:`search_in_place`); entries whose chain is ``s`` links deep are
exact after sweep ``s``, and the sweeps stop when nothing changes, which happens only at the
unique solution of the (acyclic) system, i.e. at ``WOA.m``'s sequential result, bit for bit. In
practice 2-6 sweeps per iteration. See ``docs/deviations.md#d-woa``.
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

    b: float = 1.0
    l_range: str = "matlab"
    random_whale: str = "per_dimension"
    update: str = "in_place"

    def __post_init__(self) -> None:
        super().__post_init__()
        check_choice("l_range", self.l_range, ("matlab", "paper"))
        check_choice("random_whale", self.random_whale, ("per_dimension", "per_whale"))
        check_choice("update", self.update, ("in_place", "snapshot"))


def leader_moves(X, leader, A, C, l, b):
    """Eqs. 2.1-2.2 (encircle) and 2.5 (spiral) for all whales.

    Shapes: ``X (R, N, D)``, ``leader (R, D)``, ``A, C, l (R, N)``. Returns both candidates.
    """
    Ls = leader[:, None, :]
    A3, C3, l3 = A[..., None], C[..., None], l[..., None]
    encircle = Ls - A3 * np.abs(C3 * Ls - X)
    spiral = np.abs(Ls - X) * np.exp(b * l3) * np.cos(2.0 * np.pi * l3) + Ls
    return encircle, spiral


def search_move(X, X_rand, A, C):
    """Eqs. 2.7-2.8: ``X_rand - A |C X_rand - X|`` with ``A, C (R, N)``, positions ``(R, N, D)``."""
    return X_rand - A[..., None] * np.abs(C[..., None] * X_rand - X)


def search_in_place(X, new, search, idx, A, C):
    """The search entries of ``WOA.m``'s in-place loop, solved by sweeps (see module docstring).

    Parameters
    ----------
    X : numpy.ndarray
        Positions the iteration started with, ``(R, N, D)``.
    new : numpy.ndarray
        New positions of the non-search whales (values at search whales are ignored).
    search : numpy.ndarray of bool
        ``(R, N)``: whales taking the search move.
    idx : numpy.ndarray of int
        Random whale of each coordinate, ``(R, N, D)`` (constant along ``D`` for ``per_whale``).
    A, C : numpy.ndarray
        Per-whale coefficients, ``(R, N)``.
    """
    N = X.shape[1]
    earlier = idx < np.arange(N)[None, :, None]  # k < i: WOA.m reads whale k's new coordinate
    old_src = np.take_along_axis(X, idx, axis=1)
    mask = search[..., None]
    out = np.where(mask, search_move(X, old_src, A, C), new)
    for _ in range(N):  # depth of the k < i chain is < N, so N sweeps always suffice
        src = np.where(earlier, np.take_along_axis(out, idx, axis=1), old_src)
        nxt = np.where(mask, search_move(X, src, A, C), out)
        if np.array_equal(nxt, out):
            break
        out = nxt
    return out


def woa_move(X, leader, X_rand, a, r1, r2, p, l, b):
    """Eqs. 2.1-2.8 for all whales from one snapshot (``update="snapshot"``).

    Shapes: ``X (R, N, D)``, ``leader (R, D)``, ``X_rand (R, N, D)`` (the random whale's
    coordinates for each entry), ``r1, r2, p, l`` per whale ``(R, N)``; ``a`` scalar.
    """
    A, C = 2.0 * a * r1 - a, 2.0 * r2
    encircle, spiral = leader_moves(X, leader, A, C, l, b)
    shrink = np.where((np.abs(A) < 1.0)[..., None], encircle, search_move(X, X_rand, A, C))
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

    def _draws(self, state: WOAState):
        """Per whale ``r1, r2, l, p`` (WOA.m's order) and the random whale index of each entry."""
        N, D = state.X.shape[1:]
        frac = (state.t - 1) / state.T
        u = state.streams.random((4, N))
        r1, r2, ul, p = (u[:, k] for k in range(4))
        if self.params.l_range == "paper":
            l = 2.0 * ul - 1.0
        else:
            a2 = -1.0 - frac
            l = (a2 - 1.0) * ul + 1.0
        shape = (N, D) if self.params.random_whale == "per_dimension" else (N, 1)
        ur = state.streams.random(shape)
        idx = np.minimum((ur * N).astype(np.int64), N - 1)  # floor(N rand + 1), 0-based
        return 2.0 - 2.0 * frac, r1, r2, p, l, np.broadcast_to(idx, state.X.shape)

    def ask(self, state: WOAState) -> np.ndarray:
        if state.t > 0:
            X = state.X
            a, r1, r2, p, l, idx = self._draws(state)
            if self.params.update == "snapshot":
                X_rand = np.take_along_axis(X, idx, axis=1)
                new = woa_move(X, state.leader_x, X_rand, a, r1, r2, p, l, self.params.b)
            else:
                A, C = 2.0 * a * r1 - a, 2.0 * r2
                encircle, spiral = leader_moves(X, state.leader_x, A, C, l, self.params.b)
                lead = (p < 0.5)[..., None]
                new = np.where(lead, encircle, spiral)
                search = (p < 0.5) & (np.abs(A) >= 1.0)
                if search.any():
                    new = search_in_place(X, new, search, idx, A, C)
            state.X = np.clip(new, state.space.lb, state.space.ub)
        return state.X

    def tell(self, state: WOAState, X: np.ndarray, F: np.ndarray) -> WOAState:
        # WOA.m scans whales in order with a strict <: the first minimum, only if it improves.
        j = np.argmin(F, axis=1)
        fj = F[np.arange(F.shape[0]), j]
        better = fj < state.leader_f
        state.leader_f = np.where(better, fj, state.leader_f)
        state.leader_x[better] = X[better, j[better]]
        state.t += 1
        return state
