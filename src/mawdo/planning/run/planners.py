"""Every planner by name: :data:`PLANNERS`, ``name -> run(scenario, seed, config, **options)
-> PlanResult``.

=================  ======================  ==========================================
name               sees time               what
=================  ======================  ==========================================
any optimizer      yes (predicted motion)  the receding-horizon planner driven by it
mawdo_literal      yes (predicted motion)  MAWDO with the paper's D <= 3 threshold
mawdo_time         yes (+ safe intervals)  MAWDO with the safe-interval guide on
guide_only         yes (+ safe intervals)  the guides' best seed, no optimizer
policy:<name>      as the policy knows     any registered policy in a stepped world
mawdo_observed,    tracked positions each  the same two told nothing of the future: a
guide_only_        step                    tracker and a constant-velocity predictor
observed                                   each step (:mod:`~mawdo.planning.run.policy`)
oracle_follower    positions each step     exact shortest path on the frozen map
straight           no                      the segment start -> goal
rrtstar, bitstar,  no                      OMPL, single shot on the static obstacles
prmstar                                    (``ompl`` extra)
=================  ======================  ==========================================

Every registered optimizer (:data:`mawdo.optimizers.OPTIMIZERS`) is a planner through one
adapter over the run loop, looked up when asked for, so an optimizer registered later is a
planner too. Every planner returns a :class:`~mawdo.planning.run.result.PlanResult` judged by the
independent checker, obeys the one step-limit rule (:func:`~mawdo.planning.run.config.step_limit`)
and is measured by :func:`mawdo.planning.judge.metrics.run_metrics`.

Adding a planner: a module with its ``run`` function, and one line here::

    PLANNERS.register("mine", PlannerSpec("mine", run, sees_time="no", description="..."))
"""

from __future__ import annotations

import inspect
from collections.abc import Callable, Iterator
from dataclasses import dataclass, field, replace
from functools import partial
from typing import Any

from mawdo.planning.baselines import BASELINES, BaselineSpec, as_plan_result
from mawdo.planning.run.config import PlannerConfig, resolve_config, resolve_scenario
from mawdo.planning.run.follower import ORACLE_FOLLOWER, follow_oracle
from mawdo.planning.run.result import PlanResult
from mawdo.planning.run.timed_planners import guide_only_run, mawdo_time_run
from mawdo.registry import Registry, UnknownNameError, unknown_name_message

__all__ = ["PLANNERS", "PlannerSpec", "run_planner"]

#: How a planner driven by an optimizer sees the moving obstacles.
PREDICTED = "yes (predicted motion)"
#: How a planner with observed knowledge sees them.
OBSERVED = "tracked positions each step"


@dataclass(frozen=True)
class PlannerSpec:
    """A registered planner.

    Attributes
    ----------
    name : str
        Registered name (the ``algorithm`` column of a study's store).
    run : callable
        ``run(scenario, seed, config, **options) -> PlanResult``; ``config`` a
        :class:`~mawdo.planning.run.config.PlannerConfig`.
    sees_time : str
        How the planner knows the moving obstacles: ``"yes (predicted motion)"``,
        ``"positions each step"`` or ``"no"``.
    description : str
        One line.
    needs_extra : str or None
        The optional dependency it needs (``"ompl"``), None for none.
    seeded : bool
        Its result depends on the seed (False: one run says all).
    options : tuple of str
        Keyword options ``run`` takes beyond the config (OMPL: ``time_limit``, ...).
    optimizer : str or None
        The registered optimizer driving it; None for the baselines.
    optimizer_options : dict
        Options the planner fixes for that optimizer (a variant such as ``mawdo_literal``);
        they win over ``config.options``.
    """

    name: str
    run: Callable[..., PlanResult]
    sees_time: str
    description: str
    needs_extra: str | None = None
    seeded: bool = True
    options: tuple[str, ...] = ()
    optimizer: str | None = None
    optimizer_options: dict[str, Any] = field(default_factory=dict)


def optimizer_run(scenario, seed, config: PlannerConfig, algorithm: str, fixed=None):
    """The receding-horizon run loop driven by ``algorithm`` (:func:`mawdo.planning.run.planner.
    plan`), with the options ``fixed`` over ``config.options``."""
    from mawdo.planning.run.planner import plan

    if fixed:
        config = replace(config, options={**config.options, **fixed})
    return plan(scenario, algorithm=algorithm, seed=seed, config=config)


def optimizer_planner(algorithm: str, name: str | None = None, fixed=None, description=None):
    """The :class:`PlannerSpec` of the run loop driven by a registered optimizer."""
    fixed = dict(fixed or {})
    return PlannerSpec(
        name=name or algorithm,
        run=partial(optimizer_run, algorithm=algorithm, fixed=fixed),
        sees_time=PREDICTED,
        description=description or f"receding horizon driven by {algorithm}",
        optimizer=algorithm,
        optimizer_options=fixed,
    )


#: ``policy:<name>`` is the registered policy ``<name>`` as a planner (``PLANNERS["policy:dwa"]``).
POLICY_PREFIX = "policy:"


def policy_planner(policy: str) -> PlannerSpec:
    """The :class:`PlannerSpec` of a registered policy
    (:data:`~mawdo.planning.run.policies.POLICIES`, an unknown name lists them): it drives the
    robot through a stepped world of the scenario, seeing what the policy's knowledge allows."""
    from mawdo.planning.run.policies import POLICIES, registered_policy_run

    spec = POLICIES[policy]
    sees = {"observed": OBSERVED, "oracle": PREDICTED, "none": "no"}[spec.knowledge]
    return PlannerSpec(
        name=POLICY_PREFIX + spec.name, run=partial(registered_policy_run, policy=spec.name),
        sees_time=sees, description=f"the policy {spec.name}: {spec.description}",
    )  # fmt: skip


