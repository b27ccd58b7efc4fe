"""Planning at scale: first-plan and replan time, peak memory and CPU per stage as the world grows.

Worlds are drawn by :func:`world` (seeded): constant-velocity discs (bouncing at the border),
static polygons sized to the map and their count, start and goal in opposite corners; a draw
whose static map cuts the start off from the goal (the exact oracle, :mod:`mawdo.planning.guide
.oracle`) or that the scenario validation refuses is drawn again. Per size one ``mawdo`` run of
``--steps`` steps under the planner preset ``--preset`` (default ``large``: the guide and the
cost trust the predictions 180 steps ahead; the reference world also under ``realtime``, which
looks as far as the guide's horizon): the first plan (from the call to the first step: roadmap,
guides, first optimisation) and the replans after it (p50, p95), CPU seconds
(``time.process_time``: the machine is shared), and the CPU per stage (:class:`StageClock`: each
stage's own time, the stages it calls taken out); then the same run again for the peak of traced
Python memory (:mod:`tracemalloc`; Numba's arrays are NumPy arrays and count). Traced apart:
tracemalloc records a traceback at every allocation, Numba's arrays inside the compiled kernels
included, which doubled the safe-interval search's CPU on the reference world.

``--only whole`` drives one run to its end among 10 000 movers on 4000 px (400 polygons) and
prints its CPU in all against the target (a whole run <= 10 min), the first plan, the steps and
the verdict.

Three sweeps, each from the reference world (1000 x 1000 px, 200 movers, 40 polygons): movers
10 -> 100 -> 1000, static polygons 10 -> 100 -> 1000, map 366 -> 1000 -> 2000 px (movers and
polygons scaled with the area), each with its log-log slope (the fitted exponent). Targets
(reference world, one core, quiet machine): first plan <= 1 s, replan p95 <= 50 ms.
By default two sizes per sweep (``make bench``); ``--size full`` (or
``MAWDO_BENCH_SCALE=full``) all three, ``--size big`` also 10 000 movers and a 4000 px map;
``--figure PATH`` (default ``out/bench/scaling.png``) draws the curves (the docs' figure:
``--size full --steps 3 --figure docs/img/scaling.png``).
``python -m benchmarks scaling`` or ``python benchmarks/bench_scaling.py [--size S] [--steps N]``.
"""

from __future__ import annotations

import argparse
import copy
import math
import os
import time
import tracemalloc

import numpy as np

#: the reference world of the targets
REF = {"size": 1000.0, "movers": 200, "polygons": 40}
TARGET_FIRST, TARGET_REPLAN = 1.0, 0.050
#: the world of the whole-run target (``--only whole``), and that target (CPU seconds)
BIG = {"size": 4000.0, "movers": 10_000, "polygons": 400}
TARGET_WHOLE = 600.0
STAGES = ("roadmap", "slice", "search", "kernel", "guard", "checker", "oracle")


def _flag(ok: bool) -> str:
    return "ok" if ok else "MISSED"


def _polygon(rng, size: float, radius: float) -> list:
    import shapely

    c = rng.uniform(0.06 * size, 0.94 * size, 2)
    ang = np.sort(rng.uniform(0, 2 * np.pi, int(rng.integers(3, 7))))
    rad = rng.uniform(0.3 * radius, radius, len(ang))
    p = shapely.Polygon(c + np.c_[rad * np.cos(ang), rad * np.sin(ang)])
    p = p if p.is_valid and p.area > 1.0 else p.convex_hull
    return np.asarray(p.exterior.coords)[:-1].round(3).tolist()


def world(size: float, movers: int, polygons: int, seed: int = 0, tries: int = 50):
    """A solvable scenario of ``size`` x ``size`` px with ``movers`` constant-velocity discs
    (radius 5-9 px, speed up to 2 px per step, bouncing) and ``polygons`` static polygons
    (radius up to a third of the mean spacing, at most 40 px); the robot (radius 4, speed 4)
    goes corner to corner. Redrawn (same stream) until valid and statically solvable."""
    from mawdo.planning import ScenarioError, scenario_from_dict
    from mawdo.planning.guide.oracle import scenario_optimum

    rng = np.random.default_rng([seed, int(size), movers, polygons])
    radius = min(40.0, size / (3.0 * math.sqrt(max(polygons, 1))))
    for _ in range(tries):
        obstacles = [
            {"shape": "polygon", "vertices": _polygon(rng, size, radius)} for _ in range(polygons)
        ]
        for _ in range(movers):
            c = rng.uniform(20.0, size - 20.0, 2).round(3).tolist()
            ang, speed = rng.uniform(0, 2 * np.pi), rng.uniform(0.3, 2.0)
            vel = [round(speed * math.cos(ang), 3), round(speed * math.sin(ang), 3)]
            obstacles.append({"shape": "circle", "center": c, "radius": float(rng.uniform(5, 9)),
                              "motion": {"velocity": vel}})  # fmt: skip
        spec = {"schema_version": 1, "seed": seed, "width": size, "height": size,
                "start": [12.0, 12.0], "goal": [size - 12.0, size - 12.0],
                "obstacles": obstacles}  # fmt: skip
        try:
            sc = scenario_from_dict(spec)
        except ScenarioError:
            continue
        if math.isfinite(scenario_optimum(sc).length):
            return sc
    raise RuntimeError(f"no solvable {size:g} px world with {movers} movers, {polygons} polygons")


