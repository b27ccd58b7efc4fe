"""WDO+ (issue 29): each component against a step computed by hand on a fixed population with
fixed draws, WDO recovered with every component off, the in-kernel draws, restarts and budgets.
"""

import copy

import numpy as np
import pytest

from mawdo import minimize
from mawdo.optimizers import make_optimizer
from mawdo.optimizers.base import Space
from mawdo.optimizers.kernels import words_per_permutation
from mawdo.optimizers.wdo import group_starts
from mawdo.optimizers.wdo_plus import stalled, success_sigma
from mawdo.optimizers.wdo_plus_kernel import plus_step, plus_tell
from mawdo.optimizers.wind_kernel import wind_step
from mawdo.streams import RunStreams, run_seed_sequences
from tests.optimizers.test_kernels import python_shuffle, python_xoshiro

# One run, three parcels, two dimensions: small enough to follow by hand.
P0 = np.array([[[0.5, -0.2], [0.1, 0.4], [-0.6, 0.9]]])
U0 = np.array([[[0.1, 0.0], [-0.05, 0.2], [0.0, -0.1]]])
PB = np.array([[[0.4, -0.1], [0.2, 0.3], [-0.5, 0.8]]])
PBF = np.array([[2.0, 1.0, 3.0]])  # tbest is parcel 1 at (0.2, 0.3)
RANK = np.array([[2.0, 1.0, 3.0]])
PERM = np.array([[[1, 0], [0, 1], [1, 0]]], np.int16)
NOISE = np.array([[[0.5, -1.0], [1.5, 0.25], [-0.5, 0.0]]])
PRESS = np.array([[[0.25, 0.5], [0.75, 0.0], [1.0, 0.125]]])
COEF = np.array([0.4, 0.2, 3.0, 0.4])  # alpha, g, RT, c
NO_RNG = np.ones((1, 4), np.uint64)


def run_kernel(centre=0, sigma=0.0, midpoint=False, vmax=10.0, noise=NOISE, rp=False):
    P, U, X = P0.copy(), U0.copy(), np.empty_like(P0)
    plus_step(P, U, PB, PBF, RANK, np.array([sigma]), np.array([False]), COEF, centre, vmax,
              midpoint, rp, PERM, noise, PRESS, NO_RNG, False, np.full(2, -5.0),
              np.full(2, 10.0), X)  # fmt: skip
    return P, U, X


def hand_velocity(i, d, ref, sigma, rp=False):
    """Parcel i, coordinate d, written out term by term (scalars only)."""
    r = RANK[0, i]
    friction = (1 - 0.4) * U0[0, i, d]
    gravity = -0.2 * (P0[0, i, d] - ref[d])
    pressure = abs(1 - 1 / r) * 3.0 * (PB[0, 1, d] - P0[0, i, d]) * (PRESS[0, i, d] if rp else 1)
    coriolis = 0.4 * U0[0, i, PERM[0, i, d]] / r
    return friction + gravity + pressure + coriolis + sigma * NOISE[0, i, d]


@pytest.mark.parametrize(
    ("centre", "ref"),
    [(0, (0.0, 0.0)), (1, ((0.4 + 0.2 - 0.5) / 3, (-0.1 + 0.3 + 0.8) / 3)), (2, (0.2, 0.3))],
)
def test_gravity_pulls_toward_the_chosen_reference(centre, ref):
    P, U, _ = run_kernel(centre=centre)
    # parcel 0, d = 0 by hand for the origin: 0.06 - 0.1 + 1.5 * (-0.3) + 0.2 * 0.0 = -0.49
    if centre == 0:
        assert U[0, 0, 0] == pytest.approx(0.6 * 0.1 - 0.2 * 0.5 + 1.5 * (0.2 - 0.5) + 0.0)
    for i in range(3):
        for d in range(2):
            assert U[0, i, d] == pytest.approx(hand_velocity(i, d, ref, 0.0), abs=1e-15)
            assert P[0, i, d] == pytest.approx(np.clip(P0[0, i, d] + U[0, i, d], -1, 1), abs=1e-15)


