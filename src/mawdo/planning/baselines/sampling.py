"""OMPL baselines: RRT*, BIT* and PRM*, single-shot on the static obstacles under a time budget.

The robot is a point in the map shrunk by ``robot_radius`` on every side (OMPL
``RealVectorStateSpace(2)`` bounds; :func:`mawdo.planning.world.geometry.centre_box`), so its disc
stays in the map: the box is convex, so a motion between two states in it never leaves it and
needs no margin. A state is valid when it lies in that box and outside every static obstacle
inflated by ``robot_radius + clearance`` (containing polygons,
:func:`mawdo.planning.world.geometry.inflate`; one prepared shapely union).
Motions are checked by OMPL's discrete motion validator at ``resolution`` pixels: every point of
a motion is within ``resolution / 2`` of a checked state, so with ``clearance >= resolution / 2``
(default ``clearance = resolution``) no accepted motion can come closer than ``robot_radius``
to an obstacle; corner cutting by the path simplifier is bounded the same way. The result still
goes through the independent checker (:mod:`mawdo.planning.baselines.result`).

None of these planners sees time: moving obstacles are ignored, and the route is judged against
them only afterwards. Runs under a wall-clock budget are not reproducible bit for bit.
"""

from __future__ import annotations

import math
import time

import numpy as np
import shapely

from mawdo.planning.baselines.result import BaselineResult, make_result
from mawdo.planning.world.geometry import centre_box, inflate
from mawdo.planning.world.scenario import Scenario

__all__ = ["OMPL_PLANNERS", "ompl_available", "plan_ompl"]

#: Our names -> OMPL geometric planner class names.
OMPL_PLANNERS = {"rrtstar": "RRTstar", "bitstar": "BITstar", "prmstar": "PRMstar"}

_INSTALL = (
    "the OMPL baselines need the 'ompl' package (OMPL 2.x wheels): "
    "pip install 'mawdo[ompl]'  (or: pip install ompl)"
)


def _import_ompl():
    try:
        from ompl import base, geometric, util
    except ImportError as exc:
        raise ImportError(_INSTALL) from exc
    util.setLogLevel(util.LogLevel.LOG_WARN)
    return base, geometric


def ompl_available() -> bool:
    """True if ``ompl`` can be imported."""
    try:
        _import_ompl()
    except ImportError:
        return False
    return True


def _blocked(scenario: Scenario, margin: float):
    """Prepared union of the static obstacles inflated by ``robot_radius + margin`` (pixels)."""
    r = scenario.robot_radius + margin
    shapes = [inflate(scenario.obstacles[i].shape, r) for i in scenario.static_indices]
    union = shapely.union_all(shapes) if shapes else shapely.Polygon()
    shapely.prepare(union)
    return union


class _Validity:
    """State validity through shapely, exact, with a grid of precomputed answers in front.

    The map is cut into square cells (at most ``GRID`` per side); a cell whose closed box misses
    the blocked set answers "valid" for every point in it, one inside it "invalid", and only
    points in cells that straddle an obstacle's boundary ask shapely. Counts its calls (OMPL's
    check rate).
    """

    GRID = 256

    def __init__(self, blocked, width: float, height: float, box=None) -> None:
        self.blocked = blocked
        self.box = (0.0, 0.0, float(width), float(height)) if box is None else box
        self.calls = 0
        self.cell = max(width, height) / self.GRID
        nx, ny = math.ceil(width / self.cell), math.ceil(height / self.cell)
        x0, y0 = np.meshgrid(np.arange(nx) * self.cell, np.arange(ny) * self.cell)
        boxes = shapely.box(x0, y0, x0 + self.cell, y0 + self.cell)
        state = np.where(shapely.intersects(blocked, boxes), 2, 0)
        state[shapely.contains(blocked, boxes)] = 1
        self.grid = state.tolist()  # nested lists: the fastest lookup from Python
        self.nx, self.ny = nx, ny

    def __call__(self, state) -> bool:
        self.calls += 1
        x, y = state[0], state[1]
        xlo, ylo, xhi, yhi = self.box
        if x < xlo or x > xhi or y < ylo or y > yhi:  # the robot's disc would leave the map
            return False
        i = min(max(int(x / self.cell), 0), self.nx - 1)
        j = min(max(int(y / self.cell), 0), self.ny - 1)
        g = self.grid[j][i]
        if g == 2:
            return not shapely.intersects_xy(self.blocked, x, y)
        return g == 0


def _check_options(planner: str, time_limit: float, resolution: float, clearance: float) -> None:
    if planner not in OMPL_PLANNERS:
        raise ValueError(f"unknown OMPL planner {planner!r}; known: {', '.join(OMPL_PLANNERS)}")
    if not (0 < time_limit <= 3600):
        raise ValueError(f"time_limit must be in (0, 3600] seconds, got {time_limit!r}")
    if not (0 < resolution <= 10):
        raise ValueError(f"resolution must be in (0, 10] pixels, got {resolution!r}")
    if not (resolution / 2 <= clearance <= 100):
        raise ValueError(
            f"clearance must be in [resolution / 2, 100] = [{resolution / 2:g}, 100] pixels "
            f"(smaller lets motions between checked states cut corners), got {clearance!r}"
        )


