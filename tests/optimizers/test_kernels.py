"""The Numba kernels against independent references: the NumPy equation functions of wind.py,
boundary.py and gwo.py, and a plain-Python (big integer) port of the permutation draw."""

import itertools

import numpy as np
import pytest
from scipy.stats import chisquare

from mawdo.optimizers import wind
from mawdo.optimizers.base import ranks
from mawdo.optimizers.boundary import apply_boundary, confine_positions, reflect_damped
from mawdo.optimizers.gwo import gwo_move
from mawdo.optimizers.kernels import (
    gwo_step,
    halves_to_unit,
    mewdo_step,
    segment_ranks,
    update_personal_best,
    words_per_permutation,
)
from mawdo.optimizers.wdo import group_starts
from mawdo.optimizers.wind_kernel import wind_step
from mawdo.streams import RunStreams

M64 = (1 << 64) - 1


def python_shuffle(words, d):
    """Fisher-Yates with batched multiply-shift, in Python integers (no 64-bit tricks)."""
    out, w, x, prod = list(range(d)), -1, 0, 1 << 40
    for k in range(d - 1, 0, -1):
        n = k + 1
        if prod * n > 1 << 32:
            w, prod = w + 1, 1
            x = int(words[w])
        prod *= n
        j, x = (x * n) >> 64, (x * n) & M64
        out[k], out[j] = out[j], out[k]
    return out, w + 1


@pytest.mark.parametrize("d", [1, 2, 3, 7, 13, 30, 64])
def test_permutations_equal_a_python_port_of_the_draw(d):
    n = 40
    streams = RunStreams([np.random.default_rng(5), np.random.default_rng(6)])
    got = streams.shuffle_rows(np.empty((2, n, d), np.int16))
    again = RunStreams([np.random.default_rng(5), np.random.default_rng(6)])
    W = words_per_permutation(d)
    for r, g in enumerate(again.generators):
        words = g.bit_generator.random_raw(n * W)
        for i in range(n):
            perm, used = python_shuffle(words[i * W : (i + 1) * W], d)
            assert used == W
            assert got[r, i].tolist() == perm


def test_permutations_are_uniform():
    streams = RunStreams([np.random.default_rng(11)])
    p = streams.shuffle_rows(np.empty((1, 48000, 4), np.int16))[0]
    index = {perm: k for k, perm in enumerate(itertools.permutations(range(4)))}
    counts = np.bincount([index[tuple(row)] for row in p.tolist()], minlength=24)
    assert chisquare(counts).pvalue > 1e-3
    q = streams.shuffle_rows(np.empty((1, 30000, 30), np.int16))[0]
    assert np.all(np.sort(q, axis=1) == np.arange(30))
    for v in (0, 29):  # where the first and the last element land: uniform over 30 places
        assert chisquare(np.bincount(np.argmax(q == v, axis=1), minlength=30)).pvalue > 1e-3


def test_segment_ranks_match_numpy_with_ties():
    rng = np.random.default_rng(0)
    F = rng.integers(0, 5, (6, 50)).astype(float)
    F[0, :10] = np.inf
    out = np.empty_like(F)
    segment_ranks(F, group_starts(50, 1), out)
    np.testing.assert_array_equal(out, ranks(F))
    segment_ranks(F, group_starts(50, 8), out)
    np.testing.assert_array_equal(out, wind.group_ranks(F, wind.partition(50, 8), 8))
    big = rng.random((2, 300))  # segments longer than the insertion-sort cut-off
    out = np.empty_like(big)
    segment_ranks(big, group_starts(300, 2), out)
    np.testing.assert_array_equal(out, wind.group_ranks(big, wind.partition(300, 2), 2))