def test_random_pressure_weighs_each_coordinates_pull_by_its_draw():
    P, U, _ = run_kernel(rp=True)
    # parcel 2 (rank 3), d = 0, by hand: 0.6 (0) - 0.2 (-0.6) + (2/3) 3 (0.2 + 0.6) 1.0
    # + 0.4 u[2, perm = 1] / 3 = 0.12 + 1.6 - 0.04 / 3; d = 1: weight 0.125 on (2/3) 3 (0.3 - 0.9)
    assert U[0, 2, 0] == pytest.approx(0.12 + 1.6 - 0.04 / 3, abs=1e-15)
    assert U[0, 2, 1] == pytest.approx(-0.06 - 0.2 * 0.9 - 2 * 0.6 * 0.125 + 0.4 * 0.0 / 3)
    # the best parcel feels no pressure: its velocity is the same with or without the draws
    np.testing.assert_array_equal(U[0, 1], run_kernel()[1][0, 1])
    for i in range(3):
        for d in range(2):
            assert U[0, i, d] == pytest.approx(hand_velocity(i, d, (0, 0), 0.0, rp=True), abs=1e-15)


def test_noise_adds_sigma_times_xi_and_nothing_else():
    base = run_kernel(centre=1)[1]
    noisy = run_kernel(centre=1, sigma=0.05)[1]
    np.testing.assert_allclose(noisy - base, 0.05 * NOISE, rtol=0, atol=1e-15)


def test_velocity_clamp_caps_every_coordinate():
    U = run_kernel(vmax=0.1)[1]
    ref = np.array([[[hand_velocity(i, d, (0, 0), 0) for d in range(2)] for i in range(3)]])
    np.testing.assert_allclose(U, np.clip(ref, -0.1, 0.1), rtol=0, atol=1e-15)


def test_midpoint_bound_lands_halfway_to_the_crossed_bound():
    # parcel 2, d = 1 starts at 0.9; a noise draw making its velocity +0.5 would take it to
    # 1.2 (clamped to vmax): it lands halfway between 0.9 and the bound 1, at 0.95
    noise = np.zeros_like(NOISE)  # only this coordinate is pushed
    noise[0, 2, 1] = 0.5 - hand_velocity(2, 1, (0.0, 0.0), 0.0)
    # vmax 0.3 keeps every other coordinate inside (|p| <= 0.7 there): only (2, 1) leaves
    Pm, Um, Xm = run_kernel(sigma=1.0, midpoint=True, vmax=0.3, noise=noise)
    Pc, Uc, _ = run_kernel(sigma=1.0, midpoint=False, vmax=0.3, noise=noise)
    assert Pm[0, 2, 1] == pytest.approx(0.95, abs=1e-15)
    assert Um[0, 2, 1] == pytest.approx(0.05, abs=1e-15)  # the step actually taken
    assert Pc[0, 2, 1] == 1.0 and Uc[0, 2, 1] == pytest.approx(0.3)  # WDO's clip
    assert Xm[0, 2, 1] == pytest.approx(-5.0 + 1.95 / 2 * 10.0)
    # the other coordinates are the same under both rules
    mask = np.ones_like(Pm, bool)
    mask[0, 2, 1] = False
    np.testing.assert_array_equal(Pm[mask], Pc[mask])


