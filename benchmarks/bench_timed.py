"""Timed families (issue 27): MAWDO with and without the safe-interval guide, and the guides
alone, against the issue's targets.

``python -m benchmarks timed`` (or ``python benchmarks/bench_timed.py [--scenes N]
[--families a,b] [--planners p,q] [--workers W] [--no-paper]``). For each timed family, scenes
``0 .. N-1`` of seed 0, each planner once (seed 0, ``realtime`` preset): success share, active
collisions (checker, every run), and the median and p95 of ``T / T*`` over the successful runs;
then the paper scenario with ``mawdo_time`` against ``mawdo`` (success, ``L / L*``).
Targets: success >= 99 %, 0 active collisions, ``T / T*`` median <= 1.05 and p95 <= 1.15.

``--latency`` (in ``python -m benchmarks timed`` too): the wall time of every replan step
(optimizer, guard and the safe-interval guide's queries together: the time between two
``progress`` calls of a step that replanned; the first plan excluded; one untimed warm-up run of
each case first), p95 over the runs, for
``mawdo`` and ``mawdo_time`` on the paper scenario (seeds 0-4; target <= 20 ms) and on
``crowd`` scenes 0-4 (seed 0; target <= 50 ms). One core per row unless ``--threads`` says
more (see below); the wall figure moves with the load, so the CPU time of the same steps
(``time.process_time``, every thread's) is printed beside it, and the load average
(``os.getloadavg``) above them. ``--split`` adds, per case, that CPU divided
into the cost kernel's calls (:class:`KernelClock`) and the rest, the planner's Python.
``--cases paper`` (or ``crowd``) and ``--latency-planners mawdo_time`` (or ``mawdo``) time
only those (``--cases paper --latency-planners mawdo_time``: the default planner on the paper
scenario, about a minute); ``--no-guide-gate`` times them with
:attr:`~mawdo.planning.run.config.PlannerConfig.guide_gate` off (the default presets have it
on). ``--threads 1,2`` times them with the population cost on that many threads each
(:attr:`~mawdo.planning.run.config.PlannerConfig.threads`; default one and every CPU this
process may use, a row each): the presets use one, a robot's planner may use its cores.
"""

from __future__ import annotations

import argparse
import contextlib
import os
import time
from concurrent.futures import ProcessPoolExecutor

import numpy as np

FAMILIES = ("corridor", "doorway", "chaser", "crowd", "parked", "slalom")
PLANNERS = ("mawdo", "mawdo_time", "guide_only")


def _one(args):
    family, index, planner = args
    from mawdo.planning.judge.metrics import run_metrics
    from mawdo.planning.run.planners import run_planner
    from mawdo.planning.scenes import generate_scene

    scene = generate_scene(family, index, seed=0)
    t0 = time.perf_counter()
    res = run_planner(planner, scene.scenario, seed=0)
    wall = time.perf_counter() - t0
    m = run_metrics(res, l_star=scene.l_star, snapshots=0, t_star=scene.t_star)
    if scene.t_star is None and res.solved and res.route_times is not None:  # a static family
        from mawdo.planning.judge.check import check_trajectory

        rep = check_trajectory(res.route, res.scenario, times=res.route_times)
        m |= {"active_collisions": len(rep.active), "passive_collisions": len(rep.passive)}
    return family, index, planner, m, wall


def _paper(planner):
    from mawdo.planning.judge.metrics import run_metrics
    from mawdo.planning.run.planners import run_planner

    res = run_planner(planner, "paper", seed=0)
    return planner, run_metrics(res, snapshots=0)


class KernelClock:
    """CPU seconds spent in the compiled cost kernel's calls (``ThreadedKernel.__call__``,
    its Python dispatch included), counted while the context is open."""

    def __init__(self) -> None:
        self.cpu = 0.0

    def __enter__(self) -> KernelClock:
        from mawdo.planning.refine.kernel.threads import ThreadedKernel

        self._cls, self._call = ThreadedKernel, ThreadedKernel.__call__
        call = self._call

        def timed(kernel, *args):
            t = time.process_time()
            try:
                return call(kernel, *args)
            finally:
                self.cpu += time.process_time() - t

        ThreadedKernel.__call__ = timed
        return self

    def __exit__(self, *exc) -> None:
        self._cls.__call__ = self._call


