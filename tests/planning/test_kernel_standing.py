"""The standing obstacles' grid (``kernel.static_index``), checked in the fast tier against the
pass over every segment by additivity: a world past ``INDEX_STANDING`` standing shapes (the
grid) counts, per candidate, the hitting (segment, obstacle) pairs of its two halves (each
below the threshold: the full pass), less the border pairs that both halves count. The slow
tier compares the two passes bit for bit (``test_kernel_index.py``)."""

from __future__ import annotations

import numpy as np
import pytest

from mawdo.planning import PathCost, scenario_from_dict
from mawdo.planning.refine.kernel.constants import INDEX_STANDING

SIZE = 300.0


def _shapes(rng, n):
    out = []
    for j in range(n):
        c = rng.uniform(10, SIZE - 10, 2).round(3)
        r = float(rng.choice([2.0, 5.0, 12.0]))
        if j % 3 == 0:
            out.append({"shape": "circle", "center": c.tolist(), "radius": r})
        else:  # a triangle or a non-convex quadrilateral (a dart)
            a = float(rng.uniform(0, 2 * np.pi))
            k = 3 + j % 2
            ang = a + np.arange(k) * 2 * np.pi / k
            rad = np.full(k, r)
            rad[1::2] *= 0.3 if k == 4 else 1.0
            v = c + np.c_[rad * np.cos(ang), rad * np.sin(ang)]
            out.append({"shape": "polygon", "vertices": v.round(3).tolist()})
    return out


def _collisions(shapes, X, mode):
    sc = scenario_from_dict({"schema_version": 1, "width": SIZE, "height": SIZE,
                             "start": [5.0, 5.0], "goal": [SIZE - 5.0, SIZE - 5.0],
                             "obstacles": shapes})  # fmt: skip
    return PathCost(sc, n_waypoints=X.shape[1] // 2, mode=mode, clearance=0.5).parts(X)[1]


@pytest.mark.parametrize("mode", ["snapshot", "spacetime"])
def test_the_grid_counts_what_the_two_halves_count(mode):
    rng = np.random.default_rng(3)
    n = 2 * INDEX_STANDING - 20  # more than the threshold, each half fewer
    shapes = _shapes(rng, n)
    X = rng.uniform(-10, SIZE + 10, (200, 16))  # some waypoints off the map: border pairs
    X[:100] = np.linspace(20, SIZE - 20, 8).repeat(2) + rng.normal(0, 20, (100, 16))
    whole = _collisions(shapes, X, mode)
    halves = _collisions(shapes[: n // 2], X, mode) + _collisions(shapes[n // 2 :], X, mode)
    border = _collisions([], X, mode)
    assert border.sum() > 0 and whole.sum() > 1000
    np.testing.assert_array_equal(whole, halves - border)
