"""Issue 26: adding an optimizer is its module plus one registration line.

The class below stands for the new module; ``register(...)`` in the fixture is the one line a
catalog would get. Nothing else in the package is touched: the driver, the option checks and
the registry's lookups serve it as they serve the built-in algorithms.
"""

from dataclasses import dataclass

import numpy as np
import pytest

from mawdo import OPTIMIZERS, minimize
from mawdo.optimizers.base import Optimizer, Params, initial_population, option
from mawdo.optimizers.registry import AlgorithmSpec, register, unregister
from mawdo.util.validate import ArgumentTypeError


@dataclass(frozen=True)
class ShrinkParams(Params):
    """``shrink``: factor applied to the sampling box's half-width each iteration, in (0, 1)."""

    shrink: float = option(0.5, lo=0, hi=1, lo_open=True, hi_open=True)


class Shrink(Optimizer):
    """Uniform samples in a box around each run's best, the box shrinking every iteration."""

    name = "shrink"
    params_class = ShrinkParams

    def init(self, space, streams, max_iter, x0=None):
        X = initial_population(streams, self.params.pop_size, space.lb, space.ub, x0)
        best = np.full(streams.runs, np.inf)
        return {"X": X, "space": space, "streams": streams, "best": best, "x": X[:, 0], "h": 1.0}

    def ask(self, s):
        return s["X"]

    def tell(self, s, X, F):
        j = F.argmin(axis=1)
        better = F[np.arange(len(j)), j] < s["best"]
        s["best"] = np.where(better, F[np.arange(len(j)), j], s["best"])
        s["x"] = np.where(better[:, None], X[np.arange(len(j)), j], s["x"])
        s["h"] *= self.params.shrink
        sp = s["space"]
        half = s["h"] * (sp.ub - sp.lb) / 2
        lo = np.maximum(s["x"] - half, sp.lb)[:, None, :]
        hi = np.minimum(s["x"] + half, sp.ub)[:, None, :]
        s["X"] = lo + (hi - lo) * s["streams"].random((self.params.pop_size, sp.dim))
        return s


@pytest.fixture
def shrink_registered():
    register(AlgorithmSpec("shrink", Shrink, {}, "test only", "shrinking box", label="Shrink"))
    yield
    unregister("shrink")
    assert "shrink" not in OPTIMIZERS


def test_a_throwaway_optimizer_runs_through_minimize(shrink_registered):
    seen = []

    def sphere(X):
        seen.append(X.copy())
        return (X**2).sum(axis=1)

    res = minimize(sphere, [(-5, 5)] * 3, algorithm="shrink", runs=2, seed=3, max_evals=95,
                   pop_size=10, shrink=0.7)  # fmt: skip
    assert np.all(res.nfev == 95) and res.algorithm == "shrink"
    assert res.params["shrink"] == 0.7 and res.metadata["label"] == "Shrink"
    # the driver's best is the least of the values it evaluated (first 95 points of each run)
    pts = np.concatenate([x.reshape(2, -1, 3) for x in seen], axis=1)[:, :95]
    vals = (pts**2).sum(axis=2)
    np.testing.assert_array_equal(res.fun, vals.min(axis=1))
    np.testing.assert_array_equal(res.x, pts[np.arange(2), vals.argmin(axis=1)])
    assert np.all(res.fun < vals[:, :10].min(axis=1))  # the shrinking box found better points
    # a registered function by name, and the same seed gives the same run
    a = minimize("sphere", dim=3, algorithm="shrink", seed=1, max_iter=20)
    b = minimize("sphere", dim=3, algorithm="SHRINK", seed=1, max_iter=20)
    np.testing.assert_array_equal(a.history, b.history)


@pytest.mark.parametrize(
    "value,error,match",
    [
        (1.0, ValueError, r"^shrink=1.0 must be a finite number in \(0, 1\)$"),
        (0, ValueError, r"^shrink=0 must be a finite number in \(0, 1\)$"),
        (float("nan"), ValueError, r"^shrink=nan must be a finite number in \(0, 1\)$"),
        ("0.5", ArgumentTypeError, r"not a str \(write shrink=0.5, not shrink='0.5'\)$"),
        (True, ArgumentTypeError, "bools are not numbers here"),
    ],
)
def test_its_option_is_checked_by_the_constraint_on_its_field(
    shrink_registered, value, error, match
):
    with pytest.raises(error, match=match):
        minimize("sphere", dim=3, algorithm="shrink", max_iter=2, shrink=value)
    with pytest.raises(ValueError, match="^pop_size=1 must be an integer >= 2$"):
        minimize("sphere", dim=3, algorithm="shrink", max_iter=2, pop_size=1)
    with pytest.raises(ValueError, match="shrink has no option 'shrinc'. Did you mean 'shrink'"):
        minimize("sphere", dim=3, algorithm="shrink", max_iter=2, shrinc=0.5)


def test_the_throwaway_optimizer_is_a_planner_in_the_arena_by_its_name(shrink_registered, tmp_path):
    # issue 26: no planner file, no arena edit: a registered optimizer drives the receding
    # horizon under its own name, and its runs are stored and judged like the built-in ones
    from mawdo.experiments import Store, run_plan
    from mawdo.experiments.kinds.arena import ArenaPlan
    from mawdo.planning import PLANNERS
    from mawdo.planning.judge.check import check_trajectory
    from mawdo.planning.run.config import resolve_config
    from mawdo.planning.scenes import generate_scene

    assert PLANNERS["shrink"].optimizer == "shrink"
    plan_ = ArenaPlan.from_dict({
        "name": "shrink", "families": ["forest"], "n": 2, "algorithms": ["shrink"],
        "baselines": [], "planner": "quick", "overrides": {"max_steps": 300}, "seed": 5,
    })  # fmt: skip
    db = tmp_path / "arena.db"
    assert run_plan(plan_, db, progress=False).done == 2
    with Store.read(db) as store:
        rows = [r for alg, _, r in store.rows() if alg == "shrink"]
    assert len(rows) == 2 and all(r.error_text is None for r in rows)
    for r in rows:
        # the stored verdict is the independent checker's on the same scene's executed route
        scene = generate_scene("forest", r.run, seed=5, params={})
        cfg = resolve_config("quick", {"max_steps": 300})
        res = PLANNERS["shrink"].run(scene.scenario, r.planner_seed, cfg)
        rep = check_trajectory(res.route, scene.scenario, times=res.route_times)
        assert r.collision_free == int(rep.ok) and r.success == int(res.success)
        assert r.l_star == pytest.approx(scene.l_star)
