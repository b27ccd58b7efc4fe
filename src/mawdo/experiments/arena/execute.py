"""One arena task on a worker: scenes ``first_run ..`` of one family, planned by one planner.

Each row holds the scene itself (its TOML text and SHA-256) beside the run's metrics, so any
scene can be re-run alone with ``mawdo plan FILE`` and the report never regenerates scenes. A
scene the generator rejects (no valid draw in ``MAX_ATTEMPTS``) is stored with
``status = "rejected"`` and the generator's reasons: it is not a planner failure and counts in
no rate. A failed or colliding run also keeps its trace (``result_to_bytes``) for the gallery.
"""

from __future__ import annotations

import hashlib
import time
import tomllib
import traceback
from dataclasses import dataclass
from typing import Any

import numpy as np

from mawdo.experiments.arena.plan import BASELINE_SEES_TIME, ORACLE
from mawdo.experiments.rows import RunRow, column


@dataclass(frozen=True)
class ArenaRow(RunRow):
    """One planner on one generated scene (units: pixels, radians, seconds, milliseconds).

    ``status`` is ``"ok"`` (planned; the metrics are set) or ``"rejected"`` (the generator found
    no valid scene; ``reason`` says why; metrics are None). ``success`` is the planner's verdict
    (goal reached and checker-approved), ``collision_free`` the independent checker's verdict on
    the executed route against every obstacle, moving ones included. ``gap`` = executed length /
    ``l_star`` (NaN when the goal is not reached). Latencies are replans after the first plan
    (None for single-shot planners); ``first_plan_s`` is the first plan's (or the single
    shot's) wall time; ``nfev`` the cost evaluations (OMPL: validity checks).
    """

    status: str | None = column("text")
    reason: str | None = column("text")
    scene_name: str | None = column("text")
    scene_toml: str | None = column("text")
    scene_hash: str | None = column("text")
    l_star: float | None = column("real")
    planner_seed: int | None = column("int")
    sees_time: str | None = column("text")
    success: int | None = column("int")
    collision_free: int | None = column("int")
    length: float | None = column("real")
    gap: float | None = column("real")
    clearance: float | None = column("real")
    turning: float | None = column("real")
    waits: int | None = column("int")
    evasions: int | None = column("int")
    latency_p50_ms: float | None = column("real")
    latency_p95_ms: float | None = column("real")
    latency_p99_ms: float | None = column("real")
    first_plan_s: float | None = column("real")
    nfev: int | None = column("int")
    trace: bytes | None = column("blob")


def scenario_from_toml(text: str, name: str):
    """A stored scene's TOML text as a :class:`~mawdo.planning.scenario.Scenario`."""
    from mawdo.planning.scenario import scenario_from_dict

    return scenario_from_dict(tomllib.loads(text), source=name)


def scene_hash(toml_text: str) -> str:
    """SHA-256 (hex) of a scene's TOML text."""
    return hashlib.sha256(toml_text.encode("utf-8")).hexdigest()


def _percentiles(lat_s: np.ndarray) -> tuple[float | None, float | None, float | None]:
    if lat_s.size == 0:
        return None, None, None
    p = np.percentile(lat_s * 1e3, [50, 95, 99])
    return float(p[0]), float(p[1]), float(p[2])


def _from_plan_result(res, l_star: float) -> dict[str, Any]:
    """Metrics of a receding-horizon run (ours or the oracle follower).

    The verdict and the clearance are the result's own: every run ends by judging its route with
    the independent checker (``mawdo.planning.config._Drive.result``), so checking it again
    here would only repeat that work (8-14 % of a run).
    """
    from mawdo.planning.path import polyline_length, turning_angles

    route = res.route if res.route is not None else res.trajectory
    length = polyline_length(route)
    p50, p95, p99 = _percentiles(res.latencies)
    return {
        "success": int(bool(res.success)),
        "collision_free": int(bool(res.collision_free)),
        "reason": res.reason,
        "length": float(length),
        "gap": float(length / l_star) if res.success else float("nan"),
        "clearance": float(res.min_clearance),
        "turning": float(turning_angles(route).sum()),
        "waits": int(res.waits),
        "evasions": int(res.evasions),
        "latency_p50_ms": p50,
        "latency_p95_ms": p95,
        "latency_p99_ms": p99,
        "first_plan_s": float(res.replans[0].latency) if res.replans else None,
        "nfev": int(res.nfev),
    }


