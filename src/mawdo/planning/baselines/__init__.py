"""Baseline planners judged by the same independent checker as ours.

=========  ==========  =============================================================
name       sees time   what
=========  ==========  =============================================================
straight   no          the segment start -> goal
rrtstar    no          OMPL RRT*, single shot on the static obstacles (``ompl`` extra)
bitstar    no          OMPL BIT*, idem
prmstar    no          OMPL PRM*, idem
=========  ==========  =============================================================

Every baseline returns a :class:`BaselineResult` (:func:`as_plan_result` turns it into the
:class:`~mawdo.planning.run.result.PlanResult` every planner of
:data:`mawdo.planning.run.planners.PLANNERS` returns); its route, followed at the robot's speed from
t = 0, is judged against all obstacles (moving ones included) by
:func:`mawdo.planning.judge.check.check_trajectory`. ``run_baseline(name, scenario, **options)``
dispatches by name; OMPL options are ``time_limit`` (s), ``resolution`` (px), ``clearance``
(px), ``simplify`` and ``max_time`` (s; see :func:`plan_ompl`).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from functools import partial

from mawdo.planning.baselines.result import BaselineResult, as_plan_result, judge, route_times
from mawdo.planning.baselines.sampling import OMPL_PLANNERS, ompl_available, plan_ompl
from mawdo.planning.baselines.straight import plan_straight
from mawdo.planning.world.scenario import Scenario
from mawdo.registry import Registry

__all__ = [
    "BASELINES",
    "BaselineResult",
    "BaselineSpec",
    "as_plan_result",
    "judge",
    "ompl_available",
    "plan_ompl",
    "plan_straight",
    "route_times",
    "run_baseline",
]


@dataclass(frozen=True)
class BaselineSpec:
    """A registered baseline: ``run(scenario, **options) -> BaselineResult``."""

    name: str
    run: Callable[..., BaselineResult]
    sees_time: bool
    needs_ompl: bool
    description: str


#: Registered baselines by name.
BASELINES: Registry[BaselineSpec] = Registry("baseline")
BASELINES.register(
    "straight", BaselineSpec("straight", plan_straight, False, False, "straight segment")
)
for _name, _cls in OMPL_PLANNERS.items():
    BASELINES.register(
        _name,
        BaselineSpec(
            _name,
            partial(plan_ompl, planner=_name),
            False,
            True,
            f"OMPL {_cls}, single shot on static obstacles",
        ),
    )


def run_baseline(name: str, scenario: Scenario, **options) -> BaselineResult:
    """Run the baseline ``name`` (see :data:`BASELINES`) on ``scenario``.

    Raises
    ------
    mawdo.registry.UnknownNameError
        Unknown name (close names suggested).
    ImportError
        An OMPL baseline without ``ompl`` installed (the message gives the pip command).
    TypeError
        Options the baseline does not take.
    """
    spec = BASELINES[name]
    return spec.run(scenario, **options)
