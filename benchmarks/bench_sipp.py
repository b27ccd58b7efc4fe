"""The safe-interval guide (issue 27, item 1): build + query time on a 366 x 366 map with 30
static polygons and 10 movers (5 constant-velocity circles, 3 patrolling circles, 2 random
walkers seen as reachable sets). Target: median build + query <= 10 ms (one core), where the
build is what a (re)plan redoes (start, movers, safe intervals) and the map's roadmap, built
once per map, is timed apart.

Also (issue 27, item 4) the earliest arrival T* of the timed scene families: per family, scene
generation with T* (median ms), draws per valid scene, and T* against the static optimum's time
(T* / (L*/v): how much time decides) -- measurements, no target.
``python -m benchmarks sipp``.
"""

from __future__ import annotations

import time

import numpy as np


def _flag(ok: bool) -> str:
    return "ok" if ok else "MISSED"


def _polygon(rng) -> list:
    import shapely

    c = rng.uniform(40, 326, 2)
    ang = np.sort(rng.uniform(0, 2 * np.pi, int(rng.integers(3, 7))))
    rad = rng.uniform(6, 22, len(ang))
    p = shapely.Polygon(c + np.c_[rad * np.cos(ang), rad * np.sin(ang)])
    p = p if p.is_valid and p.area > 1.0 else p.convex_hull
    return np.asarray(p.exterior.coords)[:-1].round(3).tolist()


def _mover(rng, j: int) -> dict:
    c = rng.uniform(40, 326, 2).round(3).tolist()
    if j < 5:
        motion = {"velocity": rng.uniform(-2, 2, 2).round(3).tolist()}
    elif j < 8:
        way = rng.uniform(-30, 30, (2, 2)).round(3).tolist()
        motion = {"model": "patrol", "waypoints": way, "speed": 1.5}
    else:
        motion = {"model": "bounded_random_walk", "step": 1.0, "hold": 5}
    return {"shape": "circle", "center": c, "radius": float(rng.uniform(5, 9)), "motion": motion}


def scene(seed: int):
    """A valid scenario: 30 polygons and 10 movers, start and goal in opposite corners."""
    from mawdo.planning import ScenarioError, scenario_from_dict

    rng = np.random.default_rng(seed)
    while True:
        obstacles = [{"shape": "polygon", "vertices": _polygon(rng)} for _ in range(30)]
        obstacles += [_mover(rng, j) for j in range(10)]
        spec = {
            "schema_version": 1,
            "seed": seed,
            "start": [10.0, 10.0],
            "goal": [356.0, 356.0],
            "obstacles": obstacles,
        }
        try:
            return scenario_from_dict(spec)
        except ScenarioError:
            continue


def guide_build_query(
    scenes: int = 20, k: int = 1, walkers: str = "reachable", repeats: int = 3
) -> None:
    """Per scene: the roadmap (once per map: inflation, visibility graph, static distances),
    then one query at t0 = 0: start joined, movers sliced, safe intervals (the build) and the
    search for ``k`` routes (the query); per scene the best of ``repeats`` runs."""
    from mawdo.planning.guide.sipp import SafeIntervalGuide
    from mawdo.planning.guide.sipp.roadmap import Roadmap

    SafeIntervalGuide(scene(999), walkers=walkers).routes(k=k)  # compile
    maps, build, query, found, waits, nodes = [], [], [], 0, 0, []
    for s in range(scenes):
        sc = scene(s)
        t = time.perf_counter()
        Roadmap.of(sc)
        t1 = time.perf_counter()
        maps.append(t1 - t)
        best = (np.inf, np.inf)
        for _ in range(repeats):  # best of a few: the machine is shared
            t1 = time.perf_counter()
            guide = SafeIntervalGuide(sc, walkers=walkers)
            t2 = time.perf_counter()
            routes = guide.routes(k=k)
            t3 = time.perf_counter()
            best = min(best, (t2 - t1 + t3 - t2, t2 - t1), key=lambda b: b[0])
        build.append(best[1])
        query.append(best[0] - best[1])
        found += bool(routes)
        waits += bool(routes) and routes[0].waiting > 0
        nodes.append(len(guide.nodes))
    total = 1e3 * (np.array(build) + np.array(query))
    med = np.median(total)
    print(
        f"safe-interval guide, 366 x 366, 30 polygons + 10 movers (walkers {walkers}), "
        f"{scenes} scenes, k = {k}, ~{int(np.median(nodes))} vertices, best of {repeats}:\n"
        f"  per query: build {1e3 * np.median(build):.1f} ms + search "
        f"{1e3 * np.median(query):.1f} ms; build + query median {med:.1f} ms, max "
        f"{total.max():.1f} ms (<= 10 {_flag(med <= 10)}); routes found {found}/{scenes}, "
        f"with waits {waits}\n"
        f"  per map (once, cached): roadmap median {1e3 * np.median(maps):.1f} ms; a first "
        f"query with it: median {np.median(total + 1e3 * np.array(maps)):.1f} ms"
    )


def time_optimum(n: int = 50, seed: int = 0) -> None:
    """Per timed family: ``n`` scenes generated with their T* (time, draws, T* / (L*/v))."""
    from mawdo.planning.guide.sipp.optimum import scenario_time_optimum
    from mawdo.planning.scenes import TIMED_FAMILIES, generate_scene

    print(f"timed families: {n} scenes each (seed {seed}), generation with T* per scene")
    for fam in TIMED_FAMILIES:
        generate_scene(fam, 0, seed=seed + 1)  # compile, warm caches
        gen, t_opt, ratio, draws, waits = [], [], [], [], 0
        for i in range(n):
            t = time.perf_counter()
            sc = generate_scene(fam, i, seed=seed)
            gen.append(time.perf_counter() - t)
            t = time.perf_counter()
            scenario_time_optimum(sc.scenario, spots=sc.spots)  # T* alone (roadmap cached)
            t_opt.append(time.perf_counter() - t)
            ratio.append(sc.t_star / (sc.l_star / sc.scenario.robot_speed))
            draws.append(sc.attempts)
            waits += sc.time_route.waiting > 0.5
        r = np.array(ratio)
        print(
            f"  {fam:9s} generation median {1e3 * np.median(gen):6.1f} ms (T* query alone "
            f"{1e3 * np.median(t_opt):5.1f} ms), draws/scene {np.mean(draws):.2f}; "
            f"T*/(L*/v) median {np.median(r):.3f}, p95 {np.percentile(r, 95):.3f}, "
            f"max {r.max():.3f}; {int(np.sum(r > 1.01))}/{n} over 1.01, waits in {waits}/{n}"
        )


def main() -> None:
    time_optimum()
    guide_build_query(k=1)
    guide_build_query(k=3)
    guide_build_query(k=1, walkers="known")


if __name__ == "__main__":
    main()