class PlannerRegistry(Registry[PlannerSpec]):
    """The registered planners, then every registered optimizer (looked up when asked)."""

    def _optimizers(self):
        from mawdo.optimizers import OPTIMIZERS

        return OPTIMIZERS

    def __getitem__(self, name: str) -> PlannerSpec:
        if not isinstance(name, str):
            raise TypeError(f"planner name must be a string, got {type(name).__name__}")
        key = name.strip().lower()
        if key in self._items:
            return self._items[key]
        opts = self._optimizers()
        if key in opts:
            return optimizer_planner(opts[key].name)
        if key.startswith(POLICY_PREFIX):
            return policy_planner(key.removeprefix(POLICY_PREFIX))
        raise UnknownNameError(unknown_name_message(self.kind, name, list(self)))

    def __iter__(self) -> Iterator[str]:
        return iter([*self._items, *(n for n in self._optimizers() if n not in self._items)])

    def __len__(self) -> int:
        return len(list(iter(self)))

    def __contains__(self, name) -> bool:
        if not isinstance(name, str):
            return False
        key = name.strip().lower()
        if key.startswith(POLICY_PREFIX):  # the policies are planners too, looked up when asked
            from mawdo.planning.run.policies import POLICIES

            return key.removeprefix(POLICY_PREFIX) in POLICIES
        return key in list(self)


def _baseline(base, scenario, seed, config: PlannerConfig, **options) -> PlanResult:
    return as_plan_result(scenario, base.run(scenario, **options), config)


def baseline_planner(base: BaselineSpec) -> PlannerSpec:
    """The :class:`PlannerSpec` of a single-shot baseline
    (:data:`mawdo.planning.baselines.BASELINES`): its route as a ``PlanResult``
    (:func:`~mawdo.planning.baselines.as_plan_result`), under the shared step limit."""
    takes = inspect.signature(base.run).parameters
    options = tuple(n for n, p in takes.items() if n not in ("scenario", "planner")
                    and p.kind in (p.POSITIONAL_OR_KEYWORD, p.KEYWORD_ONLY))  # fmt: skip
    return PlannerSpec(
        name=base.name, run=partial(_baseline, base),
        sees_time="predicted motion" if base.sees_time else "no", description=base.description,
        needs_extra="ompl" if base.needs_ompl else None, seeded=False, options=options,
    )  # fmt: skip


def _observed(scenario, seed, config: PlannerConfig, algorithm: str) -> PlanResult:
    from mawdo.planning.run.policy import observed_run

    return observed_run(scenario, seed, replace(config, time_guide=True), algorithm)


def _follow(scenario, seed, config: PlannerConfig) -> PlanResult:
    return follow_oracle(scenario, max_steps=config.max_steps)


#: Every planner by name (case-insensitive; an unknown name suggests close ones).
PLANNERS: PlannerRegistry = PlannerRegistry("planner")
PLANNERS.register(
    "mawdo_literal",
    optimizer_planner("mawdo", "mawdo_literal", {"low_dim": 3}, "MAWDO with the paper's D <= 3 "
                      "threshold (docs/deviations.md#d-planning-low-dim)"),
)  # fmt: skip
PLANNERS.register("mawdo_time", PlannerSpec("mawdo_time", mawdo_time_run, PREDICTED,
                  "MAWDO, safe-interval guide on (time_guide)", optimizer="mawdo"))  # fmt: skip
PLANNERS.register("guide_only", PlannerSpec("guide_only", guide_only_run, PREDICTED,
                  "the guides' best seed, no optimizer (time_guide on)", seeded=False))  # fmt: skip
PLANNERS.register("mawdo_observed", PlannerSpec(
    "mawdo_observed", partial(_observed, algorithm="mawdo"), OBSERVED,
    "MAWDO (time guide on) on tracked, constant-velocity predictions",
    optimizer="mawdo"))  # fmt: skip
PLANNERS.register("guide_only_observed", PlannerSpec(
    "guide_only_observed", partial(_observed, algorithm="guide_only"), OBSERVED,
    "guide_only on tracked, constant-velocity predictions", seeded=False))  # fmt: skip
PLANNERS.register(
    ORACLE_FOLLOWER,
    PlannerSpec(ORACLE_FOLLOWER, _follow, "positions each step",
                "exact shortest path on the obstacles frozen at each step", seeded=False),
)  # fmt: skip
for _name, _base in BASELINES.items():  # straight, rrtstar, bitstar, prmstar
    PLANNERS.register(_name, baseline_planner(_base))


def run_planner(name: str, scenario, seed: int = 0, config=None, **options) -> PlanResult:
    """Run the planner ``name`` (:data:`PLANNERS`) once.

    Parameters
    ----------
    name : str
        A registered planner or optimizer.
    scenario : Scenario or str
    seed : int
        Seed of a seeded planner (ignored by the deterministic ones).
    config : PlannerConfig or str, optional
        Settings or a preset name (default ``"realtime"``).
    **options
        The planner's own options (:attr:`PlannerSpec.options`).

    Raises
    ------
    mawdo.registry.UnknownNameError
        Unknown name (close names suggested).
    ImportError
        A planner whose extra is not installed (the message gives the pip command).
    """
    spec = PLANNERS[name]
    return spec.run(resolve_scenario(scenario), seed, resolve_config(config), **options)
