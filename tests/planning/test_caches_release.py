"""What the planner caches per scenario goes when the scenario goes.

Guides and safe-interval roadmaps are cached in weak-keyed dictionaries keyed by the scenario.
An observing planner makes a new prediction scenario every step; when a cached object held its
scenario strongly, no entry was ever dropped and a long crowd study grew by megabytes an episode
(two workers reached 9 GB each within an hour)."""

from __future__ import annotations

import gc
import weakref

import numpy as np
import pytest

from mawdo.util.weak import WeakAttribute


def _prediction(k: int):
    """A scenario like a step's prediction: the paper's map plus one walker, moved by ``k``."""
    from mawdo.planning import get_scenario
    from mawdo.planning.world.stepped import with_movers

    sc = get_scenario("paper")
    times = np.array([0.0, 100.0])
    track = np.array([[30.0 + k, 40.0], [130.0 + k, 40.0]])
    return with_movers(sc, [5.0], [(times, track)], ["walker"])


def test_a_scenario_with_a_cached_guide_and_roadmap_is_collected():
    from mawdo.planning.guide.sipp import roadmap
    from mawdo.planning.guide.sipp.roadmap import Roadmap
    from mawdo.planning.run import execute

    gc.collect()  # (entries of scenarios that earlier tests dropped go first, not meanwhile)
    before = (len(execute._GUIDES), len(roadmap._CACHE))
    gone = []
    for k in range(3):
        sc = _prediction(k)
        guide = execute.guide_for(sc, 0.5, 3)
        rm = Roadmap.of(sc, 0.5)
        assert guide.scenario is sc and rm.scenario is sc  # while it lives, it is there
        assert Roadmap.of(sc, 0.5) is rm  # and the cache answers
        gone.append(weakref.ref(sc))
        del sc, guide, rm
    gc.collect()
    assert all(ref() is None for ref in gone)
    # none of ours is left (entries of others may still drop, never appear)
    assert len(execute._GUIDES) <= before[0] and len(roadmap._CACHE) <= before[1]


def test_a_weak_attribute_names_itself_once_its_object_is_gone():
    class Target:
        pass

    class Holder:
        thing = WeakAttribute()

    target, holder = Target(), Holder()
    holder.thing = target
    assert holder.thing is target and isinstance(Holder.thing, WeakAttribute)
    del target
    gc.collect()
    with pytest.raises(ReferenceError, match=r"Holder\.thing no longer exists"):
        _ = holder.thing


def test_a_guide_built_on_a_scenario_nobody_else_holds_still_answers():
    """The safe-interval guide keeps its own scenario: its cached roadmap, which holds the
    scenario weakly, stays usable for as long as the guide is."""
    from mawdo.planning.guide.sipp.guide import SafeIntervalGuide

    guide = SafeIntervalGuide(_prediction(0))  # the scenario is held by the guide alone
    gc.collect()
    guide.routes(k=2)  # the search reads the roadmap's scenario
    assert guide.roadmap.scenario is guide.scenario
