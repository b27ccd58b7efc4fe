"""WOA against a literal transcription of ``WOA.m``'s loops, with the same random draws.

``literal_woa_m`` below follows ``WOA.m`` (Mirjalili's reference MATLAB code for Mirjalili & Lewis
2016) statement by statement, 0-based: clamp and evaluate every whale in order and update the
leader with a strict ``<``; then for every whale draw ``r1, r2``, the ``l`` draw and ``p``, and
loop over the dimensions, drawing ``rand_leader_index`` inside the ``for j`` loop and writing
``Positions(i, j)`` in place. The draws come from queues, so both codes see the same numbers; the
Numba kernel must reproduce every iteration's population (to 1e-13: the port's ``exp``/``cos`` are
``math``'s). ``literal_move`` is one move alone, given the same ``exp``/``cos`` values, and must
agree bit for bit.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from mawdo.optimizers.base import Space
from mawdo.optimizers.registry import make_optimizer
from mawdo.optimizers.woa import WOAState, woa_step
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


def literal_move(X, leader, a, u, e, c, ur, lb, ub, *, in_place=True):
    """One move of ``WOA.m``'s ``for i``/``for j`` loops per run, scalar by scalar, then the clamp.

    ``e[r][i] cos[r][i]`` stand for ``exp(b l) cos(l 2 pi)`` (given, so both codes use the same
    transcendental values); ``in_place=False`` reads every other whale from a copy of ``X``.
    """
    R, N, D = X.shape
    out = np.empty_like(X)
    for r in range(R):
        P = [list(map(float, row)) for row in X[r]]
        old = [list(row) for row in P]
        for i in range(N):
            r1, r2, _, p = u[r, :, i]
            A = 2 * a * r1 - a  # Eq. (2.3)
            C = 2 * r2  # Eq. (2.4)
            for j in range(D):
                if p < 0.5:
                    if abs(A) >= 1:
                        draw = ur[r, i, j] if ur.shape[2] > 1 else ur[r, i, 0]
                        k = math.floor(N * draw + 1) - 1
                        X_rand = P[k] if in_place else old[k]
                        D_X_rand = abs(C * X_rand[j] - P[i][j])  # Eq. (2.7)
                        P[i][j] = X_rand[j] - A * D_X_rand  # Eq. (2.8)
                    else:
                        D_Leader = abs(C * leader[r, j] - P[i][j])  # Eq. (2.1)
                        P[i][j] = leader[r, j] - A * D_Leader  # Eq. (2.2)
                else:
                    distance2Leader = abs(leader[r, j] - P[i][j])
                    P[i][j] = distance2Leader * e[r, i] * c[r, i] + leader[r, j]  # Eq. (2.5)
        out[r] = np.clip(np.array(P), lb, ub)
    return out


def random_move_case(seed, R=3, N=15, D=6, per_dimension=True):
    """A move with ``a`` near 2: about a quarter of the whales search (``|A| >= 1``, ``p < .5``)."""
    rng = np.random.default_rng(seed)
    X = rng.uniform(-2, 2, (R, N, D))
    leader = rng.uniform(-2, 2, (R, D))
    u = rng.random((R, 4, N))
    l = rng.uniform(-2, 1, (R, N))
    ur = rng.random((R, N, D if per_dimension else 1))
    lb, ub = np.full(D, -2.5), np.full(D, 2.5)  # the search move overshoots: the clamp acts
    return X, leader, 1.9, u, np.exp(l), np.cos(2 * np.pi * l), ur, lb, ub


@pytest.mark.parametrize("in_place", [True, False], ids=["in-place", "snapshot"])
@pytest.mark.parametrize("per_dimension", [True, False], ids=["per-dimension", "per-whale"])
@pytest.mark.parametrize("seed", range(6))
def test_kernel_move_equals_the_literal_loop_bit_for_bit(seed, per_dimension, in_place):
    case = random_move_case(seed, per_dimension=per_dimension)
    got = np.empty_like(case[0])
    woa_step(*case[:7], in_place, *case[7:], got)
    want = literal_move(*case, in_place=in_place)
    np.testing.assert_array_equal(got, want)
    u = case[3]
    A = 2 * 1.9 * u[:, 0] - 1.9
    search = (u[:, 3] < 0.5) & (np.abs(A) >= 1)
    assert search.sum() >= 5  # the case exercises the search move (and the clamp, below)
    assert np.any(np.abs(got) == 2.5)


def test_kernel_solves_a_chain_as_deep_as_the_population():
    """Every whale searches and reads the previous one, whose new coordinate it must see."""
    rng = np.random.default_rng(5)
    R, N, D = 2, 12, 3
    X = rng.uniform(-1, 1, (R, N, D))
    u = rng.random((R, 4, N))
    u[:, 0] = rng.choice([0.0, 0.99], (R, N))  # |A| = a >= 1: the search move
    u[:, 3] = 0.1
    ur = np.broadcast_to(((np.maximum(np.arange(N) - 1, 0) + 0.5) / N)[None, :, None], (R, N, D))
    e = c = np.ones((R, N))
    lb, ub = np.full(D, -50.0), np.full(D, 50.0)
    args = (X, np.zeros((R, D)), 1.2, u, e, c, np.ascontiguousarray(ur), True, lb, ub)
    got = np.empty_like(X)
    woa_step(*args, got)
    np.testing.assert_array_equal(got, literal_move(*args[:7], lb, ub))
    snapshot = np.empty_like(X)
    woa_step(*args[:7], False, lb, ub, snapshot)
    assert not np.array_equal(got[:, 2:], snapshot[:, 2:])  # the chain changes the result


@pytest.mark.parametrize(
    "bad", [{"random_whale": "each"}, {"update": "gauss"}, {"l_range": "unit"}]
)
def test_bad_woa_options_are_refused_by_name(bad):
    name = next(iter(bad))
    with pytest.raises(ValueError, match=name):
        make_optimizer("woa", **bad)
