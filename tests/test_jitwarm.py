"""The kernel warm-up (mawdo.jit.warm): its table reads back, its schedule is fair, and a warmed
cache leaves nothing for `mawdo plan paper` to compile."""

import os
import subprocess
import sys
import time
from pathlib import Path

import numba
import numpy as np
import pytest

from mawdo.jit import warm as jitwarm
from mawdo.jit.schedule import Schedule, plan_order
from mawdo.jit.warm import Entry, load_table, parse

SRC = str(Path(jitwarm.__file__).resolve().parents[1])


def test_signatures_read_back_as_numba_types():
    values = [
        np.zeros((2, 3)),
        np.zeros(4, dtype=np.int16)[::2],  # layout 'A'
        (np.zeros(2), np.zeros((2, 2), dtype=np.int64)),
        True,
        3,
        2.5,
    ]
    ro = np.zeros(3, dtype=np.int64)
    ro.flags.writeable = False
    values.append(ro)
    types = tuple(numba.typeof(v) for v in values)
    assert parse(repr(types)) == types
    assert not parse(repr(types))[-1].mutable  # a read-only array stays read-only


def test_every_table_row_names_a_kernel_and_types_it_can_compile():
    table = load_table()
    assert any(e.name == "fused_population_cost" for e in table)  # the path cost, the longest
    for e in table:
        disp = jitwarm.dispatcher(e)
        assert isinstance(disp, numba.core.registry.CPUDispatcher), e
        assert len(parse(e.sig)) == disp.py_func.__code__.co_argcount, e


def test_the_table_compiles_each_kernel_once():
    # `plan paper` compiles one specialisation per kernel (recorded on an empty cache: 47
    # kernels); a second row for a kernel is a signature no command passes any more (a stale
    # `wind_step` row with bool gravity and pressure codes cost every install 4.7 s of CPU)
    keys = [e.key for e in load_table()]
    assert len(keys) == len(set(keys)), sorted(k for k in keys if keys.count(k) > 1)


def test_processes_share_the_work_evenly_longest_first():
    secs = [40, 9, 8, 7, 6, 5, 4, 3]
    entries = [Entry("m", f"f{k}", s, "-", "()") for k, s in enumerate(secs)]
    parts = plan_order(entries, 2)
    assert sorted(e.name for p in parts for e in p) == sorted(e.name for e in entries)
    loads = sorted(sum(e.seconds for e in p) for p in parts)
    assert loads == [40, 42]  # longest first to the process free first: {40}, the rest
    for p in parts:
        assert p == sorted(p, key=entries.index)
    assert plan_order(entries[:1], 4) == [entries[:1]]  # no empty lists


def test_a_kernel_comes_after_its_callees_and_the_longest_chain_first():
    # recorded order: callees before their caller; c2 is called by c1, c1 by the root
    c2 = Entry("m", "c2", 3, "m.c1", "()")
    c1 = Entry("m", "c1", 5, "m.root", "()")
    x = Entry("m", "x", 9, "-", "()")
    root = Entry("m", "root", 40, "-", "()")
    y = Entry("m", "y", 8, "-", "()")
    a, b = plan_order([x, c2, c1, root, y], 2)
    assert a == [c2, c1, root]  # the longest chain (48) in order, callees first
    assert b == [x, y]  # the rest meanwhile


def test_the_parts_of_a_kernel_compile_in_both_processes_before_it():
    # the cost kernel's shape: two big callees side by side, the kernel after both
    p1 = Entry("m", "p1", 20, "m.root", "()")
    p2 = Entry("m", "p2", 12, "m.root", "()")
    root = Entry("m", "root", 10, "-", "()")
    x = Entry("m", "x", 8, "-", "()")
    a, b = plan_order([p1, p2, root, x], 2)
    assert a == [p1, root]  # root waits for p2 (ends at 12) and p1 (20)
    assert b == [p2, x]  # x meanwhile, not root
    # handed out as processes free up: root only once both of its callees are done
    sched = Schedule([p1, p2, root, x])
    assert [sched.next(), sched.next()] == [p1, p2]
    sched.finish(p2)
    assert sched.next() == x  # root is not ready: p1 is not done
    assert sched.next() is None
    sched.finish(p1)
    assert sched.next() == root and sched.empty


