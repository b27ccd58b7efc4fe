"""Faster forms of map-only steps give what the plain forms give: the roadmap's distinct edge
pairs (``np.unique`` of the rows) and the dodge spots' distances to static obstacles (one
``shape.distance(point)`` call per point and shape)."""

from __future__ import annotations

import numpy as np
import pytest

from mawdo.planning import scenario_from_dict
from mawdo.planning.guide.sipp.optimum import _static_distance, dodge_spots
from mawdo.planning.guide.sipp.roadmap import _unique_pairs


@pytest.mark.parametrize(("n", "m"), [(1, 5), (7, 40), (300, 20_000), (5, 0)])
def test_unique_pairs_are_numpys_unique_rows(n, m):
    rng = np.random.default_rng(n + m)
    src, dst = rng.integers(0, n, m), rng.integers(0, n, m)
    want = np.unique(np.column_stack([src, dst]), axis=0)
    got = _unique_pairs(src, dst, n)
    assert got.dtype == want.dtype and np.array_equal(got, want)


def _statics(rng, k: int) -> list:
    out = []
    for j in range(k):
        c = rng.uniform(30, 270, 2)
        if j % 3 == 0:
            out.append(
                {"shape": "circle", "center": c.tolist(), "radius": float(rng.uniform(4, 15))}
            )
            continue
        ang = np.linspace(0, 2 * np.pi, 6)[:-1] + rng.uniform(0, 0.5, 5)  # star-shaped: simple
        v = c + rng.uniform(5, 20, 5)[:, None] * np.c_[np.cos(ang), np.sin(ang)]
        out.append({"shape": "polygon", "vertices": v.tolist()})
    return out


def test_static_distances_are_the_shapes_own_and_the_spots_follow():
    rng = np.random.default_rng(5)
    spec = {"schema_version": 1, "width": 300.0, "height": 300.0, "start": [5.0, 5.0],
            "goal": [295.0, 295.0], "obstacles": _statics(rng, 12)}  # fmt: skip
    sc = scenario_from_dict(spec)
    shapes = [sc.obstacles[i].shape for i in sc.static_indices]
    pts = rng.uniform(0, 300, (400, 2))
    want = np.array([min(s.distance(q) for s in shapes) for q in pts])
    assert np.array_equal(_static_distance(shapes, pts), want)
    assert (want == 0).any() and (want > 5).any()  # inside some, far from others
    route = np.array([[5.0, 5.0], [150.0, 40.0], [295.0, 295.0]])
    spots = dodge_spots(route, sc)
    need = sc.robot_radius + 1.0
    assert len(spots) > 10
    assert all(min(s.distance(q) for s in shapes) > need for q in spots)
