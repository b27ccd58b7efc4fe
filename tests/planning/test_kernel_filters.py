"""The kernel's division-free distance filters (issue 15): they must decide like the exact
distance wherever they decide, and leave the rest (within rounding of a radius) to it."""

from fractions import Fraction

import numpy as np
import pytest

from mawdo.planning import PathCost, get_scenario, scenario_from_dict
from mawdo.planning.refine.kernel.primitives import segment_reaches_origin


def _exact_d2(ax, ay, bx, by) -> Fraction:
    """Squared distance from the origin to segment ab, in exact rational arithmetic."""
    ax, ay, bx, by = (Fraction(float(v)) for v in (ax, ay, bx, by))
    dx, dy = bx - ax, by - ay
    ee = dx * dx + dy * dy
    u = Fraction(0) if ee == 0 else min(max(-(ax * dx + ay * dy) / ee, Fraction(0)), Fraction(1))
    wx, wy = ax + u * dx, ay + u * dy
    return wx * wx + wy * wy


def test_division_free_reach_agrees_with_the_exact_distance_off_the_boundary():
    # Rounding at coordinates of a few hundred px is ~1e-13 px: 1e-9 px either side of the true
    # distance is decided as the exact distance decides.
    rng = np.random.default_rng(15)
    segs = rng.uniform(-400.0, 400.0, (400, 4))
    segs[:40, 2:] = segs[:40, :2]  # zero-length segments: the distance to the point
    # passing near the origin, the foot of the perpendicular inside
    segs[40:80, 2:] = -segs[40:80, :2] * rng.uniform(0.1, 3.0, (40, 1)) + rng.normal(0, 5, (40, 2))
    inside = 0
    for ax, ay, bx, by in segs:
        r = float(_exact_d2(ax, ay, bx, by)) ** 0.5
        inside += r < 5.0
        assert segment_reaches_origin(ax, ay, bx, by, (r + 1e-9) ** 2)
        assert not segment_reaches_origin(ax, ay, bx, by, (r - 1e-9) ** 2)
    assert inside > 10  # the near-origin cases are there


@pytest.mark.parametrize(
    ("dy", "hits"),
    [(0.0, 1), (-5e-7, 1), (5e-7, 0), (2e-6, 0), (-2e-6, 1)],
)
def test_standing_circle_touched_within_rounding_of_its_radius_counts_exactly(dy, hits):
    # Obstacle 2 of the paper scenario stands at (60, 110) at t0 = 0: a circle of radius 14,
    # grown by the robot radius 4 to 18 px. A straight path along y = 110 + 18 + dy touches it
    # (touching is a hit) iff dy <= 0, and only the one segment over x = 60 comes that close
    # (no waypoint lies at x = 60). |dy| of 5e-7 px is within the division-free pass's margin,
    # so the exact distance decides; 2e-6 px is beyond it.
    sc = get_scenario("paper")
    cost = PathCost(sc, mode="snapshot")
    y = 128.0 + dy
    xs = np.linspace(50.0, 70.0, 22)
    X = np.column_stack([xs[1:-1], np.full(20, y)]).reshape(1, -1)
    _, ncol, turn = cost.parts(X, start=(50.0, y), t0=0.0, goal=(70.0, y))
    assert turn[0] == 0.0
    assert ncol[0] == hits


def _overtaken_circle(h):
    """A circle of radius 14 at (60, 100) moving right at 1 px per step, and a robot of radius
    4 (speed 4) driving right along y = 100 + h from x = 20 to 140 on 20 evenly spaced
    waypoints: relative to the circle the robot moves along y = h, x = -40 + 3 t."""
    sc = scenario_from_dict(
        {
            "schema_version": 1, "width": 366.0, "height": 366.0,
            "start": [20.0, 100.0 + h], "goal": [140.0, 100.0 + h],
            "robot": {"radius": 4.0, "speed": 4.0},
            "obstacles": [{"shape": "circle", "center": [60.0, 100.0], "radius": 14.0,
                           "motion": {"velocity": [1.0, 0.0]}}],
        }
    )  # fmt: skip
    xs = np.linspace(20.0, 140.0, 22)
    X = np.column_stack([xs[1:-1], np.full(20, 100.0 + h)]).reshape(1, -1)
    return sc, X, xs


@pytest.mark.parametrize("h", [-10.0, 0.0, 8.0, 17.0, 18.0 - 2e-6, 18.0 - 5e-7, 18.0, 18.0 + 5e-7])
def test_moving_circle_counts_by_hand_deep_and_within_rounding_of_its_radius(h):
    # Deep passes (h = 0, 8) are decided as sure hits by the lens step; passes within 2e-6 px of
    # the grown radius 18 by the exact tests. Either way the count is the number of segments
    # whose relative x range comes within sqrt(18^2 - h^2) of 0 (touching counts).
    sc, X, xs = _overtaken_circle(h)
    _, ncol, _ = PathCost(sc, mode="spacetime").parts(X, t0=0.0)
    # (exact rational arithmetic on the float waypoints the kernel gets)
    rel = [
        (-40 + 3 * (Fraction(a) - 20) / 4, -40 + 3 * (Fraction(b) - 20) / 4)
        for a, b in zip(xs[:-1], xs[1:], strict=True)
    ]
    reach2 = Fraction(18) ** 2 - Fraction(h) ** 2
    near2 = [0 if lo <= 0 <= hi else min(lo * lo, hi * hi) for lo, hi in rel]
    expected = sum(1 for d2 in near2 if d2 <= reach2)
    assert ncol[0] == expected
    assert expected >= (1 if h <= 18.0 else 0) and (h > 18.0) == (expected == 0)
