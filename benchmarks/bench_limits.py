"""Timed families under kinematic limits: does the limited run carry speed through corners?

``python -m benchmarks limits`` (or ``python benchmarks/bench_limits.py [--scenes N]
[--families a,b] [--workers W] [--refiners gwo,woa] [--save PATH] [--load PATH]``). For
each timed family, scenes ``0 .. N-1`` of seed 0 (``realtime`` preset, planner seed 0), with
``v`` the scene's robot speed (px per step):

* (a) the speed cap alone: ``max_speed = 0.75 v``;
* (b) the three limits: ``max_speed = 0.75 v``, ``max_accel = 0.25 v``, ``max_turn = 0.6`` rad;

each with ``mawdo`` and ``guide_only``. Per family and overall: success share, the median
arrival step of the successful runs, the paired ratios ``mawdo(b) / mawdo(a)`` (target
<= 1.05) and ``mawdo(b) / guide_only(b)`` (target <= 0.87) over the scenes both runs of a pair
solved (median), the kinematic violations of every run (the independent
:func:`~mawdo.planning.judge.kincheck.check_kinematics`, target 0) and its active collisions
(:func:`~mawdo.planning.judge.check.check_trajectory`, target 0). ``--save`` writes the rows as
JSON, ``--load`` prints a saved table (e.g. the code before a change) without running.

Beside them, ``T*(a)``: the scene's earliest arrival at the capped speed alone, the exact
optimum of the roadmap class (:func:`~mawdo.planning.guide.sipp.optimum.scenario_time_optimum`
with the scene's spots, robot speed ``0.75 v``), and the paired median ``T*(a) / guide_only(b)``.
Every trajectory within the three limits is within the speed cap, so no run under (b) arrives
before the optimum under (a); ``T*(a)`` is that optimum up to the roadmap's restriction (waits
only at vertices, full-speed moves between them), so the ratio is where ``mawdo(b) /
guide_only(b)`` could go at best.

``--refiners``: other registered optimizers run under (b) on the same scenes, each as the
limited run's refiner in MAWDO's place; a second table gives each one's success, median arrival
and paired ratios against ``guide_only(b)`` and ``mawdo(b)``: which optimizer refines the
limited drive best.
"""

from __future__ import annotations

import argparse
import json
from concurrent.futures import ProcessPoolExecutor
from dataclasses import replace

import numpy as np

FAMILIES = ("corridor", "doorway", "chaser", "crowd", "parked", "slalom")
PLANNERS = ("mawdo", "guide_only")
CASES = {"a": (0.75, None, None), "b": (0.75, 0.25, 0.6)}  # (speed, accel) x v; turn in rad
TARGETS = {"b/a": 1.05, "b/guide": 0.87}
OPTIMUM = "T*"  # the rows of the earliest arrival under (a)


def _optimum(family: str, index: int) -> dict:
    """``T*(a)``: the scene's earliest arrival with its robot's speed capped as in case (a)."""
    from mawdo.planning.guide.sipp.optimum import scenario_time_optimum
    from mawdo.planning.scenes import generate_scene
    from mawdo.planning.world.scenario import scenario_from_dict

    scene = generate_scene(family, index, seed=0)
    spec = scene.scenario.to_dict()
    spec["robot"]["speed"] = CASES["a"][0] * scene.scenario.robot_speed
    opt = scenario_time_optimum(scenario_from_dict(spec, source=spec["name"]), spots=scene.spots)
    return {
        "family": family, "index": index, "planner": OPTIMUM, "case": "a",
        "success": bool(opt.reachable), "steps": float(opt.t_star) if opt.reachable else None,
        "kin": 0, "active": 0,
    }  # fmt: skip


def _one(args):
    family, index, planner, case = args
    if planner == OPTIMUM:
        return _optimum(family, index)
    from mawdo.planning.judge.check import check_trajectory
    from mawdo.planning.judge.kincheck import check_kinematics
    from mawdo.planning.run.config import PRESETS
    from mawdo.planning.run.planners import run_planner
    from mawdo.planning.scenes import generate_scene

    scene = generate_scene(family, index, seed=0)
    v = scene.scenario.robot_speed
    s, a, turn = CASES[case]
    cfg = replace(
        PRESETS["realtime"], max_speed=s * v, max_accel=None if a is None else a * v, max_turn=turn
    )
    res = run_planner(planner, scene.scenario, seed=0, config=cfg)
    kin = check_kinematics(res.trajectory, cfg.max_speed, cfg.max_accel, cfg.max_turn)
    rep = check_trajectory(res.route, res.scenario, times=res.route_times)
    return {
        "family": family, "index": index, "planner": planner, "case": case,
        "success": bool(res.success), "steps": int(res.steps),
        "kin": int(kin.count), "active": len(rep.active),
    }  # fmt: skip


