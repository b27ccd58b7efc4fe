"""What a user waits for (issue 28, item 2): the first ``mawdo plan paper`` after installing
(Numba compiles the kernels), a warm one (kernels cached, snapshot grid and GIF included) and
``mawdo reproduce --quick``, each as a fresh process, on a cold or warm Numba cache.

Targets: first plan after installing <= 30 s wall on 2 cores, warm plan with its figures
<= 5 s wall. ``reproduce --quick`` has no target; it is measured so that its minutes are known.

Rows (each a fresh, empty ``NUMBA_CACHE_DIR`` where it says cold; Numba then caches there and
nowhere else):

* ``install: python -m mawdo.jit --jobs 2`` - what ``make install`` / ``make demo`` run after
  ``pip install``: the kernels compiled in 2 processes at once. Counted as installing, not as
  the first plan; the next row is the first plan after it.
* ``first plan paper after install`` - the target's row (installing included the compile).
* ``cold plan paper, no install step`` - a user who ran ``pip install`` only: the command finds
  its kernels missing and compiles them in 2 processes itself (a progress line every 2 s).
* ``cold plan paper, one process`` - the same with ``MAWDO_JIT_JOBS=1``: compiled in the
  command's own process as they are needed, as before issue 28.
* ``warm plan paper + GIF (k)`` - kernels cached. Since issue 28's second session the figures
  are set up in a process forked at the command's start, while the run is planned.
* ``warm plan paper, no figures`` - the same with ``--no-figures``: the planning alone (imports,
  kernels loaded from the cache, the run, its metrics), the floor under the row above, which
  the figures' process can only approach (5 s target shown for comparison).
* ``warm plan paper + GIF, phases`` - the warm row again, traced (``benchmarks/plan_trace.py``):
  the critical path as the command's process walks it, start-up (interpreter, imports,
  arguments, kernels loaded, the run set up), the run, and after it (metrics, then waiting for
  the figures), each wall and CPU; and the figures' process beside it: when it was forked and
  its imports done (matplotlib and the rest, while the command sets its run up: since issue
  28's fourth pass), its set-up (the grid and the GIF laid out), when it was ready, the frames
  it drew during the run, the grid after the run and the GIF's process.
  ``STARTUP_BEFORE=path/to/src`` alternates each sample with the same row on another copy of
  the sources (a before/after in the same minutes).

Every copy of the sources is byte-compiled first (``compileall``), as ``pip install`` does: with
``PYTHONDONTWRITEBYTECODE`` set (as on the machine these rows were measured on) and no ``.pyc``,
every run compiled mawdo's 84 modules again, 0.45 s of CPU no installed copy spends.

Wall time depends on what else runs on the machine (here 2 cores shared with other jobs), so
each row also gives the CPU time (user + sys) of the process and all its children
(``getrusage(RUSAGE_CHILDREN)``) and the load average. ``python -m benchmarks startup``
(about 5 to 15 minutes; ``STARTUP_SAMPLES=k`` warm samples, default 3; ``STARTUP_REPRODUCE=1``
adds the cold ``reproduce --quick``, 15 to 30 minutes; ``STARTUP_SRC=path`` measures another
copy of the sources, e.g. an older commit's ``src`` for a before/after; ``STARTUP_SKIP=one,cold``
leaves rows out: ``install`` (and the first plan after it), ``cold``, ``one``, ``warm``,
``phases``;
``STARTUP_CACHE=sources`` runs the warm rows on Numba's own cache beside the sources, warmed
beforehand, and skips the cold rows: a before/after of the warm rows in a minute). Beside each
row, the same row measured before (:data:`BEFORE`).
"""

from __future__ import annotations

import os
import resource
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
SRC = Path(os.environ.get("STARTUP_SRC", ROOT / "src")).resolve()


_WARM = (("jit/warm.py", "mawdo.jit"), ("jitwarm.py", "mawdo.jitwarm"))


def _flag(ok: bool) -> str:
    return "ok" if ok else "MISSED"


def _children_cpu() -> float:
    use = resource.getrusage(resource.RUSAGE_CHILDREN)
    return use.ru_utime + use.ru_stime


