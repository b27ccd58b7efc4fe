"""Statistics against hand-computed cases and against scipy on fixed samples."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy import stats as sps

from mawdo.experiments.stats import compare, friedman, holm, ranksum, summarize


def normal_two_sided(z: float) -> float:
    return math.erfc(abs(z) / math.sqrt(2.0))


# ---------------------------------------------------------------------------- summaries
def test_summary_by_hand():
    s = summarize([4.0, 1.0, 3.0, 2.0])
    assert (s.n, s.best, s.mean, s.median, s.worst) == (4, 1.0, 2.5, 2.5, 4.0)
    assert s.std == pytest.approx(math.sqrt(5.0 / 3.0))  # sum of squares 5, ddof=1


def test_summary_of_one_value_has_undefined_std():
    s = summarize([7.0])
    assert s.best == s.mean == 7.0 and math.isnan(s.std)


# ---------------------------------------------------------------------------- rank-sum
def test_ranksum_hand_case_without_ties():
    # a = 0..9 all below b = 10..19: U_a = 0, mu = 50, sigma^2 = 100 * 21 / 12
    r = ranksum(np.arange(10.0), np.arange(10.0, 20.0))
    z = (50 - 0.5) / math.sqrt(100 * 21 / 12)
    assert r.statistic == 0.0
    assert r.pvalue == pytest.approx(normal_two_sided(z), rel=1e-12)
    assert r.sign == "+"
    worse = ranksum(np.arange(10.0, 20.0), np.arange(10.0))
    assert worse.statistic == 100.0 and worse.sign == "-"
    assert worse.pvalue == pytest.approx(r.pvalue, rel=1e-12)


def test_ranksum_small_samples_not_significant():
    # n = 3 + 3, complete separation: z = (4.5 - 0.5) / sqrt(9 * 7 / 12), p ~ 0.081 > 0.05
    r = ranksum([1.0, 2.0, 3.0], [4.0, 5.0, 6.0])
    assert r.pvalue == pytest.approx(normal_two_sided(4.0 / math.sqrt(9 * 7 / 12)), rel=1e-12)
    assert r.pvalue > 0.05 and r.sign == "="


def test_ranksum_hand_case_with_ties():
    a = [1.0, 1.0, 2.0, 2.0, 2.0, 3.0]
    b = [2.0, 3.0, 3.0, 3.0, 4.0, 4.0]
    # pooled ranks: 1,1 -> 1.5; four 2s -> 4.5; four 3s -> 8.5; two 4s -> 11.5
    r1 = 1.5 * 2 + 4.5 * 3 + 8.5
    u = r1 - 6 * 7 / 2
    ties = sum(t**3 - t for t in (2, 4, 4, 2))
    n = 12
    var = 36 / 12 * ((n + 1) - ties / (n * (n - 1)))
    z = (abs(u - 18) - 0.5) / math.sqrt(var)
    r = ranksum(a, b)
    assert r.statistic == u == 4.0
    assert r.pvalue == pytest.approx(normal_two_sided(z), rel=1e-12)
    assert r.sign == ("+" if r.pvalue < 0.05 else "=")


def test_all_equal_samples_give_p_one():
    r = ranksum(np.zeros(30), np.zeros(30))
    assert (r.pvalue, r.sign) == (1.0, "=")


def test_identical_samples_give_p_one():
    x = [0.3, 1.0, 2.5, 2.5, 7.0]
    r = ranksum(x, list(reversed(x)))
    assert (r.pvalue, r.sign) == (1.0, "=")


def test_empty_sample_gives_p_one():
    assert ranksum([], [1.0, 2.0]).pvalue == 1.0


@pytest.mark.parametrize("shift", [0.0, 0.3, 0.8, -0.8])
def test_ranksum_agrees_with_scipy_on_fixed_samples(shift):
    rng = np.random.default_rng(2024)
    a = rng.normal(size=30)
    b = rng.normal(size=30) + shift
    a[:5] = b[:5]  # some ties across samples
    ref = sps.mannwhitneyu(a, b, alternative="two-sided", method="asymptotic")
    r = ranksum(a, b)
    assert r.statistic == ref.statistic and r.pvalue == pytest.approx(ref.pvalue, rel=1e-12)
    # sign follows the mean ranks: lower mean rank of a = a better
    ranks = sps.rankdata(np.concatenate([a, b]))
    a_better = ranks[:30].mean() < ranks[30:].mean()
    expected = "=" if ref.pvalue >= 0.05 else ("+" if a_better else "-")
    assert r.sign == expected


def test_signs_are_decided_on_both_sides():
    # the parametrised cases above must exercise +, - and = at least once
    rng = np.random.default_rng(2024)
    a = rng.normal(size=30)
    b = rng.normal(size=30)
    assert ranksum(a, b + 0.8).sign == "+"
    assert ranksum(a, b - 0.8).sign == "-"


# ---------------------------------------------------------------------------- Holm
def test_holm_hand_case():
    # sorted: 0.005*4 = 0.02, 0.01*3 = 0.03, 0.03*2 = 0.06, 0.04*1 = 0.04 -> max(0.06, .04)
    got = holm([0.01, 0.04, 0.03, 0.005])
    np.testing.assert_allclose(got, [0.03, 0.06, 0.06, 0.02], rtol=1e-12)


def test_holm_caps_at_one_and_single_test_is_unchanged():
    np.testing.assert_allclose(holm([0.5, 0.6, 0.01]), [1.0, 1.0, 0.03])
    assert holm([0.2])[0] == 0.2


@settings(max_examples=100, deadline=None)
@given(st.lists(st.floats(0.0, 1.0), min_size=1, max_size=30))
def test_holm_properties(p):
    p = np.array(p)
    adj = holm(p)
    assert np.all(adj >= p - 1e-15) and np.all(adj <= 1.0)
    order = np.argsort(p, kind="stable")
    assert np.all(np.diff(adj[order]) >= 0)  # monotone in the raw p-values
    assert np.all(adj <= np.minimum(1.0, p * p.size) + 1e-15)  # never above Bonferroni


def test_compare_applies_holm_over_the_whole_family():
    rng = np.random.default_rng(5)
    samples = {}
    for f in ("f1", "f2"):
        samples["ref", f] = rng.normal(size=20)
        samples["r1", f] = rng.normal(size=20) + 1.0
        samples["r2", f] = rng.normal(size=20)
    comps = compare(samples, "ref", ["r1", "r2"], ["f1", "f2"])
    assert [(c.function, c.rival) for c in comps] == [
        ("f1", "r1"),
        ("f1", "r2"),
        ("f2", "r1"),
        ("f2", "r2"),
    ]
    np.testing.assert_allclose([c.p_holm for c in comps], holm([c.pvalue for c in comps]))
    for c in comps:
        assert c.sign_holm == ("=" if c.p_holm >= 0.05 else c.sign)
    assert comps[0].sign == "+"


# ---------------------------------------------------------------------------- Friedman
def test_friedman_hand_case():
    table = np.array([[1.0, 2.0, 3.0], [2.0, 1.0, 3.0], [1.0, 3.0, 2.0], [1.0, 2.0, 3.0]])
    fr = friedman(table, ["a", "b", "c"])
    np.testing.assert_allclose(fr.mean_ranks, [5 / 4, 8 / 4, 11 / 4])
    n, k = 4, 3
    rank_sums = np.array([5.0, 8.0, 11.0])
    chi2 = 12 / (n * k * (k + 1)) * np.sum(rank_sums**2) - 3 * n * (k + 1)
    assert fr.statistic == pytest.approx(chi2)  # 4.5
    assert fr.pvalue == pytest.approx(math.exp(-chi2 / 2))  # chi-square, 2 dof
    assert fr.n_functions == 4


def test_friedman_ties_are_averaged_and_match_scipy():
    table = np.array([[0.0, 0.0, 1.0, 2.0], [1e-3, 5.0, 5.0, 5.0], [3.0, 1.0, 2.0, 4.0]])
    fr = friedman(table, list("abcd"))
    np.testing.assert_allclose(
        fr.mean_ranks, [(1.5 + 1 + 3) / 3, (1.5 + 3 + 1) / 3, (3 + 3 + 2) / 3, (4 + 3 + 4) / 3]
    )
    ref = sps.friedmanchisquare(*table.T)
    assert fr.statistic == pytest.approx(ref.statistic) and fr.pvalue == pytest.approx(ref.pvalue)


def test_friedman_all_tied_gives_p_one_and_skips_nan_rows():
    fr = friedman(np.zeros((5, 3)), ["a", "b", "c"])
    assert fr.pvalue == 1.0
    np.testing.assert_allclose(fr.mean_ranks, 2.0)
    fr = friedman(np.array([[1.0, 2.0, 3.0], [np.nan, 1.0, 2.0], [1.0, 2.0, 3.0]]), "abc")
    assert fr.n_functions == 2


def test_friedman_needs_three_algorithms_for_the_test():
    fr = friedman(np.array([[1.0, 2.0], [2.0, 1.0], [1.0, 2.0]]), ["a", "b"])
    assert math.isnan(fr.pvalue)
    np.testing.assert_allclose(fr.mean_ranks, [4 / 3, 5 / 3])
