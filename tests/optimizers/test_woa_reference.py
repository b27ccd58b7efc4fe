"""WOA against a literal transcription of ``WOA.m``'s loops, with the same random draws.

``literal_woa_m`` below follows ``WOA.m`` (Mirjalili's reference MATLAB code for Mirjalili & Lewis
2016) statement by statement, 0-based: clamp and evaluate every whale in order and update the
leader with a strict ``<``; then for every whale draw ``r1, r2``, the ``l`` draw and ``p``, and
loop over the dimensions, drawing ``rand_leader_index`` inside the ``for j`` loop and writing
``Positions(i, j)`` in place. The draws come from queues, so both codes see the same numbers; the
vectorised implementation must reproduce every iteration's population.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from mawdo.optimizers.base import Space
from mawdo.optimizers.registry import make_optimizer
from mawdo.optimizers.woa import WOAState, search_in_place
from tests.optimizers.fixed_streams import FixedStreams


def sphere(x):
    return float(np.sum(x * x))


def literal_woa_m(P0, lb, ub, T, fobj, u, ur, *, l_range="matlab", per_dimension=True):
    """``WOA.m``'s main loop for one run; returns the population after each move.

    ``u[t][i] = (r1, r2, l-draw, p)`` and ``ur[t][i][j]`` (the random-whale draw of entry ``(i,
    j)``; only ``ur[t][i][0]`` is used when ``per_dimension`` is False) are the draws of move
    ``t``, in the order ``WOA.m`` makes them.
    """
    P = [list(row) for row in P0]
    N, D = len(P), len(P[0])
    leader_score, leader_pos = math.inf, [0.0] * D
    history = []
    for t in range(T):  # while t < Max_iter
        for i in range(N):
            P[i] = [min(max(P[i][j], lb[j]), ub[j]) for j in range(D)]  # Flag4ub / Flag4lb
            fitness = fobj(np.array(P[i]))
            if fitness < leader_score:
                leader_score, leader_pos = fitness, list(P[i])
        if t == T - 1:
            break  # our driver stops after the last evaluation; WOA.m's final move is unused
        a = 2 - t * (2 / T)
        a2 = -1 + t * (-1 / T)
        for i in range(N):
            r1, r2, ul, p = u[t][i]
            A = 2 * a * r1 - a
            C = 2 * r2
            b = 1
            l = (a2 - 1) * ul + 1 if l_range == "matlab" else 2 * ul - 1
            for j in range(D):
                if p < 0.5:
                    if abs(A) >= 1:
                        draw = ur[t][i][j] if per_dimension else ur[t][i][0]
                        rand_leader_index = math.floor(N * draw + 1) - 1
                        X_rand = P[rand_leader_index]  # the array being updated
                        D_X_rand = abs(C * X_rand[j] - P[i][j])  # Eq. (2.7)
                        P[i][j] = X_rand[j] - A * D_X_rand  # Eq. (2.8)
                    elif abs(A) < 1:
                        D_Leader = abs(C * leader_pos[j] - P[i][j])  # Eq. (2.1)
                        P[i][j] = leader_pos[j] - A * D_Leader  # Eq. (2.2)
                elif p >= 0.5:
                    distance2Leader = abs(leader_pos[j] - P[i][j])
                    P[i][j] = (
                        distance2Leader * math.exp(b * l) * math.cos(l * 2 * math.pi)
                        + (leader_pos[j])
                    )
        history.append([[min(max(v, lb[j]), ub[j]) for j, v in enumerate(row)] for row in P])
    return history, leader_score


def run_ours(P0, lb, ub, T, u, ur, **options):
    """Drive our WOA by ask/tell with the same draws; returns the population after each move."""
    R, N, D = P0.shape
    opt = make_optimizer("woa", pop_size=N, **options)
    per_dim = opt.params.random_whale == "per_dimension"
    queue = []
    for t in range(T - 1):
        queue.append(u[:, t].transpose(0, 2, 1))  # (R, 4, N): r1, r2, l, p rows
        queue.append(ur[:, t] if per_dim else ur[:, t, :, :1])
    st = WOAState(
        X=P0.copy(),
        leader_f=np.full(R, np.inf),
        leader_x=np.zeros((R, D)),
        t=0,
        T=T,
        space=Space(lb=np.asarray(lb, float), ub=np.asarray(ub, float)),
        streams=FixedStreams(runs=R, random=queue),
    )
    history = []
    for t in range(T):
        X = opt.ask(st)
        if t > 0:
            history.append(X.copy())
        F = np.array([[sphere(x) for x in run] for run in X])
        st = opt.tell(st, X, F)
    assert st.streams.exhausted()
    return history, st.leader_f


def fixed_case(seed, R=3, N=7, D=4, T=9):
    rng = np.random.default_rng(seed)
    lb, ub = [-5.0] * D, [5.0] * D
    P0 = rng.uniform(-5, 5, (R, N, D))
    u = rng.random((R, T - 1, N, 4))
    u[..., 3] *= 0.6  # p mostly < 0.5: the search and encircle branches dominate
    ur = rng.random((R, T - 1, N, D))
    return P0, lb, ub, T, u, ur


@pytest.mark.parametrize(
    "options",
    [
        {},
        {"l_range": "paper"},
        {"random_whale": "per_whale"},
    ],
    ids=["woa-m", "paper-l", "per-whale"],
)
@pytest.mark.parametrize("seed", [0, 1, 2])
def test_woa_equals_the_literal_woa_m_loop(seed, options):
    P0, lb, ub, T, u, ur = fixed_case(seed)
    ours, ours_best = run_ours(P0, lb, ub, T, u, ur, **options)
    for r in range(P0.shape[0]):
        ref, ref_best = literal_woa_m(
            P0[r].tolist(),
            lb,
            ub,
            T,
            sphere,
            u[r].tolist(),
            ur[r].tolist(),
            l_range=options.get("l_range", "matlab"),
            per_dimension=options.get("random_whale", "per_dimension") == "per_dimension",
        )
        for t, step in enumerate(ref):
            np.testing.assert_allclose(ours[t][r], step, rtol=1e-13, atol=1e-13, err_msg=f"t={t}")
        assert ours_best[r] == pytest.approx(ref_best, rel=1e-13)


def test_in_place_matters_for_these_draws():
    """The comparison above can fail: a snapshot update gives a different trajectory."""
    P0, lb, ub, T, u, ur = fixed_case(0)
    in_place, _ = run_ours(P0, lb, ub, T, u, ur)
    snapshot, _ = run_ours(P0, lb, ub, T, u, ur, update="snapshot")
    assert any(not np.allclose(a, b) for a, b in zip(in_place, snapshot, strict=True))
    per_whale, _ = run_ours(P0, lb, ub, T, u, ur, random_whale="per_whale")
    assert any(not np.allclose(a, b) for a, b in zip(in_place, per_whale, strict=True))


def literal_chain(X, new, search, idx, A, C):
    """The search entries of WOA.m's loop alone: sequential over whales, in place."""
    out = X.copy()
    R, N, D = X.shape
    for r in range(R):
        P = X[r].copy()
        for i in range(N):
            for j in range(D):
                if search[r, i]:
                    xr = P[idx[r, i, j], j]
                    P[i, j] = xr - A[r, i] * abs(C[r, i] * xr - P[i, j])
                else:
                    P[i, j] = new[r, i, j]
        out[r] = P
    return out


