"""Gymnasium environments on mawdo's stepped world: CrowdNav scenes and scenario files.

Each step the robot drives the action for one time step, the people take a step of their own
model (:class:`~mawdo.planning.world.stepped.SteppedWorld`), the step is judged
(:mod:`mawdo.gym.reward`) and the sensor reads the world for the next observation
(:mod:`mawdo.gym.observation`). Episodes are those of
:func:`~mawdo.planning.run.episode.run_episode` on the same seed: the same people, the same
sensor errors, the same verdicts.

Action: a velocity ``(vx, vy)`` in m/s (px/step in a pixel scenario), map axes, each component in
``[-v, v]`` with ``v`` the robot's speed (clipped to it); a longer vector is scaled down to ``v``
by the world, as for every mawdo policy.

An episode ends (``terminated``) when the robot reaches its goal (within the goal tolerance) or
collides (with a person, a scripted mover, a wall or the map's border), and is truncated at the
step limit.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import gymnasium as gym
import numpy as np

from mawdo.gym.observation import Observer, unit_scales
from mawdo.gym.options import check_options, sensor_of
from mawdo.gym.reward import Rewards, crowdnav_reward, judge_step
from mawdo.planning.run.episode import read_world  # the env reads the world as the runner does
from mawdo.streams import episode_seed_sequences
from mawdo.util.validate import check_real

__all__ = ["CrowdEnv", "MawdoEnv", "ScenarioEnv", "read_world"]

_SEED_HIGH = 2**63 - 1


class MawdoEnv(gym.Env):
    """The shared environment: subclasses say how an episode's world is built.

    Attributes
    ----------
    world : SteppedWorld
        The current episode's world (pixels, time steps).
    reading : Reading
        The sensor's reading the last observation was built from.
    episode_seed : int
        The current episode's seed (its world, sensor and policy streams:
        :func:`~mawdo.streams.episode_seed_sequences`).
    policy_seed : numpy.random.SeedSequence
        The episode's policy stream (what ``run_episode`` gives a policy's ``reset``).
    episode_id : int
        Counts the resets (an adapter resets its policy when it changes).
    """

    metadata = {"render_modes": ["rgb_array"], "render_fps": 4}
    env_id = "mawdo env"
    render_mode: str | None = None

    def __init__(self, options: dict[str, Any], extra: dict[str, Any]) -> None:
        self.options = check_options(self.env_id, options, extra)
        o = self.options
        self.rewards = Rewards(o["success_reward"], o["collision_penalty"],
                               o["discomfort_dist"], o["discomfort_penalty_factor"])  # fmt: skip
        self.world = self.reading = self.sensor = None
        self.episode_seed, self.policy_seed, self.episode_id = None, None, 0
        self._ended = False
        scenario = self._template()
        res, dt = unit_scales(scenario.units)
        speed = float(scenario.robot_speed) * res / dt
        self.observer = self._observer(res)
        low, high = self.observer.bounds(scenario)
        self.observation_space = gym.spaces.Box(low, high, dtype=np.float32)
        self.action_space = gym.spaces.Box(-speed, speed, shape=(2,), dtype=np.float64)

    def _observer(self, res: float) -> Observer:
        from mawdo.planning.sense.tracker import Tracker

        o = self.options
        tracker = Tracker(noise=o["sensor_noise"] / res, strays=o["strays"])
        return Observer(o["k"], o["n_rays"], o["max_range"], tracker)

    # -- what subclasses give ------------------------------------------------------------------
    def _template(self):
        """A scenario of the environment (robot, map, units) for the spaces."""
        raise NotImplementedError

    def _episode(self, seed: int):
        """``(world, step limit)`` of the episode with this seed."""
        raise NotImplementedError

    # -- the Gymnasium interface ---------------------------------------------------------------
    def reset(self, *, seed: int | None = None, options: dict | None = None):
        """Start an episode.

        Parameters
        ----------
        seed : int, optional
            The episode's seed, >= 0: the same seed gives the same episode (people, sensor
            errors), as ``run_episode(..., seed=seed)``. ``None``: the next seed drawn from the
            environment's generator (seeded by the last ``seed`` given).
        options : dict, optional
            Not used (must be empty).

        Returns
        -------
        observation : numpy.ndarray
        info : dict
            ``episode_seed``.
        """
        super().reset(seed=seed)
        if options:
            raise ValueError(f"reset takes no options, got {sorted(options)}")
        if seed is None:
            seed = int(self.np_random.integers(0, _SEED_HIGH))
        self.episode_seed = int(seed)
        streams = episode_seed_sequences(self.episode_seed)
        self.world, self.max_steps = self._episode(self.episode_seed)
        sc = self.world.scenario
        self.res, self.dt = unit_scales(sc.units)
        self.sensor = sensor_of(self.options, self.res)
        self._rng = np.random.default_rng(streams["sensor"])
        self.policy_seed = streams["policy"]
        self.episode_id += 1
        self._ended = False
        self.observer.reset(sc, self.world.walls())
        return self._observe(), {"episode_seed": self.episode_seed}

    def render(self):
        """With ``render_mode="rgb_array"``: the world now as an RGB image (``uint8``,
        ``(height, width, 3)``; :func:`mawdo.gym.render.frame`); without a render mode, None."""
        if self.render_mode is None:
            return None
        if self.world is None:
            raise RuntimeError("render before reset(): call env.reset(seed=...) first")
        from mawdo.gym.render import frame

        return frame(self.world)

    def _observe(self) -> np.ndarray:
        self.reading = read_world(self.world, self.sensor, self._rng)
        return self.observer.observe(self.reading)

    def step(self, action):
        """Drive ``action`` (m/s) for one step.

        Returns
        -------
        observation : numpy.ndarray
        reward : float
            CrowdNav's (:func:`~mawdo.gym.reward.crowdnav_reward`).
        terminated : bool
            Goal reached or collision.
        truncated : bool
            Step limit reached first.
        info : dict
            ``success``, ``collision``, ``robot_caused`` (bool), ``time_s`` (time since the
            start, s), ``separation_m`` (smallest distance to a moving agent during the step,
            m; ``inf`` without agents), ``episode_seed``.
        """
        if self.world is None:
            raise RuntimeError("step before reset(): call env.reset(seed=...) first")
        if self._ended:
            raise RuntimeError("the episode has ended; call env.reset() to start another")
        velocity = self.observer.velocity_px(action)
        world = self.world
        people0 = world.people.positions() if world.people is not None else np.zeros((0, 2))
        world.step(velocity)
        out = judge_step(world, people0)
        success = not out.collision and world.at_goal()
        sep_m = out.separation * self.res
        reward = crowdnav_reward(out.collision, success, sep_m, self.dt, self.rewards)
        terminated = out.collision or success
        truncated = not terminated and world.step_index >= self.max_steps
        self._ended = terminated or truncated
        info = {
            "success": success, "collision": out.collision, "robot_caused": out.robot_caused,
            "time_s": world.step_index * self.dt, "separation_m": sep_m,
            "episode_seed": self.episode_seed,
        }  # fmt: skip
        return self._observe(), reward, terminated, truncated, info


def _check_render(render_mode) -> str | None:
    if render_mode not in (None, *MawdoEnv.metadata["render_modes"]):
        raise ValueError(
            f"render_mode={render_mode!r}: these environments render 'rgb_array' frames "
            "(or nothing: None)"
        )
    return render_mode


class CrowdEnv(MawdoEnv):
    """``mawdo/Crowd-v0``: a CrowdNav scene (circle or square crossing) per episode.

    Parameters
    ----------
    setting : str
        ``<scene>-<people>-<visibility>``, e.g. ``circle-5-invisible``
        (:func:`~mawdo.experiments.kinds.crowd.plan.parse_setting`); each episode's scene is
        :func:`~mawdo.experiments.kinds.crowd.execute.scene_of` of the setting and the episode
        seed, its world :func:`~mawdo.experiments.kinds.crowd.execute.world_of`: the crowd
        study's episodes.
    render_mode : {None, "rgb_array"}
        ``"rgb_array"``: :meth:`render` returns the world now as an image.
    **options
        See :data:`~mawdo.gym.options.COMMON`; ``max_steps`` defaults to the scene's 25 s.
    """

    env_id = "mawdo/Crowd-v0"

    def __init__(self, setting: str = "circle-5-invisible", render_mode=None, **options) -> None:
        from mawdo.experiments.kinds.crowd.plan import parse_setting

        self.render_mode = _check_render(render_mode)
        parse_setting(setting)
        self.setting = str(setting)
        super().__init__(options, {})

    def _template(self):
        from mawdo.experiments.kinds.crowd.execute import scene_of

        return scene_of(self.setting, 0).scenario

    def _episode(self, seed: int):
        from mawdo.experiments.kinds.crowd.execute import scene_of, world_of

        scene = scene_of(self.setting, seed)
        limit = self.options["max_steps"] or scene.time_limit_steps
        return world_of(scene, seed), limit


class ScenarioEnv(MawdoEnv):
    """``mawdo/Scenario-v0``: a scenario (map, scripted obstacles and, from its ``[crowd]``
    table, people) played from its start every episode.

    Parameters
    ----------
    scenario : Scenario, str or pathlib.Path
        A scenario, a scenario file's path or a built-in scenario's name
        (:func:`~mawdo.planning.world.scenario.get_scenario`).
    render_mode : {None, "rgb_array"}
        ``"rgb_array"``: :meth:`render` returns the world now as an image.
    **options
        See :data:`~mawdo.gym.options.COMMON`, plus ``goal_tolerance``: the goal counts as
        reached within this distance of the robot centre (m; default the robot's radius, as
        CrowdNav). ``max_steps`` defaults to the planner's rule (4 straight start-goal lines at
        the robot's speed, plus 10 steps).

    Notes
    -----
    The people walk from their starts every episode (their goal changes draw from the
    episode's world stream: :func:`~mawdo.planning.people.from_scenario.people_of`).
    """

    env_id = "mawdo/Scenario-v0"

    def __init__(self, scenario=None, render_mode=None, **options) -> None:
        from mawdo.planning.world.scenario import Scenario, get_scenario

        self.render_mode = _check_render(render_mode)
        if scenario is None:
            raise ValueError("mawdo/Scenario-v0 needs scenario=<Scenario, file path or name>")
        if not isinstance(scenario, Scenario):
            if not isinstance(scenario, str | Path):
                raise ValueError(
                    f"scenario must be a Scenario, a file path or a built-in name, "
                    f"not {type(scenario).__name__}"
                )
            scenario = get_scenario(scenario)
        self.scenario = scenario
        super().__init__(options, {"goal_tolerance": None})
        tol = self.options["goal_tolerance"]
        if tol is None:
            self._goal_tolerance = float(scenario.robot_radius)
        else:
            check_real("goal_tolerance", tol, 0.0)
            self._goal_tolerance = float(scenario.units.length_to_px(tol))

    def _template(self):
        return self.scenario

    def _episode(self, seed: int):
        from mawdo.planning.people.from_scenario import people_of
        from mawdo.planning.run.config import step_limit
        from mawdo.planning.world.stepped import SteppedWorld

        sc = self.scenario
        rng = np.random.default_rng(episode_seed_sequences(seed)["world"])
        crowd = sc.spec.crowd
        world = SteppedWorld(sc, people_of(sc, rng), visible=bool(crowd and crowd.visible),
                             goal_tolerance=self._goal_tolerance)  # fmt: skip
        limit = self.options["max_steps"]
        if limit is None:
            limit = step_limit(None, sc.straight_line_length(), 0.0, sc.robot_speed)[0]
        return world, limit
