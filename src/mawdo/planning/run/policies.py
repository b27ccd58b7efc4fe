"""Every policy the stepped world can drive, by name: the registry the crowd study looks up.

=====================  ==========  ====================================================
name                   knowledge   what it is
=====================  ==========  ====================================================
mawdo                  observed    our planner (MAWDO, safe-interval guide on) on the
                                   tracker's constant-velocity predictions
guide_only             observed    the same without the optimizer: the guides' best seed
mawdo_oracle           oracle      MAWDO told every agent's future (the upper bound;
                                   exact when the people do not see the robot)
mawdo_told             oracle      ``mawdo``'s step-by-step loop with its predictor told
                                   that future (the loop's cost without the guess)
orca_robot             observed    the robot driven by ORCA on the tracks (``crowd``)
social_force_robot     observed    the robot driven by the social force (``crowd``)
dwa                    observed    a sampling local planner (dynamic window) on the
                                   tracks moving at constant velocity
straight               none        straight to the goal at full speed
woa, gwo, wdo_plus     observed    our planner with that optimizer in MAWDO's place
                                   (which swarm refines best)
=====================  ==========  ====================================================

A policy is built by ``make(options)``, ``options`` holding the planner preset and overrides,
the sensor's noise (for the tracker, pixels), the predictor's name and the world's resolution
``res`` (metres per pixel) and time step ``dt`` (seconds); each entry takes what it needs.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

from mawdo.registry import Registry

__all__ = ["POLICIES", "PolicySpec", "make_policy", "study_tracker"]


@dataclass(frozen=True)
class PolicySpec:
    """A registered policy.

    Attributes
    ----------
    name : str
        Registry name.
    make : callable
        ``make(options) -> Policy``.
    knowledge : str
        ``"oracle"`` (told the agents' future), ``"observed"`` (sensor readings only) or
        ``"none"`` (sees no agent).
    description : str
        One line for listings and reports.
    """

    name: str
    make: Callable[[dict[str, Any]], Any]
    knowledge: str
    description: str


POLICIES: Registry[PolicySpec] = Registry("policy")


def study_tracker(options):
    """The tracker of an observing policy built from a study's ``options``: the sensor's
    ``noise`` (pixels, default 0) and ``strays`` (default False; see
    :class:`~mawdo.planning.sense.tracker.Tracker`)."""
    from mawdo.planning.sense.tracker import Tracker

    noise, strays = float(options.get("noise", 0.0)), bool(options.get("strays", False))
    return Tracker(noise=noise, strays=strays)


def _settings(options) -> dict:
    """Our planner's settings in every policy built on it: the safe-interval guide on, then the
    plan's overrides."""
    return {"time_guide": True, **options.get("overrides", {})}


def _planner(algorithm: str, knowledge: str):
    def make(options):
        from mawdo.planning.run.policy import PlannerPolicy

        over = _settings(options)
        extra = {}
        if knowledge == "observed":
            extra = {"tracker": study_tracker(options), "predictor": options.get("predictor",
                     "constant_velocity")}  # fmt: skip
        return PlannerPolicy(algorithm, options.get("preset"), knowledge, **extra, **over)

    return make


def _told(options):
    from mawdo.planning.run.told import ToldFuturePolicy

    return ToldFuturePolicy(
        "mawdo", options.get("preset"), tracker=study_tracker(options), **_settings(options)
    )


def _dwa(options):
    from mawdo.planning.run.dwa import DynamicWindow

    return DynamicWindow(tracker=study_tracker(options))


def _straight(options):
    from mawdo.planning.run.policy import StraightLine

    return StraightLine()


def _robot(cls_name: str):
    def make(options):
        from mawdo.planning.people import robots

        # CrowdNav's settings in metres and seconds, at the world's resolution and time step
        res, dt = options.get("res", 0.05), options.get("dt", 0.25)
        return getattr(robots, cls_name).from_metres(res, dt, tracker=study_tracker(options))

    return make


for _spec in (
    PolicySpec("mawdo", _planner("mawdo", "observed"), "observed",
               "MAWDO on constant-velocity predictions of the tracks"),
    PolicySpec("guide_only", _planner("guide_only", "observed"), "observed",
               "the guides' best seed on the same predictions, no optimizer"),
    PolicySpec("mawdo_oracle", _planner("mawdo", "oracle"), "oracle",
               "MAWDO told every agent's future (upper bound)"),
    PolicySpec("mawdo_told", _told, "oracle",
               "MAWDO's step-by-step loop, its predictor told every agent's future"),
    PolicySpec("orca_robot", _robot("OrcaRobot"), "observed", "ORCA on the tracks"),
    PolicySpec("social_force_robot", _robot("SocialForceRobot"), "observed",
               "social force on the tracks"),
    PolicySpec("dwa", _dwa, "observed",
               "sampling local planner (dynamic window) on constant-velocity tracks"),
    PolicySpec("straight", _straight, "none", "straight to the goal, blind"),
    # the same planner with another swarm as its refiner: which optimizer refines best
    *(PolicySpec(name, _planner(name, "observed"), "observed",
                 f"the planner with {label} as its optimizer, on the same predictions")
      for name, label in (("woa", "WOA"), ("gwo", "GWO"), ("wdo_plus", "WDO+"))),
):  # fmt: skip
    POLICIES.register(_spec.name, _spec)


def make_policy(name: str, options: dict[str, Any] | None = None):
    """A fresh policy by registered name (an unknown name lists the known ones)."""
    return POLICIES[name].make(dict(options or {}))


def registered_policy_run(scenario, seed, config, policy: str):
    """A scenario run by a registered policy in a stepped world, under the planners' one step
    limit (:func:`~mawdo.planning.run.policy.run_as_planner`): any policy, a learned one
    included, judged as a planner (``policy:<name>`` in the planner registry). Policies built
    in metres get the scenario's resolution and time step (CrowdNav's for a pixel one)."""
    from mawdo.planning.run.policy import run_as_planner

    units = scenario.units
    options = {"res": units.resolution or 0.05, "dt": units.dt or 0.25}
    return run_as_planner(scenario, seed, config, make_policy(policy, options), f"policy:{policy}")
