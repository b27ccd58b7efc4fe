"""Why a safe-interval query has no route: each cause of ``SafeIntervalGuide.explain`` on a
scene where it is the cause by hand, and the paper map whose random walker, taken as a
reachable set, covers the goal."""

from __future__ import annotations

import pytest

from mawdo.planning.guide.sipp import SafeIntervalGuide
from mawdo.planning.world.scenario import get_scenario
from tests.planning.test_sipp import _box, _scene

# A circle of radius 6 crossing the goal (100, 50) at 2 px per step from x = 20: with the robot's
# radius 4 and the clearance 0.5 it covers the goal for |20 + 2 t - 100| <= 10.5, that is
# t in [34.75, 45.25] (the safe intervals of tests/planning/test_sipp.py, by hand).
CROSSER = {"shape": "circle", "center": [20, 50], "radius": 6.0, "motion": {"velocity": [2, 0]}}


def _crossing(speed: float):
    return _scene(300, 100, (100, 10), (100, 50), [dict(CROSSER, id="crosser")], speed=speed)


def test_the_goal_covered_until_the_horizon_names_the_mover():
    """At 1 px per step the robot needs 40 steps for the 40 px to the goal; from t = 40 to the
    horizon's end (45) the crosser covers the goal (from 34.75 on)."""
    guide = SafeIntervalGuide(_crossing(1.0), horizon=45.0)
    assert guide.routes() == []
    why = guide.explain()
    assert "the goal is covered" in why
    assert "(t = 40.0)" in why and "(t = 45.0)" in why
    assert "'crosser' from t = 34.8 to the end" in why
    assert "a longer horizon" in why


def test_a_route_that_exists_is_said_to():
    """With the horizon past the crossing (45.25) the robot waits and arrives after it."""
    guide = SafeIntervalGuide(_crossing(1.0), horizon=80.0)
    (route,) = guide.routes()
    assert route.arrival >= 45.25
    assert guide.explain() == (
        f"nothing stops the robot: the earliest route arrives at t = {route.arrival:.1f}"
    )


def test_a_short_horizon_gives_the_horizon_needed():
    """40 px at 4 px per step: 10 steps at the earliest, so a horizon of 8 is too short."""
    why = SafeIntervalGuide(_crossing(4.0), horizon=8.0).explain()
    assert why.startswith("the horizon is too short")
    assert "(40.0 px)" in why and "give horizon > 10.0 time steps" in why


def test_a_goal_walled_off_is_cut_off_on_the_static_map():
    sc = _scene(300, 100, (20, 50), (280, 50), [_box(140, 0, 160, 100)])
    guide = SafeIntervalGuide(sc)
    assert guide.routes() == []
    assert guide.explain().startswith("the goal cannot be reached on the static map")


def test_a_start_inside_a_mover_gives_the_search_error():
    """10.25 px from the crosser's centre: clear of its disc grown by the robot's radius (10),
    inside it grown by the clearance too (10.5)."""
    sc = _scene(300, 100, (30.25, 50), (280, 50), [dict(CROSSER, id="crosser")])
    guide = SafeIntervalGuide(sc)
    with pytest.raises(ValueError, match="start is inside a moving obstacle") as err:
        guide.routes()
    assert guide.explain() == str(err.value)


def test_the_paper_maps_walker_covers_the_goal_as_a_reachable_set():
    """On the paper map the random walker 'wanderer', taken as a disc growing at its top speed,
    covers the goal long before the robot can be there; following its seeded walk instead
    (walkers='known'), the guide finds a route."""
    sc = get_scenario("paper")
    guide = SafeIntervalGuide(sc)
    assert guide.routes() == []
    why = guide.explain()
    assert "'wanderer' from t = " in why and "reachable set" in why
    assert "walkers='known'" in why
    known = SafeIntervalGuide(sc, walkers="known")
    assert known.routes()
    assert known.explain().startswith("nothing stops the robot")


def test_a_braking_lead_through_a_wall_cannot_start():
    """Under an acceleration limit the search starts where the robot comes to rest; a lead
    whose step crosses the wall (x = 140..160) leaves no route to start."""
    sc = _scene(300, 100, (20, 50), (280, 50), [_box(140, 0, 160, 40), _box(140, 60, 160, 100)])
    guide = SafeIntervalGuide(sc, profile=(1.0, float("inf")), lead=[(135, 30), (166, 30)])
    assert guide.routes() == []
    assert guide.explain().startswith("the robot cannot brake clear")
    clear = SafeIntervalGuide(sc, profile=(1.0, float("inf")), lead=[(120, 50), (126, 50)])
    assert clear.routes()
    assert clear.explain().startswith("nothing stops the robot")
