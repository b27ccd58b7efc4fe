"""Wind.ask's per-state layout of the fixed low-dimensional coefficients (issue 15) moves the
parcels exactly as the per-iteration broadcast it replaced."""

import numpy as np
import pytest

from mawdo import make_optimizer, minimize
from mawdo.optimizers.wdo import Wind


class PerIteration(Wind):
    """The same coefficients through an overridden ``_coefficients``: ``Wind.ask`` then takes
    its general path, broadcasting and stacking them at every iteration (mawdo 0.2.0)."""

    def _coefficients(self, s):
        return Wind._coefficients(self, s)


def rastrigin(X):
    return (X**2 - 10 * np.cos(2 * np.pi * X)).sum(axis=1) + 10 * X.shape[1]


@pytest.mark.parametrize("redraw", [False, True])
@pytest.mark.parametrize("dim", [2, 7])
def test_laid_out_coefficients_move_parcels_as_the_broadcast_did(redraw, dim):
    opts = dict(pop_size=30, low_dim=10, hetero_redraw=redraw)
    fast = make_optimizer("mawdo", **opts)
    plain = PerIteration(fast.params, name="mawdo")
    assert fast.params.low_dim_stabilization and dim <= fast.params.low_dim
    runs = [
        minimize(rastrigin, [(-5, 5)] * dim, algorithm=opt, runs=3, seed=11, max_iter=60)
        for opt in (fast, plain)
    ]
    np.testing.assert_array_equal(runs[0].x, runs[1].x)
    np.testing.assert_array_equal(runs[0].history, runs[1].history)
    assert runs[0].history[:, -1].min() < runs[0].history[:, 0].min()  # the runs did move


@pytest.mark.parametrize("dim", [4, 12])
def test_wdo_fixed_coefficients_laid_out_once_move_parcels_as_the_broadcast_did(dim):
    fast = make_optimizer("wdo", pop_size=20, alpha=0.3, RT=2.5)
    plain = PerIteration(fast.params, name="wdo")
    runs = [
        minimize(rastrigin, [(-5, 5)] * dim, algorithm=opt, runs=3, seed=4, max_iter=40)
        for opt in (fast, plain)
    ]
    np.testing.assert_array_equal(runs[0].x, runs[1].x)
    np.testing.assert_array_equal(runs[0].history, runs[1].history)
    assert runs[0].history[:, -1].min() < runs[0].history[:, 0].min()