class StageClock:
    """CPU seconds per planning stage, each stage's own: while a stage calls another (the
    guard calls the checker), the time goes to the inner one. Wraps the stages' entry points
    while the context is open; changes nothing they do."""

    def __init__(self) -> None:
        self.cpu = dict.fromkeys(STAGES, 0.0)
        self._stack: list[str] = []
        self._last = 0.0
        self._saved: list = []

    def _targets(self):
        from mawdo.planning.guide.sipp import guide, roadmap
        from mawdo.planning.judge import check
        from mawdo.planning.refine.kernel.threads import ThreadedKernel
        from mawdo.planning.safety import guard, ics

        yield "roadmap", roadmap.Roadmap, "__init__"
        # (the movers sliced for a query; each vertex's safe intervals are made inside the
        # search, when it first touches the vertex, and count there)
        yield "slice", roadmap.Roadmap, "movers"
        yield "search", guide.SafeIntervalGuide, "_search"
        yield "kernel", ThreadedKernel, "__call__"
        for name in ("stretch_hits", "step_clearance", "evasive_move"):
            yield "guard", guard.Guard, name
        for name in ("movers", "wait_safe", "path_safe", "find", "after_stretch"):
            yield "guard", ics.SafeContinuation, name
        yield "checker", check, "check_trajectory"
        yield "checker", guard, "check_trajectory"
        from mawdo.planning.guide import oracle

        yield "oracle", oracle, "scenario_optimum"

    def _switch(self, push: str | None) -> None:
        now = time.process_time()
        if self._stack:
            self.cpu[self._stack[-1]] += now - self._last
        self._last = now
        if push is None:
            self._stack.pop()
        else:
            self._stack.append(push)

    def _wrap(self, stage, fn):
        def timed(*args, **kwargs):
            self._switch(stage)
            try:
                return fn(*args, **kwargs)
            finally:
                self._switch(None)

        return timed

    def __enter__(self) -> StageClock:
        for stage, owner, name in self._targets():
            fn = owner.__dict__[name]
            self._saved.append((owner, name, fn))
            setattr(owner, name, self._wrap(stage, fn))
        return self

    def __exit__(self, *exc) -> None:
        for owner, name, fn in reversed(self._saved):
            setattr(owner, name, fn)
        self._saved.clear()


def _timed_plan(sc, steps, seed: int, preset: str, every: int = 0):
    """One ``mawdo`` run of at most ``steps`` steps (None: to its end) under ``preset``, timed:
    ``(result, marks, total, stages)``, ``marks`` the CPU time and replan count at each step's
    progress call, ``stages`` the CPU per stage (``other``: the rest). With ``every`` it prints
    a line every ``every`` steps."""
    from mawdo.planning.run.planner import plan

    marks = []

    def mark(step, _, replans):
        marks.append((time.process_time(), replans))
        if every and step and step % every == 0:
            print(f"  step {step}: {marks[-1][0] - t0:.0f} s of CPU", flush=True)

    t0 = time.process_time()
    with StageClock() as clock:
        res = plan(sc, "mawdo", seed=seed, config=preset, max_steps=steps, progress=mark)
    total = time.process_time() - t0
    stages = dict(clock.cpu) | {"other": total - sum(clock.cpu.values())}
    return res, [(m - t0, r) for m, r in marks], total, stages


