"""Path planning among moving obstacles: world model, cost kernel, oracle and checker.

Modules, one job each:

* :mod:`~mawdo.planning.motion` - obstacle motion models (closed form, piecewise linear).
* :mod:`~mawdo.planning.scenario` - scenario schema, validation, loaders, built-in scenarios.
* :mod:`~mawdo.planning.rasters` - scenarios from occupancy images and MovingAI maps.
* :mod:`~mawdo.planning.geometry` - inflation by the robot radius, flat arrays for the kernel.
* :mod:`~mawdo.planning.kernel` / :mod:`~mawdo.planning.cost` - the paper's path cost (Numba).
* :mod:`~mawdo.planning.oracle` - exact shortest path by visibility graph.
* :mod:`~mawdo.planning.check` - independent collision checker (shapely).
* :mod:`~mawdo.planning.planner` / :mod:`~mawdo.planning.execute` - the receding-horizon planner
  (:func:`plan`) and its run loop; :mod:`~mawdo.planning.config` its settings.
* :mod:`~mawdo.planning.planners` - every planner by name (:data:`PLANNERS`), each returning a
  :class:`PlanResult` (:mod:`~mawdo.planning.result`).
* :mod:`~mawdo.planning.metrics` - :func:`run_metrics`, the one measure of a run.

>>> from mawdo.planning import PLANNERS, plan, run_metrics
>>> result = plan("paper", "mawdo", seed=0, config="quick")    # doctest: +SKIP
>>> run_metrics(result)["gap"]                                 # doctest: +SKIP
"""

# The names below are imported on first use (PEP 562): ``from mawdo.planning.scenario import
# ...`` or ``from mawdo.planning import get_scenario`` then loads what it needs, not the planner,
# the oracle and the checker with it (about 1 s of imports a command may not need yet).
_LAZY = {
    "CheckReport": "check",
    "check_static_path": "check",
    "check_trajectory": "check",
    "PRESETS": "config",
    "PlannerConfig": "config",
    "CostWeights": "cost",
    "PathCost": "cost",
    "assemble_paths": "cost",
    "inflate": "geometry",
    "inflated_obstacles": "geometry",
    "run_metrics": "metrics",
    "OracleResult": "oracle",
    "scenario_optimum": "oracle",
    "shortest_path": "oracle",
    "plan": "planner",
    "PLANNERS": "planners",
    "PlannerSpec": "planners",
    "run_planner": "planners",
    "from_movingai_map": "rasters",
    "from_occupancy_image": "rasters",
    "PlanResult": "result",
    "Replan": "result",
    "SCENARIOS": "scenario",
    "Obstacle": "scenario",
    "Scenario": "scenario",
    "ScenarioError": "scenario",
    "get_scenario": "scenario",
    "load_scenario": "scenario",
    "scenario_from_dict": "scenario",
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
    "PRESETS",
    "SCENARIOS",
    "CheckReport",
    "CostWeights",
    "Obstacle",
    "OracleResult",
    "PathCost",
    "PlanResult",
    "PlannerConfig",
    "PlannerSpec",
    "Replan",
    "Scenario",
    "ScenarioError",
    "assemble_paths",
    "check_static_path",
    "check_trajectory",
    "from_movingai_map",
    "from_occupancy_image",
    "get_scenario",
    "inflate",
    "inflated_obstacles",
    "load_scenario",
    "plan",
    "run_metrics",
    "run_planner",
    "scenario_from_dict",
    "scenario_optimum",
    "shortest_path",
]
