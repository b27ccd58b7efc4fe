"""Adapters both ways between the environments' observation/action and mawdo's policies.

- :class:`CallablePolicy` makes any ``observation -> action`` callable (a trained network, a
  hand-written rule) a mawdo :class:`~mawdo.planning.sense.reading.Policy`, so
  :func:`~mawdo.planning.run.episode.run_episode` and the crowd study can judge it;
  :func:`register_policy` puts it in the :data:`~mawdo.planning.run.policies.POLICIES`
  registry under a name.
- :func:`policy_action` drives a mawdo policy (the ORCA robot, our planner) through an
  environment: a callable ``observation -> action`` that hands the policy the environment's
  reading.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

from mawdo.gym.observation import Observer
from mawdo.planning.world.stepped import Move, SteppedWorld

__all__ = ["CallablePolicy", "policy_action", "register_policy"]


def _walls(scenario) -> list[np.ndarray]:
    """The static walls a world of ``scenario`` reports (pixels), the environment's rays'
    targets."""
    return SteppedWorld(scenario).walls()


class CallablePolicy:
    """A mawdo policy that asks ``fn`` for its action on the environments' observation.

    Parameters
    ----------
    fn : callable
        ``fn(observation) -> action``: the observation vector of
        :mod:`mawdo.gym.observation` (``float32``), the action a velocity ``(vx, vy)`` in m/s
        (px/step in a pixel scenario), each component clipped to the robot's speed.
    k, n_rays, max_range : int, int, float
        The observation's layout, as the environment's options of the same names
        (``max_range`` in metres).
    tracker : Tracker, optional
        Estimates the agents' velocities (default: ``Tracker(noise=0)``; give the sensor's
        noise in pixels, as the environment does, for a noisy sensor).
    on_reset : callable, optional
        ``on_reset(seed)`` at every episode's start with the policy's seed (a
        :class:`numpy.random.SeedSequence`): to reseed a stochastic ``fn``.
    """

    def __init__(self, fn: Callable, *, k: int = 10, n_rays: int = 16, max_range: float = 4.0,
                 tracker=None, on_reset: Callable | None = None) -> None:  # fmt: skip
        if not callable(fn):
            raise ValueError(f"fn must be callable (observation -> action), got {fn!r}")
        if tracker is None:
            from mawdo.planning.sense.tracker import Tracker

            tracker = Tracker(noise=0.0)
        self.fn, self.on_reset = fn, on_reset
        self.observer = Observer(k, n_rays, max_range, tracker)

    def reset(self, scenario, seed) -> None:
        """Start an episode in ``scenario`` (its units, map and static walls)."""
        self.observer.reset(scenario, _walls(scenario))
        if self.on_reset is not None:
            self.on_reset(seed)

    def act(self, reading) -> np.ndarray:
        """The velocity (pixels per step) ``fn`` asks for on this reading's observation."""
        return self.observer.velocity_px(self.fn(self.observer.observe(reading)))


def policy_action(policy, env) -> Callable[[np.ndarray], np.ndarray]:
    """A callable ``observation -> action`` (m/s) that drives a mawdo ``policy`` in ``env``.

    The policy reads the environment's current :class:`~mawdo.planning.sense.reading.Reading`
    (``env.unwrapped.reading``, the one the observation was built from), not the observation;
    at each new episode it is reset with the world's scenario and the episode's policy seed, as
    :func:`~mawdo.planning.run.episode.run_episode` resets it. For a policy that returns
    velocities (the ORCA and social-force robots, ``dwa``, a :class:`CallablePolicy`) the
    episode is then the one ``run_episode`` gives on the same seed.

    A :class:`~mawdo.planning.world.stepped.Move` (our planner's step through corner points)
    becomes the velocity of its net displacement: the environment's action is one straight
    step, so the robot cuts the corners the planner's move would pass, and the episode can
    differ from ``run_episode``'s.

    Parameters
    ----------
    policy : Policy
        ``reset(scenario, seed)``, ``act(reading) -> velocity`` (pixels per step).
    env : gymnasium.Env
        A mawdo environment (possibly wrapped).
    """
    base = env.unwrapped
    seen = {"episode": None}

    def act(observation) -> np.ndarray:
        if base.world is None:
            raise RuntimeError("policy_action: reset the environment first")
        if seen["episode"] != base.episode_id:
            policy.reset(base.world.scenario, base.policy_seed)
            seen["episode"] = base.episode_id
        out = policy.act(base.reading)
        if isinstance(out, Move):  # one straight step to where the move ends
            out = out.points[-1] - base.world.position
        return base.observer.action_of(out)

    return act


def register_policy(name: str, fn: Callable, description: str = "", **observation):
    """Register ``fn`` (``observation -> action``) as a mawdo policy called ``name``.

    The registry's ``make(options)`` builds a :class:`CallablePolicy` whose tracker takes the
    sensor's noise from ``options["noise"]`` (pixels), as the registry's other observed
    policies do. The same ``fn`` serves every episode.

    Parameters
    ----------
    name : str
        Registry name (must be new).
    fn : callable
        ``observation -> action`` (m/s).
    description : str
        One line for listings.
    **observation
        ``k``, ``n_rays``, ``max_range``, ``on_reset`` of :class:`CallablePolicy`.

    Returns
    -------
    PolicySpec
    """
    from mawdo.planning.run.policies import POLICIES, PolicySpec, study_tracker

    CallablePolicy(fn, **observation)  # bad options fail here, not in a study's worker

    def make(options):
        return CallablePolicy(fn, tracker=study_tracker(options), **observation)

    spec = PolicySpec(name, make, "observed", description or f"callable policy {name}")
    POLICIES.register(name, spec)
    return spec