def timed(
    args: list[str], cache: Path | None, cwd: Path, env: dict | None = None
) -> tuple[float, float]:
    """Run ``python ARGS`` with the Numba cache in ``cache`` (None: Numba's own, beside the
    sources); (wall s, CPU s of it and its children)."""
    env = {**os.environ, **(env or {})}
    env.pop("NUMBA_CACHE_DIR", None)
    if cache is not None:
        env["NUMBA_CACHE_DIR"] = str(cache)
    env["PYTHONPATH"] = os.pathsep.join(filter(None, [str(SRC), env.get("PYTHONPATH")]))
    cpu, t = _children_cpu(), time.perf_counter()
    proc = subprocess.run([sys.executable, *args], cwd=cwd, env=env, capture_output=True)
    wall, cpu = time.perf_counter() - t, _children_cpu() - cpu
    if proc.returncode:
        raise RuntimeError(f"{' '.join(args)} failed:\n{proc.stderr.decode()[-2000:]}")
    return wall, cpu


def _load() -> str:
    one, five, _ = os.getloadavg()
    return f"load {one:.1f} (1 min) {five:.1f} (5 min) on {os.cpu_count()} cores"


#: The same rows measured at main 486dab0 (before the issue 28 item 2 work of 2026-11-26):
#: (wall s, CPU s, load average while it ran) on this shared 2-core VM at a load of 11 to 17
#: from other jobs (so wall times are several times the CPU times), printed beside each row.
#: Rows absent here (``cold plan paper, one process``: not measured then) print "-".
BEFORE = {
    "install: python -m mawdo.jit -j 2": (548.2, 82.7, 15),
    "first plan paper after install": (104.6, 9.9, 16),
    "cold plan paper, no install step": (525.9, 94.5, 12),
    "warm plan paper + GIF": (23.3, 9.1, 12),  # the better of 2 samples (27.0 s, 10.2 s)
    "cold reproduce --quick": (1755.7, 64.3, 11),  # /usr/bin/time, not this module
}


def _before(name: str) -> str:
    was = BEFORE.get(name.split(" (")[0])
    return (
        f"before {was[0]:6.1f} s wall / {was[1]:5.1f} s CPU (load {was[2]:.0f})"
        if was
        else "before -"
    )


def _row(name: str, wall: float, cpu: float, target: float | None) -> None:
    goal = f"(target <= {target:g} s {_flag(wall <= target)})" if target else "(no target)"
    print(
        f"  {name:38s} wall {wall:7.1f} s {goal:24s} CPU {cpu:7.1f} s   {_load()}\n"
        f"  {'':38s} {_before(name)}",
        flush=True,
    )


def _compiled(src: Path) -> None:
    """Byte-compile a copy of the sources, as an install does (see the module's docstring)."""
    subprocess.run([sys.executable, "-m", "compileall", "-q", str(src)], capture_output=True)


def traced(src: Path, cache: Path | None, cwd: Path, out: str) -> tuple[float, float, dict]:
    """A warm ``plan paper`` with its figures, traced (:mod:`benchmarks.plan_trace`): (wall s,
    CPU s of it and its children, the marks by ``(role, name)``)."""
    from benchmarks.plan_trace import phases

    log = cwd / f"{out}.trace"
    env = {**os.environ, "PYTHONPATH": str(src)}
    env.pop("NUMBA_CACHE_DIR", None)
    if cache is not None:
        env["NUMBA_CACHE_DIR"] = str(cache)
    args = [str(ROOT / "benchmarks" / "plan_trace.py"), str(log), "plan", "paper"]
    args += ["--no-progress", "--out", out]
    cpu, t = _children_cpu(), time.perf_counter()
    env["TRACE_T0"] = repr(t)
    proc = subprocess.run([sys.executable, *args], cwd=cwd, env=env, capture_output=True)
    wall, cpu = time.perf_counter() - t, _children_cpu() - cpu
    if proc.returncode:
        raise RuntimeError(f"traced plan paper failed:\n{proc.stderr.decode()[-2000:]}")
    return wall, cpu, phases(str(log))