def test_a_cycle_in_the_table_cannot_stall_the_processes():
    a = Entry("m", "a", 1, "m.b", "()")
    b = Entry("m", "b", 1, "m.a", "()")
    sched = Schedule([a, b])
    assert sched.next() is None  # neither is ready while something compiles
    assert sched.next(busy=False) in (a, b)  # nothing does: one is handed out anyway
    assert sorted(e.name for p in plan_order([a, b], 2) for e in p) == ["a", "b"]


def test_a_compiling_process_that_dies_ends_the_warm_up_instead_of_hanging(monkeypatch):
    monkeypatch.setattr(jitwarm, "_CHILD", ["-c", "import sys; sys.exit(3)"])
    rows = [Entry("m", f"f{k}", 1.0, "-", "()") for k in range(3)]
    t0 = time.perf_counter()
    assert jitwarm.warm(2, rows) == 0  # none compiled: left to the command
    assert time.perf_counter() - t0 < 30


def _run(args, cache, **kw):
    env = {**os.environ, "NUMBA_CACHE_DIR": str(cache), "PYTHONPATH": SRC}
    return subprocess.run(
        [sys.executable, *args], env=env, capture_output=True, text=True, timeout=1500, **kw
    )


# Counts Numba's compiles in a fresh process running `mawdo plan paper` (after the warm-up,
# every kernel must load from the cache).
COUNT = """
import runpy, sys
from numba.core import event
seen = []
class Count(event.Listener):
    def on_start(self, ev): seen.append(ev.data["dispatcher"].py_func.__qualname__)
    def on_end(self, ev): pass
event.register("numba:compile", Count())
sys.argv = ["mawdo", "plan", "paper", "--no-figures", "--no-progress", "--out", sys.argv[1]]
from mawdo.cli import quick_exit
quick_exit.end = lambda code: None  # the program's end without teardown would skip the count
try:
    runpy.run_module("mawdo.cli", run_name="__main__")
finally:
    print("COMPILED", len(seen), seen)
"""

# Two small kernels compiled by warm() in two processes, with a progress line every 0.2 s.
SMALL = """
import sys
from mawdo.jit import warm as jitwarm
K = "mawdo.planning.refine.kernel.primitives"
rows = [
    jitwarm.Entry(K, "orient", 0.1, "-", "(" + ", ".join(["float64"] * 6) + ")"),
    jitwarm.Entry(K, "abs_atan2", 0.2, "-", "(float64, float64)"),
]
if sys.argv[1] == "warm":
    print("MISSING", len(jitwarm.missing(rows)))
    n = jitwarm.warm(2, rows, tick=lambda d, t, s: print(f"TICK {d}/{t}"), every=0.2)
    print("COMPILED", n)
else:
    print("MISSING", len(jitwarm.missing(rows)), jitwarm.looks_cached(rows))
"""


# What is left to compile, told without importing Numba where no index file exists yet, and
# by Numba's index where one does (another signature of a cached kernel is still missing).
TODO = """
import sys
from mawdo.jit import warm as jitwarm
K = "mawdo.planning.refine.kernel.primitives"
F6 = "(" + ", ".join(["float64"] * 6) + ")"
rows = [jitwarm.Entry(K, "orient", 0.1, "-", F6),
        jitwarm.Entry(K, "orient", 0.1, "-", F6.replace("float64", "float32")),
        jitwarm.Entry(K, "abs_atan2", 0.2, "-", "(float64, float64)")]
left = [r.sig[:8] + " " + r.name for r in jitwarm.todo(rows)]
print("TODO", left, "numba" in sys.modules)
if sys.argv[1] == "fill":
    jitwarm.compile_entries(rows[:1])
"""


def test_todo_needs_no_import_on_a_cold_cache_and_sees_a_missing_signature(tmp_path):
    cold = _run(["-c", TODO, "fill"], tmp_path)
    assert cold.returncode == 0, cold.stderr
    everything = "['(float64 orient', '(float32 orient', '(float64 abs_atan2']"
    assert f"TODO {everything} False" in cold.stdout  # stat calls only
    warm = _run(["-c", TODO, "check"], tmp_path)  # orient's float64 signature cached now
    assert "TODO ['(float32 orient', '(float64 abs_atan2'] True" in warm.stdout, warm.stderr