def plan_ompl(
    scenario: Scenario,
    planner: str = "rrtstar",
    time_limit: float = 1.0,
    resolution: float = 0.5,
    clearance: float | None = None,
    simplify: bool = True,
    max_time: float | None = None,
) -> BaselineResult:
    """Plan once with an OMPL planner on the static obstacles and judge the route.

    Long by design: OMPL set-up, solve and the checker's verdict in one place, each a short block.

    Parameters
    ----------
    scenario : Scenario
    planner : str
        ``"rrtstar"``, ``"bitstar"`` or ``"prmstar"``.
    time_limit : float
        Wall-clock budget of the solve (seconds, in (0, 3600]); the asymptotically optimal
        planners use all of it. The reported ``time`` adds the setup (validity grid) and the
        simplification.
    resolution : float
        Motion-checking resolution (pixels, in (0, 10]).
    clearance : float, optional
        Extra inflation beyond the robot radius (pixels, >= ``resolution / 2``); default
        ``resolution``.
    simplify : bool
        Shorten the solution with OMPL's path simplifier (within the same validity checks).
    max_time : float, optional
        Keep solving past ``time_limit`` until the first exact solution, for at most
        ``max_time`` seconds of solve in all (>= ``time_limit``, <= 3600): a planner starved of
        CPU by a loaded machine then still answers. Default None: stop at ``time_limit``.

    Returns
    -------
    BaselineResult
        ``validity_checks`` counts every state check, simplification included.

    Raises
    ------
    ImportError
        If ``ompl`` is not installed (the message gives the pip command).
    """
    base, geometric = _import_ompl()
    clearance = resolution if clearance is None else float(clearance)
    _check_options(planner, time_limit, resolution, clearance)
    if max_time is not None and not (time_limit <= max_time <= 3600):
        raise ValueError(
            f"max_time must be None or in [time_limit, 3600] = [{time_limit:g}, 3600] seconds, "
            f"got {max_time!r}"
        )
    space = base.RealVectorStateSpace(2)
    bounds = base.RealVectorBounds(2)
    box = centre_box(scenario, scenario.robot_radius)
    for axis in (0, 1):
        bounds.setLow(axis, box[axis])
        bounds.setHigh(axis, box[axis + 2])
    space.setBounds(bounds)
    si = base.SpaceInformation(space)
    t0 = time.perf_counter()
    validity = _Validity(_blocked(scenario, clearance), scenario.width, scenario.height, box)
    si.setStateValidityChecker(validity)
    # OMPL states the resolution as a fraction of the space's extent (the map diagonal)
    si.setStateValidityCheckingResolution(
        resolution / float(np.hypot(scenario.width, scenario.height))
    )
    si.setup()
    for name, p in (("start", scenario.start), ("goal", scenario.goal)):
        if shapely.intersects_xy(validity.blocked, *p):
            why = f"{name} is within robot radius + clearance ({clearance:g} px) of an obstacle"
            return make_result(planner, scenario, None, time.perf_counter() - t0, 0, why)
    pdef = base.ProblemDefinition(si)
    ends = []
    for p in (scenario.start, scenario.goal):
        st = space.allocState()
        st[0], st[1] = float(p[0]), float(p[1])
        ends.append(st)
    pdef.setStartAndGoalStates(ends[0], ends[1], 1e-9)
    pdef.setOptimizationObjective(base.PathLengthOptimizationObjective(si))
    algo = getattr(geometric, OMPL_PLANNERS[planner])(si)
    algo.setProblemDefinition(pdef)
    algo.setup()
    t_solve = time.perf_counter()
    algo.solve(float(time_limit))
    # more of the same budget while no route is found: a planner keeps its tree between calls,
    # and publishes its solution only when a call returns
    while max_time is not None and not pdef.hasExactSolution():
        left = t_solve + max_time - time.perf_counter()
        if left <= 0:
            break
        algo.solve(float(min(time_limit, left)))
    route, reason = None, "no exact solution within the time budget"
    if pdef.hasExactSolution():
        path = pdef.getSolutionPath()
        if simplify:
            geometric.PathSimplifier(si).simplifyMax(path)
        route = np.array(
            [[path.getState(i)[0], path.getState(i)[1]] for i in range(path.getStateCount())]
        )
        route[0], route[-1] = scenario.start, scenario.goal
        reason = "ok"
    seconds = time.perf_counter() - t0
    return make_result(planner, scenario, route, seconds, validity.calls, reason)
