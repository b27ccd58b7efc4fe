"""The guided, guarded planner (issue 10): single-shot quality and time on map families, the
paper scenario in receding horizon, and the exact oracle's build + query time.

Targets: static single-shot on the maze / U-trap / rooms families (20 scenes each): 0 collisions,
median gap <= 1.01, p95 <= 1.05, median time <= 50 ms; paper scenario, dynamic, 10 seeds:
gap <= 1.02, replan p95 <= 20 ms, 0 collisions; oracle build + query on a 366 x 366 map with 30
polygons <= 20 ms; seconds per arena run by family (issue 14, CPU time). The map families are
the test suite's (``tests/planning/maps.py``); run from the repository root.
``python -m benchmarks planner``.
"""

from __future__ import annotations

import time

import numpy as np


def _flag(ok: bool) -> str:
    return "ok" if ok else "MISSED"


def static_families(scenes: int = 20, algorithm: str = "mawdo", config: str = "fast") -> None:
    from tests.planning import maps

    from mawdo.planning.judge.metrics import static_optimum
    from mawdo.planning.run.execute import guide_for
    from mawdo.planning.run.planner import PRESETS, plan
    from mawdo.planning.world.path import polyline_length

    print(f"static single-shot, {algorithm}, preset {config!r}, {scenes} scenes per family")
    plan(maps.u_trap(999), algorithm, seed=0, dynamic=False, config=config)  # compile
    for name, family in maps.FAMILIES.items():
        gaps, times, totals, bad, fails = [], [], [], 0, 0
        for k in range(scenes):
            sc = family(1000 + k)
            l_star = static_optimum(sc)
            t = time.perf_counter()
            guide_for(sc, PRESETS[config].clearance, PRESETS[config].guide_routes)
            build = time.perf_counter() - t
            res = plan(sc, algorithm, seed=k, dynamic=False, config=config)
            totals.append(time.perf_counter() - t)
            # the query: guide build (once per map) + seeding and optimisation; the rest of
            # plan() drives the route step by step and runs the checker on it
            times.append(build + res.replans[0].latency)
            bad += not res.collision_free
            fails += not res.success
            if res.success:
                gaps.append(polyline_length(res.route) / l_star)
        g = np.array(gaps)
        med, p95, tm = np.median(g), np.percentile(g, 95), 1e3 * np.median(times)
        print(
            f"  {name:7s} collisions {bad} (target 0 {_flag(bad == 0)}), failures {fails}; "
            f"gap median {med:.4f} (<= 1.01 {_flag(med <= 1.01)}), "
            f"p95 {p95:.4f} (<= 1.05 {_flag(p95 <= 1.05)}); "
            f"query time median {tm:.1f} ms (<= 50 {_flag(tm <= 50)}); "
            f"plan() with driving and checking {1e3 * np.median(totals):.0f} ms"
        )


def paper_dynamic(seeds=range(10), algorithm: str = "mawdo") -> None:
    from mawdo.planning import get_scenario
    from mawdo.planning.judge.metrics import run_metrics, static_optimum
    from mawdo.planning.run.planner import follow_oracle, plan

    sc = get_scenario("paper")
    l_star = static_optimum(sc)
    gaps, lat, bad, fails, events, clear = [], [], 0, 0, np.zeros(4, int), []
    for seed in seeds:
        res = plan(sc, algorithm, seed=seed)
        m = run_metrics(res, l_star=l_star, snapshots=0)
        bad += not m["collision_free"]
        fails += not res.success
        gaps.append(m["gap"])
        clear.append(m["min_clearance_px"])
        lat.extend(res.latencies)
        events += [res.waits, res.evasions, res.fallbacks, res.near_misses]
    g = np.array(gaps)
    p95 = 1e3 * np.percentile(lat, 95)
    print(f"paper scenario, dynamic, {algorithm}, realtime preset, {len(g)} seeds")
    print(
        f"  collisions {bad} (target 0 {_flag(bad == 0)}), failures {fails}; "
        f"gap median {np.nanmedian(g):.4f} max {np.nanmax(g):.4f} "
        f"(<= 1.02 {_flag(np.nanmax(g) <= 1.02)}); "
        f"replan p95 {p95:.1f} ms (<= 20 {_flag(p95 <= 20)})"
    )
    print(
        f"  guard events over all seeds: waits {events[0]}, evasions {events[1]}, "
        f"elite fallbacks {events[2]}, near misses {events[3]}; least clearance "
        f"{min(clear):.2f} px (> 0 {_flag(min(clear) > 0)})"
    )
    # context for the gap target: the exact route on obstacles frozen each step, same scene
    oracle = run_metrics(follow_oracle(sc), l_star=l_star, snapshots=0)
    print(
        f"  beside it: oracle follower gap {oracle['gap']:.4f} (collision-free "
        f"{oracle['collision_free']}); {algorithm} is shorter on {int(np.sum(g < oracle['gap']))} "
        f"of {len(g)} seeds"
    )


def arena_runs(
    families=("forest", "maze", "dense", "crossing", "u_trap", "rooms"),
    algorithms=("mawdo", "oracle_follower"),
) -> None:
    """Seconds per arena run (scene 0 of each family, ``realtime`` preset) in *CPU* time of this
    process, which a machine shared with other jobs leaves far steadier than wall time (the
    planner is single-threaded); issue 14 budgets the arena by these per-run costs."""
    from dataclasses import replace

    from mawdo.planning import PLANNERS, PRESETS
    from mawdo.planning.scenes import generate_scene

    cfg = PRESETS["realtime"]
    print("arena runs, scene 0 per family, realtime preset, CPU seconds per run")
    for alg in algorithms:
        planner = PLANNERS[alg]
        if planner.optimizer is not None:  # compile outside the timing
            first = generate_scene(families[0], 0, seed=0).scenario
            planner.run(first, 0, replace(cfg, max_steps=2))
        row = []
        for fam in families:
            sc = generate_scene(fam, 0, seed=0).scenario
            t = time.process_time()
            res = planner.run(sc, 0, cfg)
            row.append(f"{fam} {time.process_time() - t:5.2f} s ({res.steps} steps)")
        print(f"  {alg:16s} " + ", ".join(row))


def oracle(polygons: int = 30, repeats: int = 20) -> None:
    import shapely

    from mawdo.planning.guide.oracle import shortest_path

    rng = np.random.default_rng(0)
    times = []
    for k in range(repeats + 1):
        obs = []
        for _ in range(polygons):
            c = rng.uniform(30, 336, 2)
            ang = np.sort(rng.uniform(0, 2 * np.pi, int(rng.integers(3, 7))))
            rad = rng.uniform(6, 22, len(ang))
            p = shapely.Polygon(c + np.c_[rad * np.cos(ang), rad * np.sin(ang)])
            # inflated by r = 4 with rounded corners (8 segments per quarter), as a planner sees
            obs.append((p if p.is_valid else p.convex_hull).buffer(4.0, quad_segs=8))
        t = time.perf_counter()
        shortest_path((5.0, 5.0), (361.0, 361.0), obs, (0, 0, 366, 366))
        if k:  # the first call compiles
            times.append(time.perf_counter() - t)
    med = 1e3 * np.median(times)
    verts = sum(len(o.exterior.coords) - 1 for o in obs)
    print(
        f"oracle build + query, 366 x 366, {polygons} inflated polygons (~{verts} vertices): "
        f"median {med:.1f} ms, max {1e3 * max(times):.1f} ms (<= 20 {_flag(med <= 20)})"
    )


def main() -> None:
    oracle()
    static_families()
    paper_dynamic()
    arena_runs()


if __name__ == "__main__":
    main()