def test_warm_compiles_in_processes_into_the_cache_a_new_process_finds(tmp_path):
    first = _run(["-c", SMALL, "warm"], tmp_path)
    assert first.returncode == 0, first.stderr
    lines = first.stdout.splitlines()
    assert lines[0] == "MISSING 2" and lines[-1] == "COMPILED 2", first.stdout
    assert lines[-2] == "TICK 2/2"  # the last tick: all done
    second = _run(["-c", SMALL, "check"], tmp_path)
    assert second.stdout.strip() == "MISSING 0 True", second.stderr


PENDING = (
    "from mawdo.jit import warm as jitwarm; "
    "print('PENDING', len(jitwarm.todo()), len(jitwarm.load_table()))"
)


@pytest.mark.slow
def test_a_warmed_cache_leaves_nothing_to_compile(tmp_path):
    cache = tmp_path / "numba"
    cache.mkdir()
    before = _run(["-c", PENDING], cache)
    n = len(load_table())
    assert f"PENDING {n} {n}" in before.stdout, before.stderr  # an empty cache: all of them
    warm = _run(["-m", "mawdo.jit", "--jobs", "2"], cache)
    assert warm.returncode == 0, warm.stderr
    assert f"{n} kernels compiled" in warm.stdout
    after = _run(["-c", PENDING], cache)
    assert f"PENDING 0 {n}" in after.stdout, after.stderr
    run = _run(["-c", COUNT, str(tmp_path / "out")], cache)
    assert run.returncode == 0, run.stderr
    assert "COMPILED 0 []" in run.stdout, run.stdout[-2000:]


# A compile announced on a cache miss, while another process puts that very kernel in the
# cache (as the commands' warm-up does at their first compile): the kernel loads instead.
LOADER = """
import subprocess, sys
import numpy as np
from numba.core import event
from mawdo.jit import warm as jitwarm
from mawdo.planning.refine.kernel.primitives import orient
FILL = "from mawdo.planning.refine.kernel.primitives import orient; orient(0., 0., 1., 0., 0., 1.)"
passes, answers = [], []
class Fill(event.Listener):
    def on_start(self, ev):
        if not answers:
            subprocess.run([sys.executable, "-c", FILL], check=True)
            answers.append(jitwarm.load_instead(ev.data["dispatcher"], ev.data["args"]))
    def on_end(self, ev): pass
class Passes(event.Listener):
    def on_start(self, ev): passes.append(1)
    def on_end(self, ev): pass
event.register("numba:compile", Fill())
event.register("numba:run_pass", Passes())
got = orient(0.0, 0.0, 1.0, 0.0, 0.0, 1.0)
again = jitwarm.load_instead(orient, orient.signatures[0])  # in memory now: nothing to load
print("LOADED", answers, "PASSES", len(passes), "VALUE", got, "AGAIN", again)
print("OWN", "compile" in vars(orient._compiler), "save_overload" in vars(orient._cache))
"""


def test_the_compile_that_started_the_warm_up_loads_what_it_cached(tmp_path):
    run = _run(["-c", LOADER], tmp_path)
    assert run.returncode == 0, run.stderr
    from mawdo.planning.refine.kernel.primitives import orient

    assert f"VALUE {orient.py_func(0.0, 0.0, 1.0, 0.0, 0.0, 1.0)}" in run.stdout
    assert "LOADED [True] PASSES 0" in run.stdout, run.stdout  # no compiler pass ran here
    assert "AGAIN False" in run.stdout  # a kernel in memory is never compiled again
    assert "OWN False False" in run.stdout  # Numba's own methods back after that one compile


def test_ctrl_c_during_the_install_step_ends_every_compiling_process(tmp_path):
    from tests.cli_run import ENV, children, ctrl_c, interruptible

    env = {**ENV, "NUMBA_CACHE_DIR": str(tmp_path), "PYTHONPATH": SRC}
    proc = interruptible([sys.executable, "-m", "mawdo.jit", "--jobs", "2"], env=env)
    for line in proc.stdout:  # "compiling 56 kernels into Numba's cache in 2 processes ..."
        if line.startswith("compiling") and "processes" in line:
            break
    time.sleep(2.0)
    assert len(children(proc.pid)) == 2
    err = ctrl_c(proc)  # exit 130, no traceback (none from a compiling process), none left
    assert "interrupted: run it again" in err