def test_all_components_off_is_wdos_kernel():
    rng = np.random.default_rng(4)
    R, N, D = 3, 6, 5
    p, u = rng.uniform(-1, 1, (R, N, D)), rng.uniform(-0.3, 0.3, (R, N, D))
    pb, pbf = rng.uniform(-1, 1, (R, N, D)), rng.random((R, N))
    rank = np.argsort(np.argsort(pbf, 1), 1) + 1.0
    perm = np.stack([[rng.permutation(D) for _ in range(N)] for _ in range(R)]).astype(np.int16)
    lb, width = np.full(D, -3.0), np.full(D, 6.0)
    P1, U1, X1 = p.copy(), u.copy(), np.empty((R, N, D))
    plus_step(P1, U1, pb, pbf, rank, np.zeros(R), np.zeros(R, bool), COEF, 0, 0.3, False, False,
              perm, np.zeros((R, N, D)), np.ones((R, N, D)), NO_RNG, False, lb, width,
              X1)  # fmt: skip
    P2, U2, X2 = p.copy(), u.copy(), np.empty((R, N, D))
    wind_step(P2, U2, pb, pbf, rank, perm, np.ones((1, 4), np.uint64), False, 0, COEF[None, None],
              group_starts(N, 1), 0, np.zeros(3), False, 1.0, False, False, 0.3, False, 0.5, lb,
              width, X2)  # fmt: skip
    np.testing.assert_array_equal(P1, P2)
    np.testing.assert_array_equal(U1, U2)
    np.testing.assert_array_equal(X1, X2)


def test_in_kernel_draws_are_each_parcels_permutation_then_one_word_per_coordinate():
    rng = np.random.default_rng(9)
    R, N, D = 2, 4, 7
    p, u = rng.uniform(-1, 1, (R, N, D)), rng.uniform(-0.3, 0.3, (R, N, D))
    pb, pbf = rng.uniform(-1, 1, (R, N, D)), rng.random((R, N))
    rank = np.tile(np.arange(1.0, N + 1), (R, 1))
    state = rng.integers(1, 2**63, (R, 4), dtype=np.int64).astype(np.uint64)
    W = words_per_permutation(D)
    perm, noise, press = np.empty((R, N, D), np.int16), np.empty((R, N, D)), np.empty((R, N, D))
    final = []
    for r in range(R):
        words, s = python_xoshiro(state[r], N * (W + D))
        final.append(s)
        for i in range(N):
            block = words[i * (W + D) : (i + 1) * (W + D)]
            perm[r, i] = python_shuffle(block[:W], D)[0]
            # low half -> noise, high half -> pressure weight, each k / 2**32
            noise[r, i] = [(2 * ((w & 0xFFFFFFFF) / 2**32) - 1) * np.sqrt(3) for w in block[W:]]
            press[r, i] = [(w >> 32) / 2**32 for w in block[W:]]
    out = []
    for use_rng in (False, True):
        P, U, X, st = p.copy(), u.copy(), np.empty((R, N, D)), state.copy()
        plus_step(P, U, pb, pbf, rank, np.full(R, 0.07), np.zeros(R, bool), COEF, 1, 0.3, True,
                  True, perm, noise, press, st, use_rng, np.zeros(D), np.ones(D), X)  # fmt: skip
        out.append((P, U))
    np.testing.assert_array_equal(out[0][0], out[1][0])
    np.testing.assert_array_equal(out[0][1], out[1][1])
    assert st.tolist() == final


def test_held_runs_are_returned_unmoved_and_draw_nothing():
    R, N, D = 2, 3, 2
    p = np.tile(P0, (R, 1, 1))
    st = np.array([[1, 2, 3, 4], [5, 6, 7, 8]], np.uint64)
    P, U, X = p.copy(), np.tile(U0, (R, 1, 1)), np.empty((R, N, D))
    plus_step(P, U, np.tile(PB, (R, 1, 1)), np.tile(PBF, (R, 1)), np.tile(RANK, (R, 1)),
              np.full(R, 0.1), np.array([True, False]), COEF, 1, 0.3, True, True, PERM, NOISE,
              PRESS, st, True, np.zeros(D), np.full(D, 2.0), X)  # fmt: skip
    np.testing.assert_array_equal(P[0], p[0])
    np.testing.assert_array_equal(X[0], p[0] + 1.0)
    assert st[0].tolist() == [1, 2, 3, 4] and st[1].tolist() != [5, 6, 7, 8]
    assert not np.array_equal(P[1], p[1])