def _phase_row(name: str, wall: float, cpu: float, m: dict) -> None:
    """The traced row: the critical path's phases, then the figures' process beside them."""
    main = {k[1]: v for k, v in m.items() if k[0] == "main"}
    fig = {k[1]: v for k, v in m.items() if k[0] == "figures"}
    gif = {k[1]: v for k, v in m.items() if k[0] == "gif"}
    run0, run1, end = main["run>"], main["run<"], main["end"]
    print(
        f"  {name:38s} wall {wall:7.2f} s (target <= 5 s {_flag(wall <= 5)}) CPU {cpu:6.2f} s"
        f"   {_load()}\n"
        f"  {'':38s} critical path: start-up {run0[0]:.2f} s wall / {run0[1]:.2f} s CPU "
        f"(imports {main['imported'][0]:.2f} s), run {run1[0] - run0[0]:.2f} / "
        f"{run1[1] - run0[1]:.2f}, after it {end[0] - run1[0]:.2f} s wall "
        f"(this process {end[1] - run1[1]:.2f} s CPU, then the figures)",
        flush=True,
    )
    if "warm<" in fig:  # (imports while the parent sets its run up, before the set-up)
        w0, w1 = fig["warm>"], fig["warm<"]
        print(
            f"  {'':38s} figures: forked at {w0[0]:.2f} s, imports done at {w1[0]:.2f} s "
            f"({w1[1]:.2f} s CPU), set-up begun at {fig['setup>'][0]:.2f} s",
            flush=True,
        )
    if "setup<" in fig and "finish<" in fig:
        s0, s1, f0, f1 = fig["setup>"], fig["setup<"], fig["finish>"], fig["finish<"]
        print(
            f"  {'':38s} figures: set up from {s0[0]:.2f} to {s1[0]:.2f} s "
            f"({s1[1] - s0[1]:.2f} s CPU),"
            f" frames during the run {f0[1] - s1[1]:.2f} s CPU, after the run "
            f"{f1[1] - f0[1]:.2f} s CPU (grid), GIF process {gif.get('gif<', (0, 0))[1]:.2f} s"
            f" CPU; done at {f1[0]:.2f} s",
            flush=True,
        )


def _phase_rows(samples: int, cache: Path | None, tmp: Path) -> None:
    """The traced rows, alternating with ``STARTUP_BEFORE``'s sources if set."""
    before = os.environ.get("STARTUP_BEFORE")
    copies = [("after", SRC)] + ([("before", Path(before).resolve())] if before else [])
    for _, src in copies:
        _compiled(src)
    for k in range(samples):
        for label, src in copies:
            tag = f" {label}" if before else ""
            row = f"warm plan paper + GIF, phases{tag} ({k + 1})"
            _phase_row(row, *traced(src, cache, tmp, f"p{label}{k}"))


def _cold(tmp: Path, name: str) -> Path:
    cache = tmp / name
    cache.mkdir()
    return cache


def main() -> None:
    samples = int(os.environ.get("STARTUP_SAMPLES", "3"))
    skip = set(filter(None, os.environ.get("STARTUP_SKIP", "").split(",")))
    sources = os.environ.get("STARTUP_CACHE", "") == "sources"
    if sources:
        skip |= {"install", "cold", "one"}
    plan = ["-m", "mawdo.cli", "plan", "paper", "--no-progress", "--out"]
    print(f"  sources: {SRC}")
    _compiled(SRC)
    with tempfile.TemporaryDirectory(prefix="mawdo-startup-") as tmp:
        tmp = Path(tmp)
        cache = _cold(tmp, "numba-install")
        # the install step's module: mawdo.jit, or mawdo.jitwarm in sources from before the move
        step = next((m for f, m in _WARM if (SRC / "mawdo" / f).is_file()), None)
        if step and "install" not in skip:
            warm = ["-m", step, "--jobs", "2"]
            _row("install: python -m mawdo.jit -j 2", *timed(warm, cache, tmp), None)
            _row("first plan paper after install", *timed([*plan, "first"], cache, tmp), 30)
        if step and "cold" not in skip:
            one = _cold(tmp, "numba-cold")
            _row("cold plan paper, no install step", *timed([*plan, "cold"], one, tmp), 30)
            cache = one
        if "one" not in skip:
            jobs1 = {"MAWDO_JIT_JOBS": "1"}
            cold = _cold(tmp, "numba-cold1")
            _row("cold plan paper, one process", *timed([*plan, "c1"], cold, tmp, jobs1), 30)
            cache = cold
        cache = None if sources else cache
        for k in range(samples if "warm" not in skip else 0):
            _row(f"warm plan paper + GIF ({k + 1})", *timed([*plan, f"w{k}"], cache, tmp), 5)
        bare = [*plan[:-1], "--no-figures", "--out"]
        for k in range(samples if "warm" not in skip else 0):
            _row(f"warm plan paper, no figures ({k + 1})", *timed([*bare, f"n{k}"], cache, tmp), 5)
        if "phases" not in skip:
            _phase_rows(samples, cache, tmp)
        if os.environ.get("STARTUP_REPRODUCE", "0") != "0":
            repro = _cold(tmp, "numba-reproduce")
            args = ["-m", "mawdo.cli", "reproduce", "--quick", "--no-progress", "--out", "r"]
            _row("cold reproduce --quick", *timed(args, repro, tmp), None)


if __name__ == "__main__":
    main()