def numpy_step(p, u, pbest, pbest_f, f, perm, coef, G, guidance, w, gate, centre_on, awdo,
               vmax, reflect, eta, rank_scope):  # fmt: skip
    """One move with the NumPy equation functions (the pre-kernel formulation)."""
    R, N, D = p.shape
    gid = wind.partition(N, G)
    rows = np.arange(R)[:, None]
    gb = pbest[rows, wind.group_argmin(pbest_f, gid, G)]
    tb = pbest[np.arange(R), np.argmin(pbest_f, axis=1)]
    if guidance == 0:
        B = tb[:, None, :]
    elif guidance == 1:
        B = gb[:, gid]
    else:
        w3 = w[2] * wind.distance_gate(gb, tb, 2 * np.sqrt(D))[:, gid] if gate else w[2]
        B = wind.hierarchical_guidance(pbest, gb[:, gid], tb, w[0], w[1], w3)
    r = wind.group_ranks(f, gid, G) if rank_scope == "group" else ranks(f)
    r = r[..., None].astype(float)
    centre = wind.group_centroid(p, gid, G)[:, gid] if centre_on else 0.0
    a, g, RT, c = (coef[..., k : k + 1] for k in range(4))
    step = wind.awdo_velocity if awdo else wind.wdo_velocity
    u_new = step(u, p, B, r, np.take_along_axis(u, perm, 2), a, g, RT, c, centre)
    u_new = np.clip(u_new, -vmax, vmax)
    if reflect:
        return reflect_damped(p + u_new, u_new, -1.0, 1.0, eta)
    return np.clip(p + u_new, -1.0, 1.0), u_new


@pytest.mark.parametrize(
    "guidance,gate,centre_on,awdo,reflect,scope",
    [
        (0, False, False, False, False, "population"),  # WDO
        (0, False, False, True, False, "population"),  # AWDO
        (1, False, False, True, False, "group"),  # MAWDO-1
        (2, True, False, True, False, "group"),  # MAWDO-2
        (2, False, False, True, True, "group"),
        (0, False, True, True, False, "population"),  # MAWDO-4 (low-D)
        (2, True, True, True, True, "group"),  # MAWDO in low D
    ],
)
def test_wind_step_equals_the_numpy_equations(guidance, gate, centre_on, awdo, reflect, scope):
    rng = np.random.default_rng(guidance + 2 * gate + 4 * centre_on + 8 * reflect)
    R, N, D, G = 3, 13, 5, 3
    p = rng.uniform(-1, 1, (R, N, D))
    u = rng.uniform(-0.6, 0.6, (R, N, D))  # large: clamps and reflections happen
    pbest = rng.uniform(-1, 1, (R, N, D))
    pbest_f = rng.integers(0, 6, (R, N)).astype(float)  # ties in the leaders
    f = rng.integers(0, 6, (R, N)).astype(float)
    perm = np.stack([[rng.permutation(D) for _ in range(N)] for _ in range(R)]).astype(np.int16)
    coef = rng.uniform(0.1, 1.2, (R, N, 4))
    w = np.array([0.45, 0.3, 0.25])
    vmax, eta = 0.3, 0.5
    lb, ub = np.linspace(-5, 0, D), np.linspace(1, 9, D)
    ep, eu = numpy_step(p, u, pbest, pbest_f, f, perm, coef, G, guidance, w, gate, centre_on,
                        awdo, vmax, reflect, eta, scope)  # fmt: skip
    rank = np.empty((R, N))
    segment_ranks(f, group_starts(N, G if scope == "group" else 1), rank)
    X = np.empty((R, N, D))
    P, U = p.copy(), u.copy()
    wind_step(P, U, pbest, pbest_f, rank, perm, np.ones((1, 4), np.uint64), False, 0, coef,
              group_starts(N, G), guidance, w, gate, 2 * np.sqrt(D), int(centre_on), int(awdo),
              vmax, reflect, eta, lb, ub - lb, X)  # fmt: skip
    np.testing.assert_allclose(P, ep, rtol=0, atol=1e-14)
    np.testing.assert_allclose(U, eu, rtol=0, atol=1e-14)
    np.testing.assert_allclose(X, lb + (ep + 1) / 2 * (ub - lb), rtol=1e-14, atol=1e-13)
    assert np.all(np.abs(U) <= vmax + 1e-15) and np.all(np.abs(P) <= 1)


