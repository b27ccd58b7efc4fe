"""The planner's margin fitted to the scene's narrowest passage
(:mod:`mawdo.planning.guide.passage`).

The reference is a hand calculation: one full-height wall with one gap of width ``2 r + s``
between two boxes. The guide inflates the boxes by ``r + m + SLACK``; the faces that bound the
gap are parallel, so the passage stays open exactly while ``2 (r + m + SLACK) < 2 r + s``:
the scene's slack is ``m* = s / 2 - SLACK``.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest

from mawdo.planning import scenario_from_dict
from mawdo.planning.guide.homotopy import SLACK
from mawdo.planning.guide.passage import STEPS, fit_config, fitted_clearance, passage_margin
from mawdo.planning.run.config import PRESETS, resolve_scenario

R = 4.0


def _wall(slack: float):
    """A 200 x 200 map, a wall at x = 100 (10 px thick) with one gap of ``2 R + slack`` px
    centred at y = 100; start left, goal right."""
    half = 0.5 * (2 * R + slack)
    box = lambda x0, y0, x1, y1: [[x0, y0], [x1, y0], [x1, y1], [x0, y1]]  # noqa: E731
    return scenario_from_dict({
        "schema_version": 1, "width": 200.0, "height": 200.0,
        "start": [30.0, 40.0], "goal": [170.0, 160.0], "robot": {"radius": R, "speed": 4.0},
        "obstacles": [
            {"shape": "polygon", "vertices": box(95.0, 0.0, 105.0, 100.0 - half)},
            {"shape": "polygon", "vertices": box(95.0, 100.0 + half, 105.0, 200.0)},
        ],
    })  # fmt: skip


@pytest.mark.parametrize("slack", [0.3, 0.6, 1.0])
def test_passage_margin_is_half_the_gap_slack_less_the_guide_slack(slack):
    upto = 1.0
    m = passage_margin(_wall(slack), upto)
    exact = 0.5 * slack - SLACK
    # rounded down to the bisection's resolution, never above the exact slack
    assert exact - upto / 2**STEPS <= m <= exact


def test_fitted_clearance_is_half_the_slack_only_where_the_passage_needs_it():
    narrow = fitted_clearance(_wall(0.4), 0.5)
    assert narrow == pytest.approx(0.5 * (0.2 - SLACK), abs=1.0 / 2**STEPS)
    assert fitted_clearance(_wall(3.0), 0.5) == 0.5  # 1.5 - SLACK >= 2 x 0.5: unchanged
    assert fitted_clearance(_wall(3.0), 2.0) == pytest.approx(0.5 * (1.5 - SLACK), abs=0.04)
    assert fitted_clearance(resolve_scenario("paper"), 0.5) == 0.5


def test_fit_config_keeps_the_same_object_when_nothing_changes():
    cfg = PRESETS["realtime"]
    assert fit_config(resolve_scenario("paper"), cfg) is cfg
    fitted = fit_config(_wall(0.4), cfg)
    assert fitted == replace(cfg, clearance=fitted.clearance) and fitted.clearance < 0.1


def test_passage_margin_rejects_a_bad_bound():
    with pytest.raises(ValueError, match="upto"):
        passage_margin(_wall(1.0), -1.0)


def test_a_gap_within_one_px_of_the_diameter_is_driven_through_and_accepted():
    """The planner (guide -> seeds -> refine -> guard) crosses a gap 0.3 px wider than the
    robot and the independent checker accepts the route (touching allowed, no overlap)."""
    from mawdo.planning.run.planner import plan

    sc = _wall(0.3)
    res = plan(sc, "mawdo", seed=0)
    assert res.success, res.reason
    assert res.collision_free and res.min_clearance >= 0.0
    # it went through the gap: where it crosses the wall's middle, it is within the slack
    a, b = res.route[:-1], res.route[1:]
    (i,) = np.nonzero((a[:, 0] < 100.0) & (b[:, 0] >= 100.0))
    w = (100.0 - a[i, 0]) / (b[i, 0] - a[i, 0])
    assert len(i) == 1 and abs(a[i, 1] + w * (b[i, 1] - a[i, 1]) - 100.0).max() <= 0.15
