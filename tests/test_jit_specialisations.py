"""Each kernel compiles once: no second specialisation for a literal argument (issue 28 item 2).

A counter started at a literal ``0`` and passed to a kernel inside a loop (``n = 0``, then
``n = f(..., n)``) makes Numba type the call first with ``Literal[int](0)`` and compile the
callee for it, then again for ``int64`` once the loop widens the type: a whole second compile
of the callee and of everything it calls, thrown away (``classify_segments``, and
``_mover_forbidden`` with ``_polygon_piece`` and ``_push``: about 8 s of CPU in a cold
``mawdo plan paper``). The callers compile here on an empty cache, in a fresh process, and
every compile is counted. (``_mover_forbidden`` and ``_polygon_piece`` are inlined into
``forbidden`` since the eighth session: Numba inlines their untyped code, so they are never
compiled on their own, for any type.)
"""

import os
import subprocess
import sys
from pathlib import Path

import pytest

from mawdo.jit import warm as jitwarm

SRC = str(Path(jitwarm.__file__).resolve().parents[1])

COUNT = """
import sys
from numba.core import event
from mawdo.jit import warm as jitwarm
seen = []
class Count(event.Listener):
    def on_start(self, ev):
        f = ev.data["dispatcher"].py_func
        if f.__module__.startswith("mawdo."):
            seen.append((f.__name__, repr(tuple(ev.data["args"]))))
    def on_end(self, ev): pass
event.register("numba:compile", Count())
for e in jitwarm.load_table():
    if e.name in sys.argv[1:]:
        jitwarm.dispatcher(e).compile(jitwarm.parse(e.sig))
for name, sig in seen:
    print(name, "LITERAL" if "Literal" in sig else "plain")
"""


@pytest.mark.slow
def test_kernels_that_pass_a_counter_compile_their_callees_once(tmp_path):
    env = {**os.environ, "NUMBA_CACHE_DIR": str(tmp_path), "PYTHONPATH": SRC}
    # static_pass calls classify_segments with a counter; forbidden calls forbidden_among,
    # which calls _polygon_piece with one (the callers, as `plan paper` compiles them)
    args = [sys.executable, "-c", COUNT, "static_pass", "forbidden"]
    proc = subprocess.run(args, env=env, capture_output=True, text=True, timeout=600)
    assert proc.returncode == 0, proc.stderr
    rows = [line.split() for line in proc.stdout.splitlines()]
    names = [name for name, _ in rows]
    for callee in ("classify_segments", "forbidden", "forbidden_among", "_polygon_piece"):
        assert names.count(callee) == 1, (callee, rows)
    assert names.count("_mover_forbidden") == 0, rows  # (inlined into forbidden)
    assert not [r for r in rows if r[1] == "LITERAL"], rows
    assert len(names) == len(set(names)), rows  # every mawdo kernel once
