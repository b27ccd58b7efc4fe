"""Per-run metrics of a planning run, for every planner (docs/deviations.md#d-gap, paper
Table 6 plus what it lacks).

:func:`run_metrics` is the one measure of a :class:`~mawdo.planning.run.result.PlanResult`, whatever
planner made it; the names carry their units. The checker's verdict (``collision_free``,
``collisions``, ``min_clearance_px``) is the result's own: every planner judges its route with
the independent checker when the run ends, so it is not checked a second time here. Only the
optimality references call the exact oracle; nothing here trusts the cost kernel that produced
the plans.
"""

from __future__ import annotations

import traceback

import numpy as np

from mawdo.planning.guide.oracle import scenario_optimum
from mawdo.planning.run.result import PlanResult
from mawdo.planning.world.path import polyline_length, turning_angles

__all__ = [
    "METRICS",
    "in_units",
    "run_metrics",
    "run_metrics_kept",
    "snapshot_gaps",
    "static_optimum",
]

# Column order of the study table; units in the names.
METRICS = (
    "success",
    "collision_free",
    "length_px",
    "gap",
    "smoothness_rad",
    "max_turn_rad",
    "collisions",
    "min_clearance_px",
    "snapshot_gap_median",
    "snapshot_gap_max",
    "latency_p50_ms",
    "latency_p95_ms",
    "latency_max_ms",
    "first_plan_s",
    "nfev",
    "steps",
    "waits",
    "evasions",
    "elite_fallbacks",
    "near_misses",
    "holds",
    "inevitable",
    "kinematic_violations",
)


def static_optimum(scenario) -> float:
    """``L*``: shortest collision-free length around the static obstacles (a lower bound)."""
    return scenario_optimum(scenario, static_only=True).length


def snapshot_gaps(result: PlanResult, count: int = 8) -> np.ndarray:
    """``L_plan(t) / L*(t)`` at ``count`` replans spread over the run (the paper's reading).

    ``L*(t)`` is the exact optimum from the robot's position with every obstacle frozen at ``t``;
    snapshots where the frozen map leaves no path (a moving obstacle on the robot) are skipped.
    """
    reps = result.replans
    idx = np.unique(np.linspace(0, len(reps) - 1, min(count, len(reps))).round().astype(int))
    out = []
    for i in idx:
        rp = reps[i]
        opt = scenario_optimum(
            result.scenario, t=float(rp.step), static_only=False, start=rp.position
        )
        if np.isfinite(opt.length) and opt.length > 0:
            out.append(rp.length / opt.length)
    return np.array(out)


def _stat(values: np.ndarray, fn) -> float:
    return float(fn(values)) if values.size else float("nan")


def run_metrics(
    result: PlanResult, l_star: float | None = None, snapshots: int = 8, t_star: float | None = None
) -> dict:
    """Every metric of one run of any planner, as a flat dict (see :data:`METRICS`).

    Parameters
    ----------
    result : PlanResult
    l_star : float, optional
        Precomputed static optimum (pixels), to save the oracle call across runs.
    snapshots : int
        How many replans get the per-snapshot optimality ratio (each needs an oracle call);
        0: none (``snapshot_gap_*`` are NaN).
    t_star : float, optional
        The scene's earliest arrival ``T*`` (time steps, > 0;
        :func:`~mawdo.planning.guide.sipp.optimum.scenario_time_optimum`). Given, the dict also has
        ``t_star`` and ``time_gap`` = ``steps / t_star`` (NaN unless the run succeeded), and,
        for a run with a route, ``active_collisions`` and ``passive_collisions``: the checker's
        collisions split by whether the robot moved (:mod:`mawdo.planning.judge.check`).

    Returns
    -------
    dict
        Pixels (``*_px``, ``length_px``), radians (``*_rad``), milliseconds (``*_ms``) and
        seconds (``first_plan_s``); ``gap`` = ``length_px / l_star_px`` (NaN unless the run
        succeeded); latencies are the replans after the first plan (NaN without any). A
        single-shot planner that found no route has None for the route's metrics and its
        checker verdict; one without a guard (``result.guarded`` False) has None for the
        guard's counts.
    """
    if t_star is not None and not (np.isfinite(t_star) and t_star > 0):
        raise ValueError(f"t_star must be a finite number of time steps > 0, got {t_star!r}")
    l_star = static_optimum(result.scenario) if l_star is None else l_star
    route = result.route if result.route is not None else result.trajectory
    turns = turning_angles(route)
    length = polyline_length(route)
    lat = result.latencies * 1e3
    snap = snapshot_gaps(result, snapshots) if snapshots else np.zeros(0)
    solved = result.solved
    p50, p95, p99 = np.percentile(lat, [50, 95, 99]) if lat.size else (float("nan"),) * 3
    out = {
        "success": bool(result.success),
        "reason": result.reason,
        "collision_free": bool(result.collision_free) if solved else None,
        "length_px": length if solved else None,
        "gap": length / l_star if result.success else float("nan"),
        "smoothness_rad": float(turns.sum()) if solved else None,
        "max_turn_rad": (float(turns.max()) if turns.size else 0.0) if solved else None,
        "collisions": int(result.hits) if solved else None,  # the map's border included
        "min_clearance_px": float(result.min_clearance) if solved else None,
        "snapshot_gap_median": _stat(snap, np.median),
        "snapshot_gap_max": _stat(snap, np.max),
        "latency_p50_ms": float(p50),
        "latency_p95_ms": float(p95),
        "latency_p99_ms": float(p99),
        "latency_max_ms": _stat(lat, np.max),
        "first_plan_s": float(result.replans[0].latency) if result.replans else float("nan"),
        "nfev": result.nfev,
        "steps": result.steps,
        "l_star_px": l_star,
    }
    # the guard's record, and replans kept without a search (hold_straight, hold_gap)
    counts = {"waits": result.waits, "evasions": result.evasions,
              "elite_fallbacks": result.fallbacks, "near_misses": result.near_misses,
              "holds": result.holds, "inevitable": result.inevitable,
              "kinematic_violations": result.kinematic_violations}  # fmt: skip
    out |= {k: int(v) if result.guarded else None for k, v in counts.items()}
    if t_star is not None:
        out |= time_metrics(result, float(t_star))
    return out


