"""Path planning among moving obstacles: world model, cost kernel, oracle and checker.

One folder per stage of the planning loop (guide -> refine -> guard -> move -> judge):

* :mod:`~mawdo.planning.world` - the scenario: map, robot, obstacles and their motion, geometry,
  raster maps, the file schema.
* :mod:`~mawdo.planning.guide` - exact guidance: visibility graph, shortest paths (the oracle),
  homotopy-distinct routes, the safe-interval search and its time guide.
* :mod:`~mawdo.planning.refine` - the paper's path cost and its compiled kernel, seed candidates,
  the greedy polish.
* :mod:`~mawdo.planning.safety` - the guard, the inevitable-collision rule, kinematic limits.
* :mod:`~mawdo.planning.run` - settings, the receding-horizon loop, results, every planner by name.
* :mod:`~mawdo.planning.judge` - the independent checkers, who is at fault, the per-run metrics.
* :mod:`~mawdo.planning.sense` - what the robot knows: sensor readings, the tracker, predictors,
  the policy contract; :mod:`~mawdo.planning.people` - people who react.
* :mod:`~mawdo.planning.scenes`, :mod:`~mawdo.planning.baselines`, :mod:`~mawdo.planning.render` -
  seeded scene families, baseline planners, figures.

>>> from mawdo.planning import PLANNERS, plan, run_metrics
>>> result = plan("paper", "mawdo", seed=0, config="quick")    # doctest: +SKIP
>>> run_metrics(result)["gap"]                                 # doctest: +SKIP
"""

# The names below are imported on first use (PEP 562): ``from mawdo.planning.world.scenario
# import ...`` or ``from mawdo.planning import get_scenario`` then loads what it needs, not the
# planner, the oracle and the checker with it (about 1 s of imports a command may not need yet).
_LAZY = {
    "CheckReport": "judge.check",
    "check_static_path": "judge.check",
    "check_trajectory": "judge.check",
    "PRESETS": "run.config",
    "PlannerConfig": "run.config",
    "CostWeights": "refine.cost",
    "PathCost": "refine.cost",
    "assemble_paths": "refine.cost",
    "inflate": "world.geometry",
    "inflated_obstacles": "world.geometry",
    "run_metrics": "judge.metrics",
    "OracleResult": "guide.oracle",
    "scenario_optimum": "guide.oracle",
    "shortest_path": "guide.oracle",
    "plan": "run.planner",
    "PLANNERS": "run.planners",
    "PlannerSpec": "run.planners",
    "run_planner": "run.planners",
    "from_movingai_map": "world.rasters",
    "from_occupancy_image": "world.rasters",
    "PlanResult": "run.result",
    "Replan": "run.result",
    "SCENARIOS": "world.scenario",
    "Obstacle": "world.scenario",
    "Scenario": "world.scenario",
    "ScenarioError": "world.scenario",
    "get_scenario": "world.scenario",
    "load_scenario": "world.scenario",
    "scenario_from_dict": "world.scenario",
    "SteppedWorld": "world.stepped",
    "Move": "world.stepped",
    "Track": "world.motion",
    "Units": "world.units",
    "run_episode": "run.episode",
    "PlannerPolicy": "run.policy",
    "StraightLine": "run.policy",
    "POLICIES": "run.policies",
    "make_policy": "run.policies",
    "Reading": "sense.reading",
    "Tracks": "sense.reading",
    "Policy": "sense.reading",
    "Sensor": "sense.sensor",
    "Tracker": "sense.tracker",
    "PREDICTORS": "sense.predict",
    "blame": "judge.fault",
}


def __getattr__(name):
    if name in _LAZY:
        import importlib

        value = getattr(importlib.import_module(f"mawdo.planning.{_LAZY[name]}"), name)
        globals()[name] = value  # later look-ups skip this function
        return value
    raise AttributeError(f"module 'mawdo.planning' has no attribute {name!r}")


__all__ = [
    "PLANNERS",
    "POLICIES",
    "PREDICTORS",
    "PRESETS",
    "SCENARIOS",
    "CheckReport",
    "CostWeights",
    "Move",
    "Obstacle",
    "OracleResult",
    "PathCost",
    "PlanResult",
    "PlannerConfig",
    "PlannerPolicy",
    "PlannerSpec",
    "Policy",
    "Reading",
    "Replan",
    "Scenario",
    "ScenarioError",
    "Sensor",
    "SteppedWorld",
    "StraightLine",
    "Track",
    "Tracker",
    "Tracks",
    "Units",
    "assemble_paths",
    "blame",
    "check_static_path",
    "check_trajectory",
    "from_movingai_map",
    "from_occupancy_image",
    "get_scenario",
    "inflate",
    "inflated_obstacles",
    "load_scenario",
    "make_policy",
    "plan",
    "run_episode",
    "run_metrics",
    "run_planner",
    "scenario_from_dict",
    "scenario_optimum",
    "shortest_path",
]