def run_world(sc, steps: int, seed: int = 0, preset: str = "large") -> dict:
    """One ``mawdo`` run (planner preset ``preset``) of at most ``steps`` steps: first-plan and
    replan CPU (s), traced peak memory (MiB; from a second, untimed run), CPU per stage (s;
    ``other``: the rest of the run: the static guide, the waiting spots, the optimiser's
    Python), success of the steps driven."""
    from mawdo.planning.run.planner import plan

    res, marks, total, stages = _timed_plan(sc, steps, seed, preset)
    # the memory from a run of its own, untimed: the same run (same seed) of a copy of the world,
    # which finds nothing the first built in the caches kept per world (roadmap, guides)
    tracemalloc.start()
    plan(copy.deepcopy(sc), "mawdo", seed=seed, config=preset, max_steps=steps)
    peak = tracemalloc.get_traced_memory()[1] / 2**20
    tracemalloc.stop()
    first = marks[1][0] if len(marks) > 1 else total
    pairs = zip(marks[1:-1], marks[2:], strict=False)
    rep = np.array([b[0] - a[0] for a, b in pairs if b[1] > a[1]])
    return {"first": first, "replans": rep, "total": total, "peak_mib": peak,
            "stages": stages, "collision_free": res.collision_free,
            "steps": len(marks) - 1}  # fmt: skip


def whole_run(sc, seed: int = 0, preset: str = "large", every: int = 100) -> dict:
    """One ``mawdo`` run to its end (goal, give-up or the step cap) under ``preset``: CPU
    seconds in all (the first plan and the final check included) and per stage, the first plan,
    the steps, whether it reached the goal and the checker's verdict. Prints a line every
    ``every`` steps (a run among 10 000 movers takes minutes)."""
    res, marks, total, stages = _timed_plan(sc, None, seed, preset, every)
    return {"total": total, "first": marks[1][0] if len(marks) > 1 else total,
            "steps": res.steps, "success": res.success, "collision_free": res.collision_free,
            "stages": stages}  # fmt: skip


def _whole(preset: str) -> None:
    L, m, p = BIG["size"], BIG["movers"], BIG["polygons"]
    r = whole_run(world(L, m, p), preset=preset)
    st = " ".join(f"{k} {v:.1f}" for k, v in r["stages"].items())
    print(f"whole run, {L:g} px, {m} movers, {p} polygons, preset {preset} (CPU): "
          f"{r['total']:.1f} s (<= {TARGET_WHOLE:g} {_flag(r['total'] <= TARGET_WHOLE)}), "
          f"first plan {r['first']:.1f} s, {r['steps']} steps, success {r['success']}, "
          f"collision-free {r['collision_free']} | CPU s: {st}", flush=True)  # fmt: skip


def _fmt(r: dict) -> str:
    rep = r["replans"]
    p50, p95 = (1e3 * np.median(rep), 1e3 * np.percentile(rep, 95)) if rep.size else (np.nan,) * 2
    st = " ".join(f"{k} {v:.2f}" for k, v in r["stages"].items())
    free = r["collision_free"]
    return (f"first {r['first']:7.2f} s  replan p50 {p50:6.1f} ms p95 {p95:6.1f} ms  "
            f"peak {r['peak_mib']:6.0f} MiB  free {free!s:5s} | CPU s: {st}")  # fmt: skip


def slope(x, y) -> float:
    """Least-squares slope of ``log y`` on ``log x`` (the fitted exponent; NaN below two
    points)."""
    x, y = np.log(np.asarray(x, float)), np.log(np.asarray(y, float))
    return float(np.polyfit(x, y, 1)[0]) if len(x) >= 2 else math.nan


def sweeps(size: str) -> dict:
    """Per sweep (movers, polygons, map): its sizes and the worlds' parameters. ``size``:
    ``"quick"`` (two sizes each, what ``make bench`` runs), ``"full"`` (three) or ``"big"``
    (also 10 000 movers and a 4000 px map)."""
    s, m, p = REF["size"], REF["movers"], REF["polygons"]
    movers, polygons, maps = [10, 100], [10, 100], [366.0, 1000.0]
    if size in ("full", "big"):
        movers, polygons, maps = movers + [1000], polygons + [1000], maps + [2000.0]
    if size == "big":
        movers, maps = movers + [10_000], maps + [4000.0]
    area = lambda L: (L / s) ** 2  # noqa: E731
    return {
        "movers": [(k, (s, k, p)) for k in movers],
        "polygons": [(k, (s, m, k)) for k in polygons],
        "map px": [(L, (L, max(1, round(m * area(L))), max(1, round(p * area(L))))) for L in maps],
    }