def python_xoshiro(state, n):
    """xoshiro256** (Blackman & Vigna), literally, in Python integers: n outputs, final state."""
    s = [int(v) for v in state]
    rotl = lambda x, k: ((x << k) | (x >> (64 - k))) & M64  # noqa: E731
    out = []
    for _ in range(n):
        out.append(rotl((s[1] * 5) & M64, 7) * 9 & M64)
        t = (s[1] << 17) & M64
        s[2] ^= s[0]
        s[3] ^= s[1]
        s[1] ^= s[2]
        s[0] ^= s[3]
        s[2] ^= t
        s[3] = rotl(s[3], 45)
    return out, s


def test_python_xoshiro_matches_the_published_first_output():
    assert python_xoshiro([1, 2, 3, 4], 1)[0] == [11520]  # rotl(2 * 5, 7) * 9, by hand


def test_gwo_step_equals_gwo_move_on_the_same_uniforms():
    rng = np.random.default_rng(3)
    R, N, D = 2, 7, 4
    X = rng.uniform(-3, 3, (R, N, D))
    lead = rng.uniform(-3, 3, (R, 3, D))
    lb, ub = np.full(D, -2.0), np.full(D, 2.5)
    state = rng.integers(1, 2**63, (R, 4), dtype=np.int64).astype(np.uint64)
    state[1] = [1, 2, 3, 4]
    words, final = [], []
    for r in range(R):
        w, s = python_xoshiro(state[r], 3 * N * D)
        words.append(w)
        final.append(s)
    w = np.array(words, dtype=np.uint64).reshape(R, N, D, 3)  # drawn wolf, dimension, leader
    r1 = (w & np.uint64(0xFFFFFFFF)).astype(float) / 2**32
    r2 = (w >> np.uint64(32)).astype(float) / 2**32
    expect = np.clip(
        gwo_move(X, lead, 0.7, r1.transpose(0, 3, 1, 2), r2.transpose(0, 3, 1, 2)), lb, ub
    )
    out = np.empty_like(X)
    st = state.copy()
    gwo_step(X, lead, 0.7, st, True, np.zeros((1, 2, 3, 1, 1)), lb, ub, out)
    np.testing.assert_allclose(out, expect, rtol=1e-13, atol=1e-13)
    assert st.tolist() == final  # each run's generator advanced by exactly 3 N D outputs
    one = np.empty((1, N, D))
    gwo_step(X[1:], lead[1:], 0.7, state[1:].copy(), True, np.zeros((1, 2, 3, 1, 1)), lb, ub, one)
    np.testing.assert_array_equal(one[0], out[1])  # a run alone draws what it draws in a batch


def test_magic_number_halves_equal_float_times_two_to_minus_32():
    edge = [0, 1, 2**32 - 1, 2**32, 2**63, 2**64 - 1, 0xFFFFFFFF00000000, 0x00000001FFFFFFFF]
    rand = np.random.default_rng(5).integers(0, 2**64, 200, dtype=np.uint64, endpoint=False)
    words = np.concatenate([np.array(edge, dtype=np.uint64), rand])
    r1, r2 = np.empty(words.size), np.empty(words.size)
    halves_to_unit(words, r1, r2)
    want1 = [float(int(w) & 0xFFFFFFFF) * 2.0**-32 for w in words]  # Python floats, by hand
    want2 = [float(int(w) >> 32) * 2.0**-32 for w in words]
    assert r1.tolist() == want1 and r2.tolist() == want2
    assert r1[2] == r2[5] == 1.0 - 2.0**-32 and r1[0] == r2[0] == 0.0


def test_gwo_step_xoshiro_path_equals_the_array_path_bit_for_bit():
    """The in-kernel magic-number conversion against NumPy's uint64 -> float on the same words."""
    rng = np.random.default_rng(8)
    R, N, D = 3, 6, 5
    X = rng.uniform(-3, 3, (R, N, D))
    lead = rng.uniform(-3, 3, (R, 3, D))
    lb, ub = np.full(D, -1.0), np.full(D, 1.5)  # narrow: some wolves are clipped
    state = rng.integers(1, 2**63, (R, 4), dtype=np.int64).astype(np.uint64)
    w = np.array([python_xoshiro(s, 3 * N * D)[0] for s in state], np.uint64).reshape(R, N, D, 3)
    r1 = (w & np.uint64(0xFFFFFFFF)).astype(float) * 2.0**-32
    r2 = (w >> np.uint64(32)).astype(float) * 2.0**-32
    r = np.stack([r1, r2], axis=1).transpose(0, 1, 4, 2, 3)  # (R, 2, 3, N, D)
    want = np.empty_like(X)
    gwo_step(X, lead, 0.7, np.ones((1, 4), np.uint64), False, r, lb, ub, want)
    got = np.empty_like(X)
    gwo_step(X, lead, 0.7, state.copy(), True, np.zeros((1, 2, 3, 1, 1)), lb, ub, got)
    np.testing.assert_array_equal(got, want)
    assert np.any(got == lb) and np.any(got == ub) and np.unique(got).size > R * N


