"""The batched ``purecmaes_wdo`` port against a literal one-run transcription of the source."""

from __future__ import annotations

import numpy as np
import pytest

from mawdo.optimizers.purecmaes import PureCMAES, Settings
from tests.optimizers.purecmaes_literal import purecmaes_wdo


@pytest.mark.parametrize("lam", [7, 50])
def test_batched_port_follows_the_literal_transcription_run_by_run(lam):
    # 30 generations cross several eigen decompositions; integer fitness gives ties (MATLAB's
    # sort is stable), and hsig is false in some generations of each case. (Tolerances: the
    # summation orders differ, and 30 generations carry the rounding along.)
    R, n, gens = 3, 4, 30
    rng = np.random.default_rng(lam)
    mean0 = rng.random((R, n))
    arx = rng.random((R, lam, n))  # AWDO_v03.m's first samples: rand(4, popsize)
    es = PureCMAES.start(mean0, 0.5, lam)
    recs = [{"arx": arx[r].tolist()} for r in range(R)]
    eigen_updates = 0
    for it in range(2, 2 + gens):
        fit = np.round(rng.normal(size=(R, lam)) * 3) + (arx**2).sum(axis=2)
        fit[:, : lam // 3] = np.round(fit[:, : lam // 3])
        z = rng.normal(size=(R, lam, n))
        before = es.eigeneval
        es.tell(arx, fit, counteval=it)
        eigen_updates += es.eigeneval != before
        arx = es.sample(z)
        for r in range(R):
            recs[r] = purecmaes_wdo(it, recs[r], lam, fit[r].tolist(), mean0[r], z[r].tolist())
            np.testing.assert_allclose(es.xmean[r], recs[r]["xmean"], rtol=1e-10, atol=1e-11)
            np.testing.assert_allclose(es.sigma[r], recs[r]["sigma"], rtol=1e-11)
            np.testing.assert_allclose(es.C[r], recs[r]["C"], rtol=1e-10, atol=1e-11)
            np.testing.assert_allclose(arx[r], recs[r]["arx"], rtol=1e-9, atol=1e-10)
    assert eigen_updates >= 5


def test_settings_are_the_sources_constants_for_awdo():
    # N = 4, lambda = 50 (AWDO's air population): mu = 25, weights log(25.5) - log(k)
    s = Settings.make(4, 50)
    w = np.log(25.5) - np.log(np.arange(1, 26))
    np.testing.assert_allclose(s.weights, w / w.sum(), rtol=1e-15)
    assert s.mu == 25
    mueff = w.sum() ** 2 / (w**2).sum()
    assert s.mueff == pytest.approx(mueff, rel=1e-14)
    assert s.c1 == pytest.approx(2 / (5.3**2 + mueff), rel=1e-14)
    assert s.chin == pytest.approx(2 * (1 - 1 / 16 + 1 / 336), rel=1e-15)


def test_a_run_is_the_same_alone_or_in_a_batch():
    rng = np.random.default_rng(5)
    R, lam = 4, 9
    mean0, arx = rng.random((R, 4)), rng.random((R, lam, 4))
    batch = PureCMAES.start(mean0, 0.5, lam)
    alone = PureCMAES.start(mean0[2:3], 0.5, lam)
    xa, xb = arx.copy(), arx[2:3].copy()
    for it in range(2, 14):
        fit = (xa**2).sum(axis=2)
        z = rng.normal(size=(R, lam, 4))
        batch.tell(xa, fit, it)
        alone.tell(xb, fit[2:3], it)
        xa, xb = batch.sample(z), alone.sample(z[2:3])
        assert np.array_equal(xa[2], xb[0])
        assert np.array_equal(batch.C[2], alone.C[0])


def test_collapsed_samples_keep_finite_scales_and_the_step_size_stays_capped():
    # Identical samples leave the rank-mu update empty and the covariance decays toward
    # singular; the floor keeps D >= 1e-10 (and invsqrtC finite). A huge evolution path would
    # grow sigma past any float; the cap holds it at SIGMA_MAX.
    from mawdo.optimizers.purecmaes import EIG_FLOOR, SIGMA_MAX

    lam = 8
    es = PureCMAES.start(np.full((2, 4), 0.5), 0.5, lam)
    arx = np.full((2, lam, 4), 0.5)
    for it in range(2, 200):
        es.tell(arx, np.zeros((2, lam)), it)
    assert es.D.min() >= np.sqrt(EIG_FLOOR) and es.D.min() < 1e-6  # the floor held it
    assert np.isfinite(es.invsqrtC).all()
    assert np.isfinite(es.sample(np.ones((2, lam, 4)))).all()
    es.ps[:] = 1e300  # norm(ps) / chiN - 1 ~ 1e300: exp overflows to inf
    with np.errstate(over="ignore"):
        es.tell(arx, np.zeros((2, lam)), 200)
    assert (es.sigma == SIGMA_MAX).all()


def test_invalid_fitness_ranks_after_every_valid_one_even_at_large_values():
    from mawdo.optimizers.base import finite_last

    F = np.array(
        [[3.0, np.nan, 1e20, np.inf], [np.nan, np.nan, np.nan, np.nan], [1.0, 2.0, 0.0, 5.0]]
    )
    G = finite_last(F)
    assert np.isfinite(G).all()
    assert G[0, 1] > 1e20 and G[0, 3] > 1e20  # (1e20 + 1 would round back to 1e20)
    assert np.array_equal(G[0, [0, 2]], F[0, [0, 2]]) and (G[1] == 1.0).all()
    assert np.array_equal(G[2], F[2])