def test_success_rule_by_hand():
    # exp((0.6 - 0.2) / 0.8) = e^0.5; exp((0 - 0.2) / 0.8) = e^-0.25; capped at vmax
    out = success_sigma(np.array([0.1, 0.1, 0.25]), np.array([0.6, 0.0, 1.0]), 0.2, 1.0, 0.3)
    np.testing.assert_allclose(out, [0.1 * np.e**0.5, 0.1 * np.e**-0.25, 0.3], rtol=1e-15)
    # damp 2 halves the exponent
    assert success_sigma(np.array([1.0]), np.array([0.6]), 0.2, 2.0, 9.0)[0] == pytest.approx(
        np.e**0.25
    )


def test_stall_counter_and_restart_mask_by_hand():
    best = np.array([np.inf, 1.0, 1.0, 5.0])
    run_best = np.array([3.0, 1.0 - 1e-13, 0.5, 5.0])  # first finite, within tol, better, same
    stall = np.array([0, 2, 2, 2])
    sigma = np.array([0.1, 0.1, 0.1, 1e-12])
    b, s, mask = stalled(best, stall, run_best, 3, sigma, 1e-9)
    np.testing.assert_array_equal(b, [3.0, 1.0 - 1e-13, 0.5, 5.0])
    np.testing.assert_array_equal(s, [0, 3, 0, 3])
    np.testing.assert_array_equal(mask, [False, True, False, True])


def numpy_tell(F, p, pbest, pbest_f, sigma, hold, best, stall, adapt, limit, sigma_min):
    """WDO+'s bookkeeping as the NumPy rule (the pre-kernel ``tell``): new arrays."""
    if adapt and (~hold).any():
        gain = success_sigma(sigma, (F < pbest_f).mean(axis=1), 0.2, 0.5, 0.3)
        sigma = np.where(~hold, gain, sigma)
    better = F < pbest_f
    pbest = np.where(better[..., None], p, pbest)
    pbest_f = np.where(better, F, pbest_f)
    best, stall, mask = stalled(best, stall, pbest_f.min(axis=1), limit, sigma, sigma_min)
    return pbest, pbest_f, sigma, best, stall, mask


@pytest.mark.parametrize("adapt", [True, False])
def test_fused_tell_is_the_numpy_rule_bit_for_bit(adapt):
    R, N, D, limit = 64, 7, 3, 4
    rng = np.random.default_rng(3)
    pbest, pbest_f = rng.uniform(-1, 1, (R, N, D)), np.full((R, N), np.inf)
    sigma, best = rng.uniform(0, 0.3, R), np.full(R, np.inf)
    stall, hold = np.zeros(R, np.int64), rng.random(R) < 0.2
    gain = np.exp((np.arange(N + 1) / N - 0.2) / (0.8 * 0.5)) if adapt else np.empty(0)
    sigma_min = 0.02 if adapt else -1.0
    seen = set()
    for _ in range(40):
        p = rng.uniform(-1, 1, (R, N, D))
        # few distinct values: ties with the personal bests, repeats of the run's best
        F = rng.integers(0, 6, (R, N)).astype(float) + rng.integers(0, 2, R)[:, None] * 1e-13
        F[rng.random((R, N)) < 0.03] = np.nan
        want = numpy_tell(F, p, pbest, pbest_f, sigma, hold, best, stall, adapt, limit,
                          sigma_min)  # fmt: skip
        f, mask = np.empty((R, N)), np.empty(R, bool)
        n = plus_tell(F, p, f, pbest, pbest_f, sigma, hold, gain, 0.3, best, stall, limit,
                      sigma_min, True, mask)  # fmt: skip
        got = pbest, pbest_f, sigma, best, stall, mask
        for a, b in zip(got, want, strict=True):
            assert np.array_equal(a, b, equal_nan=True)
        assert n == mask.sum() and not hold.any()
        np.testing.assert_array_equal(f, F)
        seen.update(mask.nonzero()[0].tolist())
        pbest_f[mask], best[mask], stall[mask] = np.inf, np.inf, 0  # the restart's resets
        hold = mask.copy()
    assert len(seen) > R // 2  # the stall test fired on most runs