@pytest.mark.parametrize("policy", ["clip", "reflect"])
def test_confine_positions_equals_apply_boundary(policy):
    p = np.random.default_rng(4).uniform(-3.5, 3.5, (3, 40, 5))
    expect, _ = apply_boundary(policy, p, np.zeros_like(p), -1.0, 1.0, 0.5)
    got = confine_positions(policy, p.copy(), -1.0, 1.0)
    np.testing.assert_array_equal(got, expect)


def test_update_personal_best_is_strict_and_in_place():
    rng = np.random.default_rng(8)
    p = rng.random((2, 6, 3))
    f = np.array([[1.0, 2.0, np.inf, 0.5, 3.0, 3.0], [0.0, 0.0, 0.0, 9.0, 9.0, 9.0]])
    pbest_f = np.array([[2.0, 2.0, np.inf, 0.4, np.inf, 3.5], [1.0, -1.0, 0.0, 8.0, 10.0, 9.0]])
    pbest = rng.random((2, 6, 3))
    better = f < pbest_f
    expect_x = np.where(better[..., None], p, pbest)
    expect_f = np.where(better, f, pbest_f)
    update_personal_best(p, f, pbest, pbest_f)
    np.testing.assert_array_equal(pbest, expect_x)
    np.testing.assert_array_equal(pbest_f, expect_f)


def test_wind_step_draws_each_parcels_permutation_from_its_runs_xoshiro():
    rng = np.random.default_rng(9)
    R, N, D = 2, 5, 7
    p, u = rng.uniform(-1, 1, (R, N, D)), rng.uniform(-0.3, 0.3, (R, N, D))
    pbest, pbest_f = rng.uniform(-1, 1, (R, N, D)), rng.random((R, N))
    rank = np.tile(np.arange(1.0, N + 1), (R, 1))
    coef = np.array([[[0.4, 0.2, 3.0, 0.4]]])
    state = rng.integers(1, 2**63, (R, 4), dtype=np.int64).astype(np.uint64)
    W = words_per_permutation(D)
    perm = np.empty((R, N, D), np.int16)
    final = []
    for r in range(R):
        words, s = python_xoshiro(state[r], N * W)
        final.append(s)
        for i in range(N):
            perm[r, i] = python_shuffle(words[i * W : (i + 1) * W], D)[0]
    args = (coef, group_starts(N, 1), 0, np.zeros(3), False, 1.0, 0, 0, 0.3, False, 0.5,
            np.zeros(D), np.ones(D))  # fmt: skip
    out = []
    for mode in ("perm", "rng"):
        P, U, X, st = p.copy(), u.copy(), np.empty((R, N, D)), state.copy()
        wind_step(P, U, pbest, pbest_f, rank, perm, st, mode == "rng", 0, *args, X)
        out.append((P, U))
    np.testing.assert_array_equal(out[0][0], out[1][0])
    np.testing.assert_array_equal(out[0][1], out[1][1])
    assert st.tolist() == final


