"""Per-run metrics of a planning run (docs/deviations.md#d-gap, paper Table 6 plus what it lacks).

Computed from the executed route, the scenario, the exact oracle and the independent checker;
nothing here trusts the cost kernel that produced the plans.
"""

from __future__ import annotations

import numpy as np

from mawdo.planning.check import check_trajectory
from mawdo.planning.oracle import scenario_optimum
from mawdo.planning.path import polyline_length, turning_angles
from mawdo.planning.planner import PlanResult

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


def run_metrics(result: PlanResult, l_star: float | None = None, snapshots: int = 8) -> dict:
    """Every metric of one run, as a flat dict of numbers (see ``METRICS``).

    Parameters
    ----------
    result : PlanResult
    l_star : float, optional
        Precomputed static optimum (pixels), to save the oracle call across runs.
    snapshots : int
        How many replans get the per-snapshot optimality ratio (each needs an oracle call).
    """
    sc = result.scenario
    l_star = static_optimum(sc) if l_star is None else l_star
    route = result.route if result.route is not None else result.trajectory
    times = result.route_times if result.route_times is not None else None
    check = check_trajectory(route, sc, times=times)
    turns = turning_angles(route)
    length = polyline_length(route)
    lat = result.latencies * 1e3
    snap = snapshot_gaps(result, snapshots) if snapshots else np.zeros(0)
    return {
        "success": bool(result.success),
        "reason": result.reason,
        "collision_free": bool(check.ok),
        "length_px": length,
        "gap": length / l_star if result.success else float("nan"),
        "smoothness_rad": float(turns.sum()),
        "max_turn_rad": float(turns.max()) if turns.size else 0.0,
        "collisions": check.hits,  # the map's border included
        "min_clearance_px": float(check.min_clearance),
        "snapshot_gap_median": float(np.median(snap)) if snap.size else float("nan"),
        "snapshot_gap_max": float(np.max(snap)) if snap.size else float("nan"),
        "latency_p50_ms": float(np.median(lat)) if lat.size else float("nan"),
        "latency_p95_ms": float(np.percentile(lat, 95)) if lat.size else float("nan"),
        "latency_max_ms": float(np.max(lat)) if lat.size else float("nan"),
        "first_plan_s": float(result.replans[0].latency) if result.replans else float("nan"),
        "nfev": result.nfev,
        "steps": result.steps,
        "l_star_px": l_star,
        # the guard's record (issue 10): 0 for runs stored before it existed
        "waits": int(getattr(result, "waits", 0)),
        "evasions": int(getattr(result, "evasions", 0)),
        "elite_fallbacks": int(getattr(result, "fallbacks", 0)),
        "near_misses": int(getattr(result, "near_misses", 0)),
        # steps on a kept plan, without a replan (PlannerConfig.hold_straight, hold_gap)
        "holds": int(getattr(result, "holds", 0)),
    }
