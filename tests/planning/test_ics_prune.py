"""The inevitable-collision rule's mover prefilter (``SafeContinuation.prune``) is exact: it
leaves out only movers that cannot take part, so every verdict, and every run, is what the
full tables give (the reference: ``prune = False``, all movers looked at)."""

from __future__ import annotations

import numpy as np
import pytest

import mawdo.planning.safety.ics as ics
from mawdo.planning import get_scenario
from mawdo.planning.run.planner import plan
from mawdo.planning.safety.ics import SafeContinuation
from mawdo.planning.scenes import generate_scene

C = 0.5  # the planner's margin (px)


def _scenes():
    out = [get_scenario("paper")]
    out += [generate_scene(f, 0, seed=0).scenario for f in ("corridor", "crowd", "chaser")]
    return out


def _queries(sc, rng, n):
    """``n`` decisions ``(p, t, t0, route)``: half of them next to a mover (where the full
    check fails often), half anywhere on the map."""
    movers = [sc.obstacles[i] for i in sc.moving_indices]
    for k in range(n):
        t0 = float(rng.integers(0, 80))
        t = t0 + float(rng.choice([0.0, 0.5, 1.0, 2.0]))
        if k % 2:
            o = movers[rng.integers(len(movers))]
            centre = np.asarray(o.shape.bounds(), float).reshape(2, 2).mean(axis=0)
            p = centre + o.offset(t0) + rng.uniform(-40.0, 40.0, 2)
        else:
            p = rng.uniform([0.0, 0.0], [sc.width, sc.height])
        p = np.clip(p, sc.robot_radius, [sc.width - sc.robot_radius, sc.height - sc.robot_radius])
        via = rng.uniform([0.0, 0.0], [sc.width, sc.height])
        route = np.array([p, via, sc.goal]) if k % 3 else np.array([p, sc.goal])
        yield p, t, t0, route


def _same(a, b) -> bool:
    if a is None or b is None:
        return a is None and b is None
    return (
        a.kind == b.kind and np.array_equal(a.points, b.points) and np.array_equal(a.times, b.times)
    )


def _compare(scenes, n=40):
    """Per scene and query, ``find`` with and without the prefilter: (differences, queries
    where some mover was left out, queries where the full check found no safe plan rest)."""
    diff = pruned = failed = 0
    rng = np.random.default_rng(7)
    for sc in scenes:
        full, fast = SafeContinuation(sc, C, 30), SafeContinuation(sc, C, 30)
        full.prune = False
        n_movers = len(sc.moving_indices)
        for p, t, t0, route in _queries(sc, rng, n):
            a = full.find(p, t, t0, route=route)
            diff += not _same(a, fast.find(p, t, t0, route=route))
            diff += not _same(full.find(p, t, t0, wait_first=True),
                              fast.find(p, t, t0, wait_first=True))  # fmt: skip
            pruned += len(fast.movers(t0, near=(p, t))[0]) < n_movers
            failed += a is None or a.kind != "goal"
    return diff, pruned, failed


def test_the_prefilter_changes_no_verdict_and_is_exercised():
    diff, pruned, failed = _compare(_scenes())
    assert diff == 0
    # the comparison means something: movers were left out, and full checks failed
    assert pruned >= 20 and failed >= 20, (pruned, failed)


def test_a_prefilter_that_left_out_a_mover_in_reach_would_be_caught(monkeypatch):
    """The same comparison with the reach cut by 40 px (a wrong prefilter) finds verdicts
    that differ: the test above can fail."""
    monkeypatch.setattr(ics, "PRUNE_TOL", -40.0)
    diff, _, _ = _compare(_scenes())
    assert diff > 0


def _run(sc, time_guide, prune, monkeypatch):
    monkeypatch.setattr(SafeContinuation, "prune", prune)
    return plan(sc, "mawdo", seed=0, config="realtime", time_guide=time_guide)


def _assert_same_run(a, b):
    assert np.array_equal(a.route, b.route)
    assert np.array_equal(a.route_times, b.route_times)
    assert [r.cost for r in a.replans] == [r.cost for r in b.replans]
    assert (a.reason, a.steps, a.waits, a.evasions, a.fallbacks, a.holds, a.inevitable) == (
        b.reason, b.steps, b.waits, b.evasions, b.fallbacks, b.holds, b.inevitable
    )  # fmt: skip


def test_the_paper_run_is_the_same_with_and_without_the_prefilter(monkeypatch):
    sc = get_scenario("paper")
    _assert_same_run(_run(sc, False, False, monkeypatch), _run(sc, False, True, monkeypatch))


@pytest.mark.slow
@pytest.mark.parametrize("family", ["corridor", "doorway", "parked", "crowd"])
def test_timed_family_runs_are_the_same_with_and_without_the_prefilter(family, monkeypatch):
    sc = generate_scene(family, 1, seed=0).scenario
    for time_guide in (False, True):
        a = _run(sc, time_guide, False, monkeypatch)
        _assert_same_run(a, _run(sc, time_guide, True, monkeypatch))
