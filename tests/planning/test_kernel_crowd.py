"""The moving obstacles' pass on crowd scenes (issue 27's faster pass): counts equal shapely's.

Crowd scenes have 30-60 small movers whose tracks have many knots, so a block's path times fall
on several pieces of each mover (the few-knot step takes them four at a time, more than four
in several rounds), and most segments are far from most movers (the box test in front of the
lens test drops them). The reference (:func:`tests.planning.reference.reference_parts`) is
independent: exact distances by shapely between each obstacle's shape and the robot's path
relative to it, piece by piece.
"""

import numpy as np
import pytest

from mawdo.planning import PathCost
from mawdo.planning.scenes import generate_scene

from .reference import border_hits, paths_from, reference_parts


def _sample(sc, rng, n=160):
    """Uniform paths over the map and jittered straight lines from start to goal."""
    W, H = sc.width, sc.height
    uniform = rng.uniform(0, 1, (n, 40)) * np.tile([W, H], 20)
    line = np.linspace(sc.start, sc.goal, 22)[1:-1].ravel()
    sigma = rng.choice([1.0, 5.0, 20.0], size=(n, 1))
    near = np.clip(line + rng.normal(0, 1, (n, 40)) * sigma, 0, np.tile([W, H], 20))
    return np.vstack([uniform, near])


def _most_pieces(sc, X, start, t0):
    """The most pieces of one mover's track that a candidate's path times fall on."""
    paths = paths_from(X, start, sc.goal)
    seg = np.hypot(*np.diff(paths, axis=1).transpose(2, 0, 1))
    tmax = t0 + float(seg.sum(axis=1).max()) / sc.robot_speed
    most = 0
    for o in sc.obstacles:
        kt, _ = o.knots(t0, tmax)
        most = max(most, int(np.count_nonzero((kt > t0) & (kt <= tmax))) + 1)
    return most


@pytest.mark.parametrize(("index", "t0"), [(0, 0.0), (1, 0.0), (2, 23.5)])
def test_crowd_counts_equal_shapely(index, t0):
    sc = generate_scene("crowd", index, seed=0).scenario
    rng = np.random.default_rng(27 + index)
    X = _sample(sc, rng)
    start = None if t0 == 0.0 else (sc.start[0] + 10.0, sc.start[1] + 10.0)
    _, ncol, _ = PathCost(sc, mode="spacetime").parts(X, start=start, t0=t0)
    start = sc.start if start is None else np.asarray(start)
    _, ref, _, ambiguous = reference_parts(sc, X, start, "spacetime", t0)
    assert ambiguous.mean() < 0.02  # tangencies within rounding are left out
    keep = ~ambiguous
    bad = np.nonzero(ncol[keep] != ref[keep])[0]
    assert bad.size == 0, (bad[:10], ncol[keep][bad[:10]], ref[keep][bad[:10]])
    # the sample reaches the cases the pass takes apart: candidates with few hits and with
    # many (most of their (segment, mover) pairs miss), and some mover's track with more than
    # four pieces over a candidate's path times
    obstacle = ref - border_hits(sc, paths_from(X, start, sc.goal))
    assert obstacle.min() <= 3 and obstacle.max() >= 20
    assert _most_pieces(sc, X, start, t0) > 4
