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

from mawdo.planning.check import CheckReport, check_static_path, check_trajectory
from mawdo.planning.config import PRESETS, PlannerConfig
from mawdo.planning.cost import CostWeights, PathCost, assemble_paths
from mawdo.planning.geometry import inflate, inflated_obstacles
from mawdo.planning.metrics import run_metrics
from mawdo.planning.oracle import OracleResult, scenario_optimum, shortest_path
from mawdo.planning.planner import plan
from mawdo.planning.planners import PLANNERS, PlannerSpec, run_planner
from mawdo.planning.rasters import from_movingai_map, from_occupancy_image
from mawdo.planning.result import PlanResult, Replan
from mawdo.planning.scenario import (
    SCENARIOS,
    Obstacle,
    Scenario,
    ScenarioError,
    get_scenario,
    load_scenario,
    scenario_from_dict,
)

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
