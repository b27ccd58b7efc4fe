"""Path planning among moving obstacles: world model, cost kernel, oracle and checker.

Modules, one job each:

* :mod:`~mawdo.planning.motion` - obstacle motion models (closed form, piecewise linear).
* :mod:`~mawdo.planning.scenario` - scenario schema, validation, loaders, built-in scenarios.
* :mod:`~mawdo.planning.rasters` - scenarios from occupancy images and MovingAI maps.
* :mod:`~mawdo.planning.geometry` - inflation by the robot radius, flat arrays for the kernel.
* :mod:`~mawdo.planning.kernel` / :mod:`~mawdo.planning.cost` - the paper's path cost (Numba).
* :mod:`~mawdo.planning.oracle` - exact shortest path by visibility graph.
* :mod:`~mawdo.planning.check` - independent collision checker (shapely).
"""

from mawdo.planning.check import CheckReport, check_static_path, check_trajectory
from mawdo.planning.cost import CostWeights, PathCost, assemble_paths
from mawdo.planning.geometry import inflate, inflated_obstacles
from mawdo.planning.oracle import OracleResult, scenario_optimum, shortest_path
from mawdo.planning.rasters import from_movingai_map, from_occupancy_image
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
    "SCENARIOS",
    "CheckReport",
    "CostWeights",
    "Obstacle",
    "OracleResult",
    "PathCost",
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
    "scenario_from_dict",
    "scenario_optimum",
    "shortest_path",
]
