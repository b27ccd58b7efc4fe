"""What a user waits for (issue 28, item 2): the first ``mawdo plan paper`` after installing
(Numba compiles the kernels), a warm one (kernels cached, snapshot grid and GIF included) and
``mawdo reproduce --quick``, each as a fresh process, on a cold or warm Numba cache.

Targets: cold first plan <= 30 s wall on 2 cores, warm plan with its figures <= 5 s wall.
``reproduce --quick`` has no target; it is measured so that its minutes are known.

A cold cache is a fresh, empty ``NUMBA_CACHE_DIR`` (Numba then caches there and nowhere else);
warm reuses the folder a cold run filled. Wall time depends on what else runs on the machine,
so each row also gives the CPU time of the process and its children, and the load average.
``python -m benchmarks startup`` (about 5 to 15 minutes; ``STARTUP_SAMPLES=k`` for k warm
samples, default 3; ``STARTUP_REPRODUCE=0`` skips the reproduction).
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


def _flag(ok: bool) -> str:
    return "ok" if ok else "MISSED"


def _children_cpu() -> float:
    use = resource.getrusage(resource.RUSAGE_CHILDREN)
    return use.ru_utime + use.ru_stime


def timed(args: list[str], cache: Path, cwd: Path) -> tuple[float, float]:
    """Run ``python -m mawdo.cli ARGS`` with the Numba cache in ``cache``; (wall s, CPU s)."""
    env = {**os.environ, "NUMBA_CACHE_DIR": str(cache)}
    env["PYTHONPATH"] = os.pathsep.join(filter(None, [str(ROOT / "src"), env.get("PYTHONPATH")]))
    cpu, t = _children_cpu(), time.perf_counter()
    proc = subprocess.run(
        [sys.executable, "-m", "mawdo.cli", *args], cwd=cwd, env=env, capture_output=True
    )
    wall, cpu = time.perf_counter() - t, _children_cpu() - cpu
    if proc.returncode:
        raise RuntimeError(f"mawdo {' '.join(args)} failed:\n{proc.stderr.decode()[-2000:]}")
    return wall, cpu


def _load() -> str:
    one, five, _ = os.getloadavg()
    return f"load {one:.1f} (1 min) {five:.1f} (5 min) on {os.cpu_count()} cores"


def _row(name: str, wall: float, cpu: float, target: float | None) -> None:
    goal = f"(target <= {target:g} s {_flag(wall <= target)})" if target else "(no target)"
    print(f"  {name:34s} wall {wall:7.1f} s {goal:24s} CPU {cpu:7.1f} s   {_load()}")


def main() -> None:
    samples = int(os.environ.get("STARTUP_SAMPLES", "3"))
    with tempfile.TemporaryDirectory(prefix="mawdo-startup-") as tmp:
        tmp = Path(tmp)
        cache = tmp / "numba-cold"
        cache.mkdir()
        plan = ["plan", "paper", "--no-progress", "--out"]
        _row("cold first `plan paper`", *timed([*plan, str(tmp / "cold")], cache, tmp), 30)
        for k in range(samples):
            out = str(tmp / f"warm{k}")
            _row(f"warm `plan paper` + GIF ({k + 1})", *timed([*plan, out], cache, tmp), 5)
        if os.environ.get("STARTUP_REPRODUCE", "1") != "0":
            cold = tmp / "numba-reproduce"
            cold.mkdir()
            args = ["reproduce", "--quick", "--no-progress", "--out", str(tmp / "repro")]
            _row("cold `reproduce --quick`", *timed(args, cold, tmp), None)


if __name__ == "__main__":
    main()