def run(families, scenes: int, workers: int, refiners=()) -> list[dict]:
    """Every (family, scene, planner, case) run's row; ``refiners`` under case (b) only."""
    jobs = [(f, i, p, c) for f in families for i in range(scenes) for p in PLANNERS for c in CASES]
    jobs += [(f, i, OPTIMUM, "a") for f in families for i in range(scenes)]
    jobs += [(f, i, p, "b") for f in families for i in range(scenes) for p in refiners]
    if workers <= 1:
        return [_one(j) for j in jobs]
    with ProcessPoolExecutor(workers) as pool:
        return list(pool.map(_one, jobs))


def _ratio(rows, num, den) -> list[float]:
    """Paired ratios of arrival steps (both runs successful) over the scenes."""
    by = {(r["family"], r["index"], r["planner"], r["case"]): r for r in rows}
    out = []
    for (f, i, p, c), r in by.items():
        if (p, c) != num:
            continue
        o = by.get((f, i, *den))
        if o is not None and r["success"] and o["success"]:
            out.append(r["steps"] / o["steps"])
    return out


def _ratio_text(ratios: list[float]) -> str:
    """The median of paired ratios, or a dash without pairs."""
    return f"{np.median(ratios):.3f}" if ratios else "    -"


def _runs_text(sel: list[dict]) -> tuple[str, str]:
    """``("solved/runs", median arrival step of the solved)`` of some runs."""
    ok = [r["steps"] for r in sel if r["success"]]
    med = f"{np.median(ok):6.1f}" if ok else "     -"
    return f"{len(ok)}/{len(sel)}", med


def _line(name: str, rows: list[dict]) -> str:
    cells = []
    for p in PLANNERS:
        for c in CASES:
            done, med = _runs_text([r for r in rows if r["planner"] == p and r["case"] == c])
            cells.append(f"{done} {med}")
    ba = _ratio_text(_ratio(rows, ("mawdo", "b"), ("mawdo", "a")))
    bg = _ratio_text(_ratio(rows, ("mawdo", "b"), ("guide_only", "b")))
    og = _ratio_text(_ratio(rows, (OPTIMUM, "a"), ("guide_only", "b")))
    kin = sum(r["kin"] for r in rows)
    act = sum(r["active"] for r in rows)
    return f"{name:9s} " + "  ".join(cells) + f"  {ba:>6s} {bg:>8s} {og:>8s} {kin:4d} {act:4d}"


def report(rows: list[dict]) -> None:
    """The table (per family, then overall), targets beside the figures."""
    head = "  ".join(f"{p[:6]}({c}) ok  T" for p in PLANNERS for c in CASES)
    print(f"{'family':9s} {head}   b/a   b/guide  T*(a)/g   kin  act")
    for f in dict.fromkeys(r["family"] for r in rows):
        print(_line(f, [r for r in rows if r["family"] == f]))
    print(_line("overall", rows))
    print(
        f"targets: mawdo(b)/mawdo(a) <= {TARGETS['b/a']}, mawdo(b)/guide_only(b) <= "
        f"{TARGETS['b/guide']}, kinematic violations 0, active collisions 0 (ratios: medians "
        "of paired arrival steps; T*(a)/g: the earliest arrival under the speed cap alone over "
        "guide_only(b), where b/guide could go at best)"
    )


def report_refiners(rows: list[dict]) -> None:
    """Each optimizer as the refiner under (b): success, median arrival, paired ratios."""
    names = [p for p in dict.fromkeys(r["planner"] for r in rows if r["case"] == "b")]
    names = [p for p in names if p not in ("guide_only", OPTIMUM)]
    if len(names) < 2:
        return
    print(f"\n{'refiner (b)':12s} {'ok':>7s} {'T':>6s} {'/guide':>7s} {'/mawdo':>7s}  kin  act")
    for p in names:
        sel = [r for r in rows if r["planner"] == p and r["case"] == "b"]
        done, med = _runs_text(sel)
        g = _ratio_text(_ratio(rows, (p, "b"), ("guide_only", "b")))
        m = _ratio_text(_ratio(rows, (p, "b"), ("mawdo", "b")))
        kin, act = sum(r["kin"] for r in sel), sum(r["active"] for r in sel)
        print(f"{p:12s} {done:>7s} {med} {g:>7s} {m:>7s} {kin:4d} {act:4d}")


def main(argv=None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--scenes", type=int, default=8)
    ap.add_argument("--families", default=",".join(FAMILIES))
    ap.add_argument("--workers", type=int, default=1)
    ap.add_argument("--refiners", default="", help="more optimizers under (b), e.g. gwo,woa")
    ap.add_argument("--save", default=None)
    ap.add_argument("--load", default=None)
    args = ap.parse_args([] if argv is None else argv)
    if args.load:
        with open(args.load) as fh:
            rows = json.load(fh)
    else:
        refiners = [r for r in args.refiners.split(",") if r]
        rows = run(args.families.split(","), args.scenes, args.workers, refiners)
    if args.save:
        with open(args.save, "w") as fh:
            json.dump(rows, fh, indent=1)
    report([r for r in rows if r["planner"] in (*PLANNERS, OPTIMUM)])
    report_refiners(rows)


if __name__ == "__main__":
    import sys

    main(sys.argv[1:])