def test_a_flat_function_restarts_every_stall_plus_one_iterations():
    opt = make_optimizer("wdo_plus", pop_size=5, stall=2)
    res = minimize(lambda X: np.zeros(X.shape[:-1]), algorithm=opt, dim=3, runs=2, seed=1,
                   max_iter=7, lb=-1.0, ub=1.0)  # fmt: skip
    # a flat function never improves after the first value: a restart every stall + 1 = 3
    # iterations (2 of stall, then the held evaluation of the fresh population)
    assert res.metadata["restarts"].tolist() == [2, 2]


def test_restart_redraws_the_stalled_run_from_its_own_stream_and_leaves_the_other():
    opt = make_optimizer("wdo_plus", pop_size=4, stall=3)
    streams = RunStreams.from_seed_sequences(run_seed_sequences(5, 2))
    s = opt.init(Space(np.full(2, -1.0), np.full(2, 1.0)), streams, 100)
    X = opt.ask(s)
    s = opt.tell(s, X, np.ones((2, 4)))  # the first values: both runs' best is 1
    X = opt.ask(s)
    s.stall[:] = [2, 2]
    s.sigma[:] = [0.01, 0.02]
    before = s.p.copy()
    twin = copy.deepcopy(streams.generators[0])  # what run 0's stream draws next
    s = opt.tell(s, X, np.array([[1.0] * 4, [0.5] * 4]))  # run 0 stalls a third time, run 1 not
    np.testing.assert_array_equal(s.p[0], twin.uniform(size=(4, 2)) * 2.0 - 1.0)
    np.testing.assert_array_equal(s.p[1], before[1])
    assert s.hold.tolist() == [True, False] and s.restarts.tolist() == [1, 0]
    assert s.sigma[0] == 0.05 and s.sigma[1] != 0.05  # reset to sigma0 / adapted
    assert np.isinf(s.pbest_f[0]).all() and (s.pbest_f[1] == 0.5).all()
    assert s.stall.tolist() == [0, 0] and (s.u[0] == 0).all()


@pytest.mark.parametrize("evals", [997, 1000, 2003])
def test_budget_is_met_exactly(evals):
    res = minimize("rastrigin", algorithm="wdo_plus", dim=4, runs=3, seed=2, max_evals=evals,
                   stall=3)  # fmt: skip
    assert res.nfev.tolist() == [evals] * 3
    assert res.metadata["restarts"].min() > 0  # the restarts' evaluations are counted too


def test_same_seed_same_runs_whatever_the_split():
    kw = {"algorithm": "wdo_plus", "dim": 5, "seed": 11, "max_evals": 3000, "stall": 5}
    whole = minimize("rastrigin", runs=4, **kw)
    parts = [minimize("rastrigin", runs=2, first_run=k, **kw) for k in (0, 2)]
    np.testing.assert_array_equal(whole.fun, np.concatenate([q.fun for q in parts]))
    np.testing.assert_array_equal(whole.x, np.concatenate([q.x for q in parts]))
    assert whole.metadata["restarts"].tolist() == [
        *parts[0].metadata["restarts"],
        *parts[1].metadata["restarts"],
    ]


def test_sigma0_above_vmax_or_zero_with_adaptation_is_refused():
    with pytest.raises(ValueError, match="sigma0=0.5 must not exceed vmax=0.3"):
        make_optimizer("wdo_plus", sigma0=0.5)
    with pytest.raises(ValueError, match="sigma0=0 cannot adapt: give sigma0 > 0, or adapt=False"):
        make_optimizer("wdo_plus", sigma0=0.0)
    assert make_optimizer("wdo_plus", sigma0=0.0, adapt=False).params.sigma0 == 0.0