def test_search_sweeps_solve_long_chains_exactly():
    """Every whale searches and reads the previous one: a chain as deep as the population."""
    rng = np.random.default_rng(5)
    R, N, D = 2, 12, 3
    X = rng.uniform(-1, 1, (R, N, D))
    search = np.ones((R, N), bool)
    idx = np.broadcast_to(np.maximum(np.arange(N) - 1, 0)[None, :, None], (R, N, D)).copy()
    A = rng.uniform(1.0, 1.5, (R, N)) * rng.choice([-1, 1], (R, N))
    C = rng.uniform(0, 2, (R, N))
    got = search_in_place(X, X.copy(), search, idx, A, C)
    np.testing.assert_array_equal(got, literal_chain(X, X, search, idx, A, C))
    # and a random mix of search and non-search whales with random indices
    search = rng.random((R, N)) < 0.6
    idx = rng.integers(0, N, (R, N, D))
    new = rng.uniform(-1, 1, (R, N, D))
    got = search_in_place(X, new, search, idx, A, C)
    np.testing.assert_array_equal(got, literal_chain(X, new, search, idx, A, C))


@pytest.mark.parametrize(
    "bad", [{"random_whale": "each"}, {"update": "gauss"}, {"l_range": "unit"}]
)
def test_bad_woa_options_are_refused_by_name(bad):
    name = next(iter(bad))
    with pytest.raises(ValueError, match=name):
        make_optimizer("woa", **bad)