@pytest.mark.parametrize("coef_draw", [1, 2])
def test_wind_step_draws_awdo_coefficients_before_the_permutations(coef_draw):
    rng = np.random.default_rng(10 + coef_draw)
    R, N, D = 2, 4, 6
    p, u = rng.uniform(-1, 1, (R, N, D)), rng.uniform(-0.3, 0.3, (R, N, D))
    pbest, pbest_f = rng.uniform(-1, 1, (R, N, D)), rng.random((R, N))
    rank = np.tile(np.arange(1.0, N + 1), (R, 1))
    state = rng.integers(1, 2**63, (R, 4), dtype=np.int64).astype(np.uint64)
    W = words_per_permutation(D)
    perm = np.empty((R, N, D), np.int16)
    coef = np.empty((R, N, 4))
    for r in range(R):
        n_words = 4 + N * W if coef_draw == 1 else N * (4 + W)
        words = python_xoshiro(state[r], n_words)[0]
        unif = [(w >> 11) / 2**53 for w in words]
        for i in range(N):
            if coef_draw == 1:
                coef[r, i], start = unif[:4], 4 + i * W
            else:
                coef[r, i], start = unif[i * (4 + W) : i * (4 + W) + 4], i * (4 + W) + 4
            perm[r, i] = python_shuffle(words[start : start + W], D)[0]
    args = (group_starts(N, 1), 0, np.zeros(3), False, 1.0, 0, 1, 0.3, False, 0.5,
            np.zeros(D), np.ones(D))  # fmt: skip
    P1, U1, X = p.copy(), u.copy(), np.empty((R, N, D))
    wind_step(P1, U1, pbest, pbest_f, rank, perm, state.copy(), True, coef_draw,
              np.zeros((1, 1, 4)), *args, X)  # fmt: skip
    P0, U0 = p.copy(), u.copy()
    wind_step(P0, U0, pbest, pbest_f, rank, perm, state.copy(), False, 0, coef, *args, X)
    np.testing.assert_array_equal(U1, U0)
    np.testing.assert_array_equal(P1, P0)


def test_mewdo_step_equals_the_numpy_strategies():
    rng = np.random.default_rng(12)
    R, N, D = 3, 9, 5
    p, u = rng.uniform(-1, 1, (R, N, D)), rng.uniform(-0.5, 0.5, (R, N, D))
    pbest = rng.uniform(-1, 1, (R, N, D))
    f = rng.random((R, N))
    r = ranks(f).astype(float)
    tb = rng.integers(0, N, R)
    guide = rng.integers(0, N, (R, N))
    centre = p.mean(axis=1)
    strat = rng.integers(0, 3, (R, N))
    draws = rng.random((R, N, 6))
    perm = np.stack([[rng.permutation(D) for _ in range(N)] for _ in range(R)]).astype(np.int16)
    alpha, g, RT, c, vmax = 0.4, 0.2, 3.0, 0.4, 0.3
    up = np.take_along_axis(u, perm, 2)
    B = pbest[np.arange(R), tb][:, None, :]
    rr = r[..., None]
    v0 = wind.wdo_velocity(u, p, B, rr, up, alpha, g, RT, c)
    a1, g1, RT1, c1 = (draws[..., k : k + 1] for k in range(1, 5))
    v1 = wind.awdo_velocity(u, p, B, rr, up, a1, g1, RT1, c1)
    G = pbest[np.arange(R)[:, None], guide]
    v2 = wind.awdo_velocity(u, p, G, 1.0, up, alpha, g, 1.0, c, centre[:, None, :])
    sel = strat[..., None]
    eu = np.clip(np.where(sel == 0, v0, np.where(sel == 1, v1, v2)), -vmax, vmax)
    ep = np.clip(p + eu, -1, 1)
    P, U, X = p.copy(), u.copy(), np.empty((R, N, D))
    lb, width = np.full(D, -3.0), np.full(D, 4.0)
    mewdo_step(P, U, pbest, r, tb, guide, centre, strat, draws, perm, np.zeros((1, 1), np.uint64),
               False, np.array([alpha, g, RT, c]), vmax, lb, width, X)  # fmt: skip
    np.testing.assert_array_equal(U, eu)
    np.testing.assert_array_equal(P, ep)
    np.testing.assert_allclose(X, lb + (ep + 1) / 2 * width, rtol=1e-15)


@pytest.mark.parametrize("shape", [(1, 1, 1), (3, 50, 30), (2, 7, 1000)])
def test_mewdo_centroid_is_numpy_mean_to_the_bit(shape):
    from mawdo.optimizers.mewdo import centroid

    p = np.random.default_rng(sum(shape)).normal(0, 1e3, shape)
    out = np.full((shape[0], shape[2]), np.nan)
    centroid(p, out)
    np.testing.assert_array_equal(out, p.mean(axis=1))