def time_metrics(result: PlanResult, t_star: float) -> dict:
    """``t_star``, ``time_gap`` (``steps / t_star``, NaN unless the run succeeded) and the
    checker's ``active_collisions`` / ``passive_collisions`` (None without a route)."""
    from mawdo.planning.judge.check import check_trajectory

    out = {"t_star": t_star, "time_gap": result.steps / t_star if result.success else float("nan")}
    if not result.solved or result.route_times is None:
        return out | {"active_collisions": None, "passive_collisions": None}
    rep = check_trajectory(result.route, result.scenario, times=result.route_times)
    return out | {"active_collisions": len(rep.active), "passive_collisions": len(rep.passive)}


def run_metrics_kept(
    result: PlanResult, l_star: float | None = None, snapshots: int = 8
) -> tuple[dict | None, str | None]:
    """:func:`run_metrics` of a computed run that never throws the run away.

    Returns
    -------
    metrics : dict or None
        Every metric; when the oracle-based ones fail (a huge map, say), those that need no
        oracle, with the reason in ``metrics["metrics_error"]``; None when even those fail.
    error : str or None
        Why ``metrics`` is None.
    """
    errors = []
    if l_star is None:
        try:
            l_star = static_optimum(result.scenario)
        except Exception as exc:  # noqa: BLE001 - metrics without L* are still worth having
            l_star = float("nan")
            errors.append(f"static optimum: {one_line(exc)}")
    try:
        m = run_metrics(result, l_star=l_star, snapshots=snapshots)
    except Exception as exc:  # noqa: BLE001 - keep the run, lose only the failing metric
        errors.append(f"full metrics: {one_line(exc)}")
        try:
            m = run_metrics(result, l_star=l_star, snapshots=0)
        except Exception as exc2:  # noqa: BLE001
            errors.append(one_line(exc2))
            return None, "; ".join(errors)
    if errors:
        m["metrics_error"] = "; ".join(errors)
    return m, None


def in_units(metrics: dict, units) -> dict:
    """The metrics of :func:`run_metrics` as the scenario's user reads them.

    Parameters
    ----------
    metrics : dict
        Metrics in pixels and time steps (their keys as :func:`run_metrics` names them).
    units : Units
        The scenario's units (:attr:`Scenario.units <mawdo.planning.world.scenario.Scenario
        .units>`).

    Returns
    -------
    dict
        For pixel units a copy of ``metrics``. For metres and seconds, in the same order:
        each ``<name>_px`` as ``<name>_m`` (times the resolution), ``t_star`` (steps) as
        ``t_star_s``, and after ``steps`` (a count, kept) ``arrival_s``, the run's time in
        seconds when it reached the goal (None otherwise); None and NaN stay as they are.
        Latencies (``*_ms``, ``first_plan_s``) are wall-clock times, the same in any units.
    """
    if units.is_pixels:
        return dict(metrics)
    out: dict = {}
    for key, value in metrics.items():
        if key.endswith("_px"):
            out[key[:-3] + "_m"] = None if value is None else float(units.length(value))
        elif key == "t_star":
            out["t_star_s"] = None if value is None else float(units.time(value))
        else:
            out[key] = value
        if key == "steps":
            reached = metrics.get("success") and value is not None
            out["arrival_s"] = float(units.time(value)) if reached else None
    return out


def one_line(exc: BaseException) -> str:
    """An exception as one line, ``Type: message``."""
    return "".join(traceback.format_exception_only(exc)).strip()
