"""One arena task on a worker: scenes ``first_run ..`` of one family, planned by one planner.

Each row holds the scene itself (its TOML text and SHA-256) beside the run's metrics, so any
scene can be re-run alone with ``mawdo plan FILE`` and the report never regenerates scenes. A
scene the generator rejects (no valid draw in ``MAX_ATTEMPTS``) is stored with
``status = "rejected"`` and the generator's reasons: it is not a planner failure and counts in
no rate. A failed or colliding run also keeps its trace (``result_to_bytes``) for the gallery.
Every planner is run through :data:`mawdo.planning.run.planners.PLANNERS` and measured by
:func:`mawdo.planning.judge.metrics.run_metrics`.
"""

from __future__ import annotations

import hashlib
import time
import tomllib
import traceback
from dataclasses import dataclass
from typing import Any

import numpy as np

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

    Timed scene families also store ``t_star``, the scene's earliest arrival (time
    steps), ``time_gap`` = arrival step / ``t_star`` (NaN unless the run succeeded), and the
    checker's ``active_collisions`` (the robot moving) and ``passive_collisions`` (the robot at
    rest, hit by an obstacle); ``inevitable`` counts the steps at which no option kept a safe
    continuation; ``robot_caused`` the collisions the robot's own motion produced, for runs
    stepped in a world (observed knowledge; None for the others:
    :func:`~mawdo.planning.judge.fault.blame`). ``replans`` counts the run's (re)plans, the
    first included, and ``gated`` those the guide gate took without a search
    (:mod:`~mawdo.planning.run.gate`): an optimizer-driven planner searched ``replans -
    gated`` times. Stores made before these columns existed read them as None.
    """

    status: str | None = column("text", required=True)
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
    t_star: float | None = column("real")
    time_gap: float | None = column("real")
    active_collisions: int | None = column("int")
    passive_collisions: int | None = column("int")
    inevitable: int | None = column("int")
    robot_caused: int | None = column("int")
    replans: int | None = column("int")
    gated: int | None = column("int")


#: Row fields a caller that needs no trace or scene text leaves unread (large blobs).
NO_TRACE = ("trace", "scene_toml")


def is_timed(rows) -> bool:
    """A family is timed when every planned scene of it carries an earliest arrival ``t_star``."""
    ok = [r for r in rows if r.status == "ok"]
    return bool(ok) and all(r.t_star is not None for r in ok)


def scenario_from_toml(text: str, name: str):
    """A stored scene's TOML text as a :class:`~mawdo.planning.world.scenario.Scenario`."""
    from mawdo.planning.world.scenario import scenario_from_dict

    return scenario_from_dict(tomllib.loads(text), source=name)


def scene_hash(toml_text: str) -> str:
    """SHA-256 (hex) of a scene's TOML text."""
    return hashlib.sha256(toml_text.encode("utf-8")).hexdigest()


#: Arena column -> :func:`~mawdo.planning.judge.metrics.run_metrics` name (the columns keep the
#: names stored since the arena's first schema, so old stores stay readable).
COLUMNS = {
    "success": "success",
    "collision_free": "collision_free",
    "reason": "reason",
    "length": "length_px",
    "gap": "gap",
    "clearance": "min_clearance_px",
    "turning": "smoothness_rad",
    "waits": "waits",
    "evasions": "evasions",
    "latency_p50_ms": "latency_p50_ms",
    "latency_p95_ms": "latency_p95_ms",
    "latency_p99_ms": "latency_p99_ms",
    "first_plan_s": "first_plan_s",
    "nfev": "nfev",
    "inevitable": "inevitable",
}
#: The columns of a timed scene (one with an earliest arrival ``t_star``).
TIME_COLUMNS = ("t_star", "time_gap", "active_collisions", "passive_collisions")
# not measured: stored as None (NULL), not NaN (the gap of a failed run stays NaN)
_NONE_IF_NAN = ("latency_p50_ms", "latency_p95_ms", "latency_p99_ms", "first_plan_s")


def row_metrics(res, l_star: float, t_star: float | None = None) -> dict[str, Any]:
    """The arena columns of a run of any planner, from
    :func:`~mawdo.planning.judge.metrics.run_metrics` (no snapshot ratios, the scene's ``l_star``
    and, for a timed scene, its ``t_star``)."""
    from mawdo.planning.judge.metrics import run_metrics

    m = run_metrics(res, l_star=l_star, snapshots=0, t_star=t_star)
    out = {col: m[name] for col, name in COLUMNS.items()}
    out |= {col: m[col] for col in TIME_COLUMNS if col in m}
    for col in ("success", "collision_free"):
        out[col] = None if out[col] is None else int(out[col])
    for col in _NONE_IF_NAN:
        out[col] = None if np.isnan(out[col]) else out[col]
    out["robot_caused"] = getattr(res, "robot_caused", None)
    out["replans"], out["gated"] = len(res.replans), int(res.gated)
    return out


def plan_scene(name: str, sc, l_star: float, seed: int, preset: str, overrides: dict,
               options: dict | None = None, t_star: float | None = None):  # fmt: skip
    """Run the planner ``name`` (:data:`~mawdo.planning.run.planners.PLANNERS`) on ``sc`` with the
    preset and its overrides, passing it those of ``options`` it takes; returns the
    :class:`~mawdo.planning.run.result.PlanResult` and its arena columns (:func:`row_metrics`;
    ``t_star`` for a timed scene)."""
    from mawdo.planning.run.config import resolve_config
    from mawdo.planning.run.planners import PLANNERS

    planner = PLANNERS[name]
    opts = {k: v for k, v in (options or {}).items() if k in planner.options}
    res = planner.run(sc, seed, resolve_config(preset, overrides), **opts)
    return res, row_metrics(res, l_star, t_star)


def _plan_one(spec: dict[str, Any], scene, seed: int) -> tuple[dict[str, Any], bytes | None]:
    """The metrics of the task's planner on ``scene`` and, if it failed, its trace."""
    from mawdo.planning.run.result import result_to_bytes

    res, m = plan_scene(spec["algorithm"], scene.scenario, scene.l_star, seed, spec["preset"],
                        spec["overrides"], spec["planner_options"], scene.t_star)  # fmt: skip
    bad = not (m["success"] and m["collision_free"])
    return m, (result_to_bytes(res) if bad else None)


def execute_arena_task(spec: dict[str, Any]) -> list[ArenaRow]:
    """Generate and plan scenes ``first_run .. first_run + n_runs - 1`` of one family.

    A run that raises becomes a row with its error text; a rejected scene a row with
    ``status="rejected"``.
    """
    from mawdo.planning.scenes import SceneRejected, generate_scene

    fam, rows = spec["problem"], []
    from mawdo.planning.run.planners import PLANNERS

    sees = PLANNERS[spec["algorithm"]].sees_time
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