def step_times(scenario, time_guide: bool, seed: int = 0, clock=None, **settings) -> list[tuple]:
    """Wall and CPU time (s) of each replanning step of one realtime run (see the module
    docstring), with planner ``settings`` changed; with a :class:`KernelClock` ``clock``, the
    step's kernel CPU third."""
    from mawdo.planning.run.planner import plan

    marks = []

    def mark(step, _, replans):
        kernel = clock.cpu if clock is not None else 0.0
        marks.append((time.perf_counter(), time.process_time(), replans, kernel))

    plan(scenario, "mawdo", seed=seed, time_guide=time_guide, progress=mark, **settings)
    pairs = zip(marks[1:-1], marks[2:], strict=True)
    out = [(b[0] - a[0], b[1] - a[1], b[3] - a[3]) for a, b in pairs if b[2] > a[2]]
    return out if clock is not None else [t[:2] for t in out]


def latency(
    runs: int = 5,
    split: bool = False,
    cases=("paper", "crowd"),
    planners=None,
    threads=(1,),
    **settings,
) -> None:
    """Replan p95 of ``mawdo`` and ``mawdo_time`` on the paper scenario and on ``crowd``;
    ``split``: a second row per case, the CPU of the steps in the cost kernel and the rest
    (the Python around it), each as median and p95 over the steps. ``cases``: which of the
    two scenes; ``planners``: which of ``mawdo`` and ``mawdo_time`` (default both);
    ``threads``: the population cost's thread counts, a row each; ``settings``: planner
    settings changed in every run (``guide_gate=False``)."""
    from mawdo.planning import get_scenario
    from mawdo.planning.scenes import generate_scene

    make = {
        "paper": lambda: ([get_scenario("paper")] * runs, 20.0),
        "crowd": lambda: ([generate_scene("crowd", i, seed=0).scenario for i in range(runs)], 50.0),
    }
    cases = [(name, *make[name]()) for name in cases]
    kinds = [(p, p == "mawdo_time", t) for p in (planners or ("mawdo", "mawdo_time"))
             for t in threads]  # fmt: skip
    # one untimed run of each kind first: a kernel compiled (or loaded from the cache) inside a
    # measured replan would be counted as latency
    for _, scenes, _ in cases:
        for _, on, t in kinds:
            step_times(scenes[0], on, seed=0, threads=t, **settings)
    print("load average (1, 5, 15 min): " + ", ".join(f"{x:.2f}" for x in os.getloadavg()))
    for name, scenes, target in cases:
        for planner, on, th in kinds:
            with KernelClock() if split else contextlib.nullcontext() as clock:
                got = [step_times(sc, on, k, clock, threads=th, **settings)
                       for k, sc in enumerate(scenes)]  # fmt: skip
                lat = np.array([t for run in got for t in run])
            p95, med = 1e3 * np.percentile(lat, 95, axis=0), 1e3 * np.median(lat, axis=0)
            ok = "ok" if p95[0] <= target else "MISSED"
            print(f"replan {name:5s} {planner:11s} {th} thr {len(lat):4d} replans  "
                  f"median {med[0]:6.1f} ms "
                  f"p95 {p95[0]:6.1f} ms (<= {target:g} {ok})  CPU median {med[1]:6.1f} ms "
                  f"p95 {p95[1]:6.1f} ms (<= {target:g})")  # fmt: skip
            if split:
                rest = 1e3 * (lat[:, 1] - lat[:, 2])
                print(f"       {'':5s} {'':11s} CPU split: kernel median {med[2]:6.1f} ms p95 "
                      f"{p95[2]:6.1f} ms, rest median {np.median(rest):6.1f} ms p95 "
                      f"{np.percentile(rest, 95):6.1f} ms")  # fmt: skip