def baseline_trace(scenario, result):
    """A single-shot baseline's route as a :class:`PlanResult` (for the gallery's renderer)."""
    from mawdo.planning.baselines import route_times
    from mawdo.planning.config import PlannerConfig, PlanResult, Replan

    route = result.route if result.route is not None else scenario.start[None, :]
    times = route_times(route, scenario.robot_speed) if len(route) > 1 else np.zeros(1)
    steps = np.arange(0.0, np.floor(times[-1]) + 1.0)
    traj = np.column_stack([np.interp(steps, times, route[:, i]) for i in (0, 1)])
    rep = Replan(
        step=0,
        position=scenario.start.copy(),
        waypoints=route[1:-1],
        cost=float("nan"),
        length=float(result.length),
        collisions=0,
        latency=float(result.time),
        nfev=int(result.validity_checks),
        history=np.zeros(0),
    )
    return PlanResult(
        scenario=scenario,
        algorithm=result.planner,
        seed=0,
        config=PlannerConfig(),
        trajectory=traj,
        success=bool(result.success),
        reason=result.reason,
        replans=[rep],
        route=route,
        route_times=times,
        collision_free=bool(result.collision_free),
        min_clearance=float(result.min_clearance),
    )


def _from_baseline(scenario, result, l_star: float) -> dict[str, Any]:
    from mawdo.planning.path import turning_angles

    route = result.route
    return {
        "success": int(bool(result.success)),
        "collision_free": int(bool(result.collision_free)) if result.solved else None,
        "reason": result.reason,
        "length": float(result.length) if result.solved else None,
        "gap": float(result.length / l_star) if result.success else float("nan"),
        "clearance": float(result.min_clearance) if result.solved else None,
        "turning": float(turning_angles(route).sum()) if route is not None else None,
        "waits": None,
        "evasions": None,
        "latency_p50_ms": None,
        "latency_p95_ms": None,
        "latency_p99_ms": None,
        "first_plan_s": float(result.time),
        "nfev": int(result.validity_checks),
    }


def _plan_one(spec: dict[str, Any], scene, seed: int) -> tuple[dict[str, Any], bytes | None]:
    """Run the task's planner on ``scene``; returns its metrics and, if failed, its trace."""
    from mawdo.planning.planner import follow_oracle, plan, result_to_bytes, step_limit

    name, sc = spec["algorithm"], scene.scenario
    if name == ORACLE:
        # the step limit our planner gets (planning.execute): follow_oracle's own default
        # (4 straight lines) cuts long detours such as mazes short
        steps, _ = step_limit(
            spec["overrides"].get("max_steps"),
            sc.straight_line_length(),
            scene.l_star,
            sc.robot_speed,
        )
        res = follow_oracle(sc, max_steps=steps)
        m = _from_plan_result(res, scene.l_star)
    elif spec["is_baseline"]:
        from mawdo.planning.baselines import run_baseline

        opts = spec["ompl"] if name != "straight" else {}
        base = run_baseline(name, sc, **opts)
        m = _from_baseline(sc, base, scene.l_star)
        res = baseline_trace(sc, base) if not (m["success"] and m["collision_free"]) else None
    else:
        res = plan(sc, algorithm=name, seed=seed, config=spec["preset"], **spec["overrides"])
        m = _from_plan_result(res, scene.l_star)
    bad = not (m["success"] and m["collision_free"])
    return m, (result_to_bytes(res) if bad and res is not None else None)


def execute_arena_task(spec: dict[str, Any]) -> list[ArenaRow]:
    """Generate and plan scenes ``first_run .. first_run + n_runs - 1`` of one family.

    A run that raises becomes a row with its error text; a rejected scene a row with
    ``status="rejected"``.
    """
    from mawdo.planning.scenes import SceneRejected, generate_scene

    fam, rows = spec["problem"], []
    sees = BASELINE_SEES_TIME.get(spec["algorithm"], "yes (predicted motion)")
    for i, seed in enumerate(spec["planner_seeds"]):
        k = spec["first_run"] + i
        t1 = time.perf_counter()
        common = {"run": k, "planner_seed": seed, "sees_time": sees}
        try:
            scene = generate_scene(fam, k, seed=spec["seed"], params=spec["params"])
        except SceneRejected as exc:
            rows.append(ArenaRow(**common, wall_time=0.0, status="rejected", reason=str(exc)))
            continue
        toml = scene.to_toml()
        common |= {
            "scene_name": scene.name,
            "scene_toml": toml,
            "scene_hash": scene_hash(toml),
            "l_star": float(scene.l_star),
        }
        t1 = time.perf_counter()  # generation is not the planner's time
        try:
            m, trace = _plan_one(spec, scene, seed)
        except Exception as exc:  # noqa: BLE001 - a failing run is a row, not a dead study
            err = "".join(traceback.format_exception_only(exc)).strip()
            rows.append(ArenaRow(**common, wall_time=time.perf_counter() - t1, error_text=err))
            continue
        rows.append(
            ArenaRow(**common, **m, wall_time=time.perf_counter() - t1, status="ok", trace=trace)
        )
    return rows
