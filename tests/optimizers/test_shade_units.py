"""Hand-checked pieces of L-SHADE, jSO and NL-SHADE-RSP: the memory update (weighted Lehmer
mean), the population size schedules, the archive, the removal loop and the index draws."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy import stats

from mawdo import minimize
from mawdo.budget import Budget
from mawdo.optimizers import shade_ops as ops
from mawdo.optimizers.base import Space
from mawdo.optimizers.lshade import generations, initial_size, next_size, plan_evaluations
from mawdo.optimizers.nlshade_rsp import (
    archive_probability,
    rank_capped,
    remove_worst_as_coded,
    uniform_capped,
)
from mawdo.optimizers.registry import make_optimizer
from mawdo.streams import RunStreams
from tests.optimizers import shade_literal as lit

# -- the memory update ------------------------------------------------------------------------


def test_weighted_lehmer_mean_by_hand():
    # successes F = 0.5 (improvement 1) and 1.0 (improvement 3): w = 1/4, 3/4
    F = np.array([[0.5, 0.9, 1.0]])
    delta = np.array([[1.0, 7.0, 3.0]])
    success = np.array([[True, False, True]])
    w = ops.lehmer_weights(delta, success)
    np.testing.assert_array_equal(w, [[0.25, 0.0, 0.75]])
    num, den = ops.lehmer_terms(F, w)
    assert num[0] == pytest.approx(0.25 * 0.25 + 0.75 * 1.0)  # 0.8125
    assert den[0] == pytest.approx(0.25 * 0.5 + 0.75 * 1.0)  # 0.875
    assert num[0] / den[0] == pytest.approx(13 / 14)


def memory_state(name, R=2, N=6, D=3, **options):
    opt = make_optimizer(name, pop_size=N, **options)
    streams = RunStreams([np.random.default_rng(k) for k in range(R)])
    st = opt.init(Space(np.full(D, -1.0), np.full(D, 1.0)), streams, 1000)
    return opt, st


def test_lshade_memory_update_and_terminal_cr():
    opt, st = memory_state("lshade")
    st.Fi = np.array([[0.5, 0.9, 1.0, 0.2, 0.2, 0.2], [0.4, 0.6, 0.8, 0.3, 0.3, 0.3]])
    st.CRi = np.array([[0.2, 0.7, 0.6, 0.1, 0.1, 0.1], [0.0, 0.0, 0.0, 0.9, 0.9, 0.9]])
    better = np.array([[True, False, True, False, False, False], [True, True, True] + [False] * 3])
    delta = np.array([[1.0, 9, 3, 9, 9, 9], [1.0, 1, 2, 9, 9, 9]])
    opt._update_memory(st, better, delta)
    assert st.MF[0, 0] == pytest.approx(13 / 14)
    assert st.MCR[0, 0] == pytest.approx((0.25 * 0.04 + 0.75 * 0.36) / (0.25 * 0.2 + 0.75 * 0.6))
    # run 1: every successful CR is 0 -> the terminal value -1; F by weights 1/4, 1/4, 1/2
    assert st.MCR[1, 0] == -1.0
    assert st.MF[1, 0] == pytest.approx((0.04 + 0.09 + 0.32) / (0.1 + 0.15 + 0.4))
    np.testing.assert_array_equal(st.k, [1, 1])
    assert np.all(st.MF[:, 1:] == 0.5)  # the other entries untouched
    # a generation without success leaves the memory and its position alone
    opt._update_memory(st, np.zeros_like(better), delta)
    np.testing.assert_array_equal(st.k, [1, 1])


def test_jso_memory_is_averaged_with_the_old_entry():
    opt, st = memory_state("jso", R=1)
    st.Fi, st.CRi = np.array([[0.5, 1.0, 0.3, 0.3, 0.3, 0.3]]), np.zeros((1, 6))
    better = np.array([[True, True, False, False, False, False]])
    opt._update_memory(st, better, np.array([[1.0, 3.0, 1, 1, 1, 1]]))
    assert st.MF[0, 0] == pytest.approx((13 / 14 + 0.3) / 2)  # jSO: M_F starts at 0.3
    assert st.MCR[0, 0] == pytest.approx((-1 + 0.8) / 2)  # terminal -1 averaged with 0.8


def test_nlshade_memory_mean_and_reset():
    opt, st = memory_state("nlshade_rsp", R=2, N=4, D=2)
    CR = np.array([[0.5, 1.0, 0.2, 0.2], [0.0, 0.0, 0.0, 0.0]])
    F = np.full((2, 4), 0.6)
    success = np.array([[True, True, False, False], [True, False, False, False]])
    delta = np.array([[1.0, 3.0, 0, 0], [2.0, 0, 0, 0]])
    opt._update_memory(st, success, delta, CR, F)
    assert st.MCR[0, 0] == pytest.approx(13 / 14) and st.MF[0, 0] == pytest.approx(0.6)
    assert st.MCR[1, 0] == 0.5  # |sum w CR| <= 1e-6: the code's 0.5
    np.testing.assert_array_equal(st.k, [1, 1])
    st.MF[:, 1] = st.MCR[:, 1] = 0.9
    opt._update_memory(st, np.zeros_like(success), delta, CR, F)  # no success: reset in place
    np.testing.assert_array_equal(st.k, [1, 1])
    assert np.all(st.MF[:, 1] == 0.5) and np.all(st.MCR[:, 1] == 0.5)


def test_infinite_improvements_share_the_weight():
    """A parent with a non-finite value (+inf) improved by a finite trial: the authors' sums
    would be inf/inf; the infinite improvements share the weights equally."""
    delta = np.array([[np.inf, 2.0, np.inf, 5.0], [1e308, 1e308, 1.0, 0.0]])
    success = np.array([[True, True, True, False], [True, True, True, False]])
    w = ops.lehmer_weights(delta, success)
    np.testing.assert_array_equal(w[0], [0.5, 0.0, 0.5, 0.0])
    np.testing.assert_allclose(w[1], [0.5, 0.5, 0.5e-308, 0.0])  # the sum overflows: scaled


# -- the population size schedules ------------------------------------------------------------


def test_c_round_and_the_linear_schedule():
    assert [ops.c_round(x) for x in (2.5, -2.5, 0.49999999999999994, 91.5, 1.32)] == [
        3, -3, 0, 92, 1,
    ]  # fmt: skip
    # L-SHADE, D = 10: N_0 = 180, M = 100 000
    assert initial_size("18D", 10) == 180
    assert initial_size("25sqrtDlnD", 10) == 182  # round(25 sqrt(10) ln 10) = round(182.03)
    assert ops.lpsr_size(180, 100_000, 180, 4) == 180  # round(-0.000176*180 + 180) = 180
    assert ops.lpsr_size(50_000, 100_000, 180, 4) == 92  # round(-88 + 180)
    assert ops.lpsr_size(100_000, 100_000, 180, 4) == 4
    assert ops.lpsr_size(150_000, 100_000, 180, 4) == 4  # never below N_min
    assert next_size(50_000, 100_000, 80, 180) == 80  # sizes only fall


def test_nonlinear_schedule_by_hand():
    # NL-SHADE-RSP, D = 10: N_0 = 300, M = 200 000; at half the budget x^(1-x) = sqrt(1/2)
    new, raw = ops.nonlinear_size(100_000, 200_000, 300, 4)
    assert raw == round(-296 * math.sqrt(0.5) + 300) == 91 and new == 91
    assert ops.nonlinear_size(0, 200_000, 300, 4) == (300, 300)
    assert ops.nonlinear_size(200_000, 200_000, 300, 4) == (4, 4)
    assert int(91 * 2.1) == 191  # the archive size the code derives from it


def test_iteration_budgets_plan_the_evaluations_their_schedule_needs():
    reduce = lambda nfes, m, n: next_size(nfes, m, n, 24)  # noqa: E731
    M = plan_evaluations(Budget(max_iter=40), 24, reduce)
    assert generations(M, 24, reduce) >= 40 > generations(M - 1, 24, reduce)
    assert plan_evaluations(Budget(max_evals=777), 24, reduce) == 777
    assert plan_evaluations(Budget(max_iter=40, max_evals=100), 24, reduce) == 100


@pytest.mark.parametrize("name", ["lshade", "jso", "nlshade_rsp"])
def test_runs_shrink_in_lock_step_and_spend_the_budget(name):
    res = minimize(lambda X: (X**2).sum(1), [(-3, 3)] * 4, algorithm=name, runs=3, seed=1,
                   max_evals=2000, pop_size=40)  # fmt: skip
    per_iteration = np.diff(res.history_nfev, axis=1)
    assert np.all(per_iteration == per_iteration[0])  # every run evaluates the same sizes
    sizes = per_iteration[0]
    assert sizes[0] == 40 and sizes[-1] <= 40 and np.all(np.diff(sizes[:-1]) <= 0)
    assert np.all(res.nfev == 2000)


# -- the archive ------------------------------------------------------------------------------


def test_archive_fills_then_replaces_random_members_in_order():
    archive = np.zeros((1, 3, 1))
    archive[0, :2, 0] = [10.0, 11.0]
    parents = np.arange(5.0).reshape(1, 5, 1)
    inserted = np.array([[True, False, True, True, True]])
    u = np.array([[0.9, 0.0, 0.5, 0.1, 0.2]])  # slots 0.5*3 -> 1, 0.1*3 -> 0, 0.2*3 -> 0
    n = ops.archive_insert(archive, np.array([2]), 3, parents, inserted, u)
    assert n.tolist() == [3]
    # parent 0 appended in slot 2; then 2 -> slot 1, 3 -> slot 0, 4 -> slot 0 (the last wins)
    np.testing.assert_array_equal(archive[0, :, 0], [4.0, 2.0, 0.0])
    assert ops.archive_insert(archive, n, 0, parents, inserted, u).tolist() == [3]  # no archive


def test_lshade_archive_is_cut_to_its_first_members_when_the_population_shrinks():
    opt, st = memory_state("lshade", R=1, N=20, D=2)
    st.arc_size, st.n_arc = 52, np.array([50])
    st.archive = np.arange(52.0 * 2).reshape(1, 52, 2)
    before = st.archive.copy()
    st.F = np.arange(20.0)[None, ::-1].copy()  # member 0 is the worst
    st.nfes = 250  # plan round(-16/1000 * 250 + 20) = 16
    opt._reduce(st)
    assert st.X.shape[1] == 16 and st.arc_size == int(16 * 2.6) == 41
    assert st.n_arc.tolist() == [41]
    np.testing.assert_array_equal(st.archive, before)  # the first 41 stay where they were
    np.testing.assert_array_equal(st.F[0], np.arange(15.0, -1, -1))  # the 4 worst went
    assert st.p_num == max(2, ops.c_round(16 * 0.11))


# -- NL-SHADE-RSP's removal loop and archive probability --------------------------------------


def test_removal_as_coded_by_hand_and_against_the_literal_loop():
    F = np.array([[5.0, 1.0, 3.0, 9.0]])
    X = F[..., None].copy()
    # the worst is last: the shift does nothing, the rescan finds it again, and the first two
    # are kept, where removing the two worst keeps [1, 3]
    assert remove_worst_as_coded(X, F, 2)[1].tolist() == [[5.0, 1.0]]
    assert np.take_along_axis(F, ops.keep_best(F, 2), 1).tolist() == [[1.0, 3.0]]
    rng = np.random.default_rng(3)
    for _ in range(300):
        N = int(rng.integers(4, 12))
        F = rng.integers(0, 6, (1, N)).astype(float)  # ties too
        n = N - int(rng.integers(0, 4))
        pop, fit = lit.remove_worst(list(range(N)), F[0].tolist(), N, n)
        Xo, Fo = remove_worst_as_coded(np.arange(N, dtype=float)[None, :, None], F, n)
        assert Fo[0].tolist() == fit and Xo[0, :, 0].tolist() == pop


def test_archive_probability_follows_the_code():
    gain = np.array([[0.5, 0.1, 0.2, 0.0], [0.3, 0.3, 0.3, 0.3], [0.1, 0.1, 0.0, 0.0]])
    accepted = np.array([[True, True, True, False], [True] * 4, [False, True, True, True]])
    used = np.array([[True, False, False, True], [True] * 4, [True, False, False, False]])
    p = archive_probability(gain, accepted, used)
    a, b = 0.5 / 1, (0.1 + 0.2) / (4 - 1)  # NArchUsages counts the accepted users only
    assert p[0] == pytest.approx(a / (a + b))
    assert p[1] == 0.9  # all users: 0/0 = NaN, which std::min(0.9, NaN) turns into 0.9
    assert p[2] == 0.5  # no accepted archive user


# -- the index draws: the codes' rejection loops, one uniform each ----------------------------


def test_index_excluding_is_uniform_on_the_allowed_indices():
    u = np.random.default_rng(0).random(60_000)
    me, r1 = np.full(u.shape, 2), np.full(u.shape, 5)
    k = ops.index_excluding(u, 7, me, r1)
    counts = np.bincount(k, minlength=7)
    assert counts[2] == counts[5] == 0
    assert stats.chisquare(counts[[0, 1, 3, 4, 6]]).pvalue > 1e-3
    for ui in u[:200]:  # and the same index as the literal port's pick from the allowed list
        assert ops.index_excluding(np.array(ui), 7, np.array(2), np.array(5)) == lit.pick(
            ui, [0, 1, 3, 4, 6]
        )


def test_capped_draws_match_the_literal_law():
    rng = np.random.default_rng(1)
    N = 9
    w = [math.exp(-i / N) for i in range(N)]
    for _ in range(400):
        u = rng.random()
        excl = [int(x) for x in rng.integers(0, N, 3)]
        k = rank_capped(np.array([u]), N, [np.array([e]) for e in excl], 26)[0]
        assert k == lit.capped(u, w, excl, 26)
        e = int(rng.integers(-1, N))
        k = uniform_capped(np.array([u]), N, np.array([e]), 25)[0]
        assert k == lit.capped(u, [1.0] * N, [e] if e >= 0 else [], 25)
    # u below q^draws lands on an excluded index, as the code's 26th failed draw does
    assert rank_capped(np.array([0.0]), N, [np.array([0])] * 3, 26)[0] == 0


def test_truncated_cauchy_has_the_law_of_the_rejection_loop():
    u = np.random.default_rng(2).random(20_000)
    for mu in (0.05, 0.5, 0.9):
        F = ops.truncated_cauchy(np.full(u.shape, mu), u)
        assert np.all(F > 0)
        c = stats.cauchy(mu, 0.1)
        cdf = lambda x, c=c: (c.cdf(x) - c.cdf(0)) / c.sf(0)  # noqa: E731
        assert stats.kstest(F, cdf).pvalue > 1e-3