def _row(name, runs) -> str:
    ok = [m for m in runs if m["success"]]
    act = sum(m.get("active_collisions") or 0 for m in runs)
    gaps = np.array([m.get("time_gap", np.nan) for m in ok])
    med, p95 = (np.median(gaps), np.percentile(gaps, 95)) if gaps.size else (np.nan, np.nan)
    lg = np.array([m["gap"] for m in ok])
    lmed, lmax = (np.median(lg), np.max(lg)) if lg.size else (np.nan, np.nan)
    return (f"{name:24s} success {len(ok)}/{len(runs)} (target >= 99 %)  active {act} "
            f"(target 0)  T/T* median {med:.3f} (<= 1.05)  p95 {p95:.3f} (<= 1.15)  "
            f"L/L* median {lmed:.4f} max {lmax:.4f}")  # fmt: skip


def main(argv=None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--scenes", type=int, default=5)
    ap.add_argument("--families", default=",".join(FAMILIES))
    ap.add_argument("--planners", default=",".join(PLANNERS))
    ap.add_argument("--workers", type=int, default=1)
    ap.add_argument("--no-paper", action="store_true")
    ap.add_argument("--latency", action="store_true", help="only the replan latency figures")
    ap.add_argument("--split", action="store_true",
                    help="with the latency figures, each step's CPU in the cost kernel and in "
                         "the rest")  # fmt: skip
    ap.add_argument("--cases", default="paper,crowd",
                    help="with --latency, the scenes timed (paper, crowd)")  # fmt: skip
    ap.add_argument("--latency-planners", default="mawdo,mawdo_time",
                    help="with --latency, the planners timed (mawdo, mawdo_time)")  # fmt: skip
    ap.add_argument("--no-guide-gate", action="store_true",
                    help="with --latency, the planner's guide gate off")  # fmt: skip
    from mawdo.cli.plan import usable_cpus

    ap.add_argument("--threads", default=",".join(map(str, sorted({1, usable_cpus()}))),
                    help="with --latency, the cost's thread counts, a row each")  # fmt: skip
    a = ap.parse_args([] if argv is None else argv)
    if a.latency or argv is None:
        cases, planners = a.cases.split(","), a.latency_planners.split(",")
        for name, known in ((cases, ("paper", "crowd")), (planners, ("mawdo", "mawdo_time"))):
            if bad := [x for x in name if x not in known]:
                ap.error(f"unknown {bad[0]!r}: choose from {', '.join(known)}")
        gate = {"guide_gate": False} if a.no_guide_gate else {}
        try:
            threads = [int(t) for t in a.threads.split(",")]
        except ValueError:
            threads = []
        if not threads or min(threads) < 1:
            ap.error(f"--threads {a.threads!r}: give thread counts >= 1, like 1,2")
        latency(split=a.split, cases=cases, planners=planners, threads=threads, **gate)
        if a.latency:
            return
    fams, plans = a.families.split(","), a.planners.split(",")
    jobs = [(f, i, p) for f in fams for i in range(a.scenes) for p in plans]
    out = []
    with ProcessPoolExecutor(a.workers) as pool:
        for f, i, p, m, wall in pool.map(_one, jobs):  # in order, each as soon as it is done
            out.append((f, i, p, m, wall))
            print(f"  {f}-{i} {p:11s} ok={m['success']!s:5s} active={m.get('active_collisions')} "
                  f"passive={m.get('passive_collisions')} T/T*={m.get('time_gap', np.nan):.3f} "
                  f"L/L*={m['gap']:.4f} {wall:.0f}s "
                  f"{'' if m['success'] else m['reason'][:70]}", flush=True)  # fmt: skip
        paper = [] if a.no_paper else list(pool.map(_paper, ["mawdo", "mawdo_time"]))
    for f in fams:
        for p in plans:
            print(_row(f"{f} {p}", [m for ff, _, pp, m, _ in out if ff == f and pp == p]))
    for p, m in paper:
        print(f"paper {p:11s} success {m['success']}  L/L* {m['gap']:.4f}  steps {m['steps']}")


if __name__ == "__main__":
    import sys

    main(sys.argv[1:])
