"""One crowd task on a worker: episodes ``first_run ..`` of one setting, run by one policy.

Every policy runs in the same world runner (:func:`~mawdo.planning.run.episode.run_episode`),
judged by the same checker on the realised trajectories; the row's lengths are metres and its
times seconds (the scene's resolution and time step).
"""

from __future__ import annotations

import time
import traceback
from dataclasses import dataclass
from typing import Any

import numpy as np

from mawdo.experiments.rows import RunRow, column

#: CrowdNav's discomfort distance (metres): a separation below it counts against comfort.
DISCOMFORT_M = 0.2


@dataclass(frozen=True)
class CrowdRow(RunRow):
    """One policy on one episode (metres, seconds, milliseconds).

    ``success``: goal reached, no collision of any kind; ``robot_caused``: at least one
    collision the robot's motion produced (:func:`~mawdo.planning.judge.fault.blame`);
    ``collision``: any collision; ``timeout``: the time limit ran out first. ``time_s``: arrival
    time (successes only); ``discomfort``: share of steps whose separation from the nearest
    person (surface to surface, the smallest during the step) is below :data:`DISCOMFORT_M`;
    ``min_separation_m``: the checker's smallest clearance over the episode (continuous in time).
    """

    status: str | None = column("text", required=True)
    reason: str | None = column("text")
    people: int | None = column("int")
    visible: int | None = column("int")
    success: int | None = column("int")
    robot_caused: int | None = column("int")
    collision: int | None = column("int")
    timeout: int | None = column("int")
    time_s: float | None = column("real")
    discomfort: float | None = column("real")
    min_separation_m: float | None = column("real")
    length_m: float | None = column("real")
    latency_p50_ms: float | None = column("real")
    latency_p95_ms: float | None = column("real")
    steps: int | None = column("int")


def scene_of(setting: str, seed: int):
    """The :class:`~mawdo.planning.people.crowdnav.CrowdScene` of a setting and seed."""
    from mawdo.experiments.kinds.crowd.plan import parse_setting
    from mawdo.planning.people import crowdnav

    scene, people, visible = parse_setting(setting)
    make = crowdnav.circle_crossing if scene == "circle" else crowdnav.square_crossing
    return make(people, seed, visible=visible)


def _people(scene, seed: int):
    from mawdo.streams import episode_seed_sequences

    return scene.make_people(np.random.default_rng(episode_seed_sequences(seed)["world"]))


def world_of(scene, seed: int):
    """A fresh world of the scene: its people (drawn from the episode's world stream)."""
    from mawdo.planning.world.stepped import SteppedWorld

    return SteppedWorld(scene.scenario, people=_people(scene, seed), visible=scene.visible,
                        goal_tolerance=scene.scenario.robot_radius)  # fmt: skip


def future_of(scene, seed: int, steps: int):
    """The scenario with every person's future as if the robot were absent (exact for an
    invisible robot): what an ``oracle`` policy is told."""
    from mawdo.planning.world.stepped import people_future

    return people_future(scene.scenario, _people(scene, seed), steps)


def _sensor(spec: dict, res: float):
    s = spec["sensor"]
    if s["noise"] == 0 and s["range"] is None and s["miss_rate"] == 0:
        return None
    from mawdo.planning.sense.sensor import Sensor

    rng = np.inf if s["range"] is None else s["range"] / res
    return Sensor(range=rng, noise=s["noise"] / res, miss_rate=s["miss_rate"])


def separations(res) -> np.ndarray:
    """Smallest surface-to-surface distance (pixels) from the robot to any moving agent during
    each step (continuous in time: the checker's clearance of every piece of the executed
    route, as CrowdNav measures within a step, read from the run's own check when it kept
    one); ``inf`` without agents."""
    from mawdo.planning.judge.check import check_trajectory

    sc = res.scenario
    n = len(res.trajectory) - 1
    moving = sc.moving_indices
    if not moving or n < 1:
        return np.full(max(n, 0), np.inf)
    rep = res.check or check_trajectory(res.route, sc, times=res.route_times)
    piece = rep.clearance[:, moving].min(axis=1)
    step = np.clip(np.floor(res.route_times[:-1] + 1e-9).astype(int), 0, n - 1)
    out = np.full(n, np.inf)
    np.minimum.at(out, step, piece)
    return out


def episode_row(res, scene) -> dict[str, Any]:
    """The row's metrics of a finished episode."""
    from mawdo.planning.world.path import polyline_length

    r, dt = scene.res, scene.dt
    lat = res.latencies * 1e3
    sep = separations(res)
    hits = res.robot_caused + res.other_collisions
    return {
        "reason": res.reason,
        "success": int(res.success),
        "robot_caused": int(res.robot_caused > 0),
        "collision": int(hits > 0),
        "timeout": int(res.reason.startswith("step limit")),
        "time_s": res.steps * dt if res.success else None,
        "discomfort": float(np.mean(sep < DISCOMFORT_M / r)) if len(sep) else 0.0,
        "min_separation_m": float(res.min_clearance) * r,
        "length_m": polyline_length(res.route) * r,
        "latency_p50_ms": float(np.percentile(lat, 50)) if len(lat) else None,
        "latency_p95_ms": float(np.percentile(lat, 95)) if len(lat) else None,
        "steps": res.steps,
    }


def run_one(spec: dict[str, Any], setting: str, seed: int):
    """One episode of ``spec``'s policy: the result and the scene."""
    from mawdo.planning.run.episode import run_episode
    from mawdo.planning.run.policies import POLICIES

    scene = scene_of(setting, seed)
    entry = POLICIES[spec["algorithm"]]
    options = {
        "preset": spec["preset"],
        "overrides": spec["overrides"],
        "noise": spec["sensor"]["noise"] / scene.res,
        "predictor": spec["predictor"],
        "strays": spec.get("strays", False),
    }
    policy = entry.make(options)
    steps = scene.time_limit_steps
    known = future_of(scene, seed, steps) if entry.knowledge == "oracle" else None
    res = run_episode(
        world_of(scene, seed),
        policy,
        steps,
        seed=seed,
        sensor=_sensor(spec, scene.res),
        name=entry.name,
        known=known,
    )
    return res, scene


def execute_crowd_task(spec: dict[str, Any]) -> list[CrowdRow]:
    """Run episodes ``first_run ..`` of one setting with one policy; a run that raises becomes
    a row with its error text."""
    from mawdo.experiments.kinds.crowd.plan import parse_setting

    _, people, visible = parse_setting(spec["problem"])
    rows = []
    for i, seed in enumerate(spec["seeds"]):
        common = {"run": spec["first_run"] + i, "people": people, "visible": int(visible)}
        t0 = time.perf_counter()
        try:
            res, scene = run_one(spec, spec["problem"], seed)
            m = episode_row(res, scene)
        except Exception as exc:  # noqa: BLE001 - a failing run is a row, not a dead study
            err = "".join(traceback.format_exception_only(exc)).strip()
            rows.append(CrowdRow(**common, wall_time=time.perf_counter() - t0, error_text=err))
            continue
        rows.append(CrowdRow(**common, **m, status="ok", wall_time=time.perf_counter() - t0))
    return rows
