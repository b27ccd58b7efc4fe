"""``ask_generation`` against the ``cmaes`` library itself: the same samples, bit for bit.

Two ``CMA`` objects in the same state (a ``deepcopy``, its generator's state copied too) are
driven side by side for many generations: one by ``lambda`` calls of the library's ``ask()``,
the other by :func:`ask_generation`; both are told the same values. The samples and the generators'
states must stay identical. The mean starts in a corner of the box so that most draws are
infeasible and ``ask()`` resamples; a small ``n_max_resampling`` forces its clipping path too.
"""

from __future__ import annotations

import copy

import numpy as np
import pytest
from cmaes import CMA

from mawdo.optimizers.cmaes_ref import ask_generation


def same_generator(a: np.random.RandomState, b: np.random.RandomState) -> bool:
    sa, sb = a.get_state(), b.get_state()
    return all(np.array_equal(x, y) for x, y in zip(sa, sb, strict=True))


def drive(cma: CMA, generations: int, target: np.ndarray) -> tuple[int, int]:
    """Run both ways; return (samples on a bound exactly, samples checked)."""
    twin = copy.deepcopy(cma)
    twin._rng.set_state(cma._rng.get_state())  # CMA's pickling drops the generator
    lam, on_bound, seen = cma.population_size, 0, 0
    for _ in range(generations):
        ref = np.stack([cma.ask() for _ in range(lam)])
        got = ask_generation(twin, lam)
        np.testing.assert_array_equal(got, ref)
        assert same_generator(cma._rng, twin._rng)
        if cma._bounds is not None:
            on_bound += int(np.any((ref == cma._bounds[:, 0]) | (ref == cma._bounds[:, 1])))
        seen += lam
        f = ((ref - target) ** 2).sum(axis=1).tolist()
        cma.tell(list(zip(ref, f, strict=True)))
        twin.tell(list(zip(got, f, strict=True)))
    np.testing.assert_array_equal(cma.mean, twin.mean)
    return on_bound, seen


@pytest.mark.parametrize("dim", [2, 5, 20])
def test_bounded_samples_equal_the_librarys_asks_with_resampling(dim):
    # mean in the corner of [0, 1]^D: a draw is feasible with probability ~2^-D, so ask()
    # resamples most draws (and clips after 100 failures at D = 20)
    bounds = np.tile([0.0, 1.0], (dim, 1))
    cma = CMA(mean=np.zeros(dim), sigma=0.3, bounds=bounds, seed=dim, population_size=9)
    drive(cma, 40, target=np.full(dim, -1.0))  # the optimum lies outside: the mean stays put


def test_the_clipping_path_is_reproduced():
    dim = 6
    bounds = np.tile([0.0, 1.0], (dim, 1))
    cma = CMA(mean=np.zeros(dim), sigma=0.5, bounds=bounds, seed=3, n_max_resampling=2)
    on_bound, _ = drive(cma, 30, target=np.full(dim, -1.0))
    # a Gaussian draw lands exactly on 0.0 or 1.0 with probability 0: these were clipped
    assert on_bound > 0


@pytest.mark.parametrize("resampling", [0, 1])
def test_no_resampling_budget_clips_every_draw_as_ask_does(resampling):
    dim = 4
    bounds = np.tile([-1.0, 1.0], (dim, 1))
    cma = CMA(mean=np.full(dim, 0.9), sigma=1.0, bounds=bounds, seed=5, n_max_resampling=resampling)
    drive(cma, 20, target=np.zeros(dim))


@pytest.mark.parametrize("dim", [4, 20])
def test_unbounded_samples_equal_the_librarys_asks(dim):
    # AWDO-CMA's use: no bounds, lambda = the air population
    cma = CMA(mean=np.full(dim, 0.5), sigma=0.5, seed=11, population_size=20)
    drive(cma, 60, target=np.linspace(-2, 2, dim))


def test_zero_samples_leave_the_cma_untouched():
    cma = CMA(mean=np.zeros(3), sigma=1.0, seed=1)
    twin = copy.deepcopy(cma)
    twin._rng.set_state(cma._rng.get_state())
    assert ask_generation(twin, 0).shape == (0, 3)
    assert twin._B is None and same_generator(cma._rng, twin._rng)


def test_both_generator_paths_are_taken(monkeypatch):
    # blocks that drew exactly what the samples used leave the generator as it is; blocks that
    # drew past them rewind it: the corner case above must meet both, so both are checked
    import mawdo.optimizers.cmaes_ref as ref

    seen = []
    accept = ref._accept_draws

    def spy(*args):
        out, used, drawn = accept(*args)
        seen.append(used == drawn)
        return out, used, drawn

    monkeypatch.setattr(ref, "_accept_draws", spy)
    for dim in (5, 20):
        bounds = np.tile([0.0, 1.0], (dim, 1))
        cma = CMA(mean=np.zeros(dim), sigma=0.3, bounds=bounds, seed=dim, population_size=9)
        drive(cma, 40, target=np.full(dim, -1.0))
    assert any(seen) and not all(seen)