def figure(results: dict, path: str, preset: str = "large") -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(1, len(results), figsize=(4.2 * len(results), 3.8))
    for ax, (name, rows) in zip(np.atleast_1d(axes), results.items(), strict=True):
        x = [k for k, _ in rows]
        ax.loglog(x, [r["first"] for _, r in rows], "o-", label="first plan")
        p95 = [np.percentile(r["replans"], 95) if r["replans"].size else np.nan for _, r in rows]
        ax.loglog(x, p95, "s-", label="replan p95")
        for st in ("roadmap", "slice", "search", "kernel", "guard", "checker"):
            y = [max(r["stages"][st], 1e-4) for _, r in rows]
            ax.loglog(x, y, ":", lw=1, label=f"{st} (run)")
        ax.axhline(TARGET_FIRST, color="k", lw=0.6, ls="--")
        ax.axhline(TARGET_REPLAN, color="grey", lw=0.6, ls="--")
        ax.set_xlabel(name)
        ax.set_ylabel("CPU seconds")
        ax.set_title(f"{name}: first plan ~ n^{slope(x, [r['first'] for _, r in rows]):.2f}")
    handles, labels = np.atleast_1d(axes)[0].get_legend_handles_labels()
    fig.legend(handles, labels, loc="lower center", ncol=len(labels), fontsize=7, frameon=False)
    fig.suptitle(f"mawdo at scale, preset {preset}, CPU seconds (stages: over the whole run; "
                 "targets dashed: first plan 1 s, replan p95 50 ms)", fontsize=9)  # fmt: skip
    fig.tight_layout(rect=(0, 0.07, 1, 1))
    os.makedirs(os.path.dirname(path) or ".", exist_ok=True)
    fig.savefig(path, dpi=110)
    plt.close(fig)


def main(argv=None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    env = os.environ.get("MAWDO_BENCH_SCALE", "quick")
    ap.add_argument("--size", choices=("quick", "full", "big"), default=env,
                    help="sizes per sweep (default $MAWDO_BENCH_SCALE or quick: two each; "
                         "full: three; big: also 10 000 movers and a 4000 px map)")  # fmt: skip
    ap.add_argument("--steps", type=int, default=4, help="steps driven per run")
    ap.add_argument("--figure", default="out/bench/scaling.png")
    ap.add_argument("--only", default="", choices=("", "ref", "whole"),
                    help="the reference world only ('ref'), or only one whole run among "
                         "10 000 movers on 4000 px ('whole', about 10 min)")  # fmt: skip
    ap.add_argument(
        "--sweep",
        default="",
        choices=("", "movers", "polygons", "map"),
        help="run this sweep only (without the reference world)",
    )
    ap.add_argument("--preset", default="large",
                    help="planner preset of the sweeps (default large; the reference world "
                         "is also run under realtime)")  # fmt: skip
    a = ap.parse_args([] if argv is None else argv)
    run_world(world(366.0, 5, 5, seed=99), steps=2)  # compile / load the kernels
    if a.only == "whole":
        _whole(a.preset)
        return
    sc = world(REF["size"], REF["movers"], REF["polygons"])
    for preset in dict.fromkeys(("realtime", a.preset) if not a.sweep else ()):
        # a fresh copy: the roadmap and guides are kept per world, and each run builds its own
        r = run_world(copy.deepcopy(sc), a.steps, preset=preset)
        p95 = np.percentile(r["replans"], 95) if r["replans"].size else np.nan
        print(f"reference {REF['size']:g} px, {REF['movers']} movers, {REF['polygons']} "
              f"polygons, preset {preset}, {a.steps} steps (CPU):\n  {_fmt(r)}\n  first plan "
              f"{r['first']:.2f} s (<= {TARGET_FIRST:g} {_flag(r['first'] <= TARGET_FIRST)}), "
              f"replan p95 {1e3 * p95:.1f} ms (<= {1e3 * TARGET_REPLAN:g} "
              f"{_flag(p95 <= TARGET_REPLAN)})", flush=True)  # fmt: skip
    if a.only == "ref":
        return
    results = {}
    for name, sizes in sweeps(a.size).items():
        if a.sweep and name != a.sweep:
            continue
        rows = []
        for k, (L, m, p) in sizes:
            try:
                rr = run_world(world(L, m, p), a.steps, preset=a.preset)
            except (ValueError, RuntimeError) as exc:  # a size the planner refuses
                print(f"  {name} {k:>6g}: refused: {exc}", flush=True)
                continue
            rows.append((k, rr))
            print(f"  {name} {k:>6g} ({L:g} px, {m} movers, {p} polygons): {_fmt(rr)}", flush=True)
        x = [k for k, _ in rows]
        fits = {
            st: slope(x, [max(rr["stages"][st], 1e-4) for _, rr in rows])
            for st in ("roadmap", "slice", "search", "kernel", "guard", "checker")
        }
        print(f"  {name}: exponent first plan {slope(x, [rr['first'] for _, rr in rows]):.2f}, "
              + ", ".join(f"{st} {v:.2f}" for st, v in fits.items()), flush=True)  # fmt: skip
        results[name] = rows
        if a.figure:  # after each sweep: a long run leaves its curves so far
            figure(results, a.figure, a.preset)
    if a.figure:
        print(f"figure: {a.figure}")


if __name__ == "__main__":
    import sys

    main(sys.argv[1:])
