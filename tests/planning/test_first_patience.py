"""The first plan's stagnation stop (``PlannerConfig.first_patience``)."""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest

from mawdo.planning.run.config import PRESETS, PlannerConfig
from mawdo.planning.run.planner import plan

from . import maps

# no guide seeds: the swarm starts from path-like and random candidates and improves in steps
_OPEN = {"guide_routes": 0, "time_guide": False}


def _first(sc, **over):
    cfg = replace(PRESETS["quick"], **_OPEN, **over)
    return plan(sc, "mawdo", seed=0, config=cfg, max_steps=1).replans[0]


def _stop_by_hand(h: np.ndarray, patience: int) -> int:
    """Iterations run under the rule, read off the full history one iteration at a time."""
    for n in range(1, len(h) + 1):
        if n > patience and not h[n - 1] < h[n - 1 - patience]:
            return n
    return len(h)


@pytest.fixture(scope="module")
def full():
    sc = maps.rooms(1, moving=3)
    return sc, _first(sc)


def test_the_full_history_improves_late_enough_to_matter(full):
    h = full[1].history
    assert len(h) == PRESETS["quick"].first_iters
    gaps = np.diff(np.flatnonzero(np.diff(h) < 0))
    assert gaps.size >= 3 and gaps.max() >= 10  # stalls of 10+ iterations between improvements


@pytest.mark.parametrize("patience", [5, 10, 15])
def test_the_first_plan_stops_where_the_rule_says_and_follows_the_same_stream(full, patience):
    sc, ref = full
    got = _first(sc, first_patience=patience)
    n = _stop_by_hand(ref.history, patience)
    assert n < len(ref.history)  # the stop does happen on this map
    assert len(got.history) == n
    # the callback only reads: the iterations run are those of the full run, bit for bit
    assert np.array_equal(got.history, ref.history[:n])
    assert got.nfev < ref.nfev


def test_a_patience_longer_than_the_budget_changes_nothing(full):
    sc, ref = full
    got = _first(sc, first_patience=PRESETS["quick"].first_iters)
    assert np.array_equal(got.history, ref.history)
    assert np.array_equal(got.waypoints, ref.waypoints)


@pytest.mark.parametrize("bad", [0, -3, 2.0, True])
def test_bad_patience_is_refused_by_name(bad):
    with pytest.raises((ValueError, TypeError), match="first_patience"):
        PlannerConfig(first_patience=bad)


def test_only_the_large_preset_stops_early():
    assert PRESETS["large"].first_patience is not None
    assert all(PRESETS[k].first_patience is None for k in PRESETS if k != "large")
