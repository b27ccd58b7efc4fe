"""Polyline helpers used by the planner and the metrics, against hand calculations."""

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from mawdo.planning.world.path import advance, densify, polyline_length, respread, turning_angles

L_SHAPE = np.array([[0.0, 0.0], [3.0, 0.0], [3.0, 4.0]])


def test_length_and_turning_by_hand():
    assert polyline_length(L_SHAPE) == 7.0
    np.testing.assert_allclose(turning_angles(L_SHAPE), [math.pi / 2])
    zigzag = np.array([[0, 0], [1, 1], [2, 0], [2, 0], [3, 1.0]])  # a repeated point: no turn
    np.testing.assert_allclose(turning_angles(zigzag), [math.pi / 2, math.pi / 2])
    assert turning_angles(np.array([[0, 0], [1, 0], [2, 0.0]])).tolist() == [0.0]
    back = np.array([[0, 0], [1, 0], [0, 0.0]])
    assert turning_angles(back)[0] == pytest.approx(math.pi)


def test_advance_passes_the_corner():
    pos, rem, passed, frac = advance(L_SHAPE, 5.0)
    np.testing.assert_allclose(pos, [3.0, 2.0])
    np.testing.assert_allclose(rem, [[3.0, 2.0], [3.0, 4.0]])
    np.testing.assert_allclose(passed, [[3.0, 0.0]])
    np.testing.assert_allclose(frac, [3.0 / 5.0])
    pos, rem, passed, _ = advance(L_SHAPE, 2.0)
    np.testing.assert_allclose(pos, [2.0, 0.0])
    assert passed.shape == (0, 2) and rem.shape == (3, 2)
    pos, rem, passed, _ = advance(L_SHAPE, 100.0)  # past the end: stop at the goal
    np.testing.assert_allclose(pos, [3.0, 4.0])
    assert rem.shape == (1, 2) and len(passed) == 1


def test_advance_by_zero_passes_nothing():
    pts = np.array([[1.0, 0.0], [1.0, 0.0], [0.0, 0.0]])  # found by hypothesis: 0/0 before
    pos, rem, passed, frac = advance(pts, 0.0)
    np.testing.assert_array_equal(pos, [1.0, 0.0])
    np.testing.assert_array_equal(rem, pts)
    assert passed.shape == (0, 2) and frac.shape == (0,)


def test_densify_keeps_the_geometry_and_respread_does_not():
    d = densify(L_SHAPE, 5)
    assert d.shape == (5, 2)
    full = np.vstack([L_SHAPE[0], d, L_SHAPE[-1]])
    assert polyline_length(full) == pytest.approx(7.0)
    assert any(np.allclose(p, [3.0, 0.0]) for p in d)  # the corner is kept
    r = respread(L_SHAPE, 5)
    assert polyline_length(np.vstack([L_SHAPE[0], r, L_SHAPE[-1]])) < 7.0  # corner cut


@settings(max_examples=60, deadline=None)
@given(
    st.lists(st.tuples(st.floats(0, 100), st.floats(0, 100)), min_size=2, max_size=8),
    st.integers(1, 25),
)
def test_densify_preserves_length_and_endpoints(pts, m):
    pts = np.array(pts)
    k = len(pts) - 2
    d = densify(pts, m)
    assert d.shape == (m, 2)
    full = np.vstack([pts[0], d, pts[-1]])
    if k <= m:  # all vertices kept: the route is the same curve
        assert polyline_length(full) == pytest.approx(polyline_length(pts), rel=1e-9, abs=1e-9)


def _densify_by_list(points, m):
    """densify's rule, written the plain way: keep the last m interior vertices, then split
    the longest piece at its midpoint (the earliest on the route on ties), re-measuring the
    list of pieces every time."""
    pts = np.asarray(points, dtype=float)
    inner = pts[1:-1][-m:]
    base = np.vstack([pts[:1], inner, pts[-1:]])
    seg = np.hypot(*np.diff(base, axis=0).T)
    pieces = [(j, 0.0, 1.0) for j in range(len(seg))]  # in route order
    for _ in range(m - len(inner)):
        lengths = [seg[j] * (b - a) for j, a, b in pieces]
        i = lengths.index(max(lengths))  # first maximum: the earliest piece
        j, a, b = pieces[i]
        c = 0.5 * (a + b)
        pieces[i : i + 1] = [(j, a, c), (j, c, b)]
    out = []
    for k, (j, a, _) in enumerate(pieces):
        if k > 0:  # each piece but the first starts at a vertex or a cut
            out.append(base[j] if a == 0.0 else base[j] + a * (base[j + 1] - base[j]))
    return np.array(out).reshape(-1, 2)


@settings(max_examples=150, deadline=None)
@given(
    st.lists(st.tuples(st.integers(0, 6), st.integers(0, 6)), min_size=2, max_size=9),
    st.integers(1, 30),
)
def test_densify_equals_the_plain_list_version(pts, m):
    # a coarse integer grid makes equal segment lengths (ties) and repeated points common
    pts = 50.0 * np.array(pts, dtype=float)
    np.testing.assert_array_equal(densify(pts, m), _densify_by_list(pts, m))


@settings(max_examples=60, deadline=None)
@given(
    st.lists(st.tuples(st.floats(0, 100), st.floats(0, 100)), min_size=2, max_size=8),
    st.floats(0, 500),
)
def test_advance_splits_the_length(pts, dist):
    pts = np.array(pts)
    total = polyline_length(pts)
    pos, rem, passed, frac = advance(pts, dist)
    assert polyline_length(rem) == pytest.approx(max(total - dist, 0.0), abs=1e-7)
    assert np.all((frac >= 0) & (frac <= 1 + 1e-12))


def test_densify_many_is_densify_bit_for_bit_ties_and_zero_lengths_included():
    from mawdo.planning.world.path_kernels import densify_many

    rng = np.random.default_rng(0)
    for trial in range(600):
        k, m = int(rng.integers(2, 6)), int(rng.integers(1, 14))
        if trial % 3 == 0:  # a lattice: equal lengths (ties) and repeated points
            pts = rng.integers(0, 4, (k, 2)).astype(float) * 10
        else:
            pts = rng.uniform(0, 366, (k, 2))
        rows = np.zeros((1, 6, 2))
        rows[0, :k] = pts
        assert np.array_equal(densify_many(rows, np.array([k]), m)[0], densify(pts, m))


def test_via_paths_are_the_loop_of_densify_on_the_same_draws():
    from mawdo.planning.refine.seeding import via_paths

    start, goal = np.array([20.0, 30.0]), np.array([340.0, 300.0])
    got = via_paths(start, goal, 9, 50, np.random.default_rng(7), 0.0, 366.0, 366.0, 366.0)
    rng = np.random.default_rng(7)  # the reference: one path at a time, as the draws come
    ref = np.empty((50, 18))
    for i in range(50):
        k = 1 + int(rng.random() < 0.5)
        via = rng.random((k, 2)) * [366.0, 366.0]
        ref[i] = densify(np.vstack([start, via, goal]), 9).reshape(-1)
    assert np.array_equal(got, np.clip(ref, 0.0, 366.0))
