"""The jit table's upkeep (:mod:`mawdo.jit.record`): rows re-timed alone in a fresh process, a
recording merged into the table without losing or repeating a row."""

from mawdo.jit import warm as jitwarm
from mawdo.jit.record import _merge, retime, write_table

CHEAP = ("_less", "stride", "orient")  # three small kernels of the real table


def _rows() -> list[jitwarm.Entry]:
    return [e for e in jitwarm.load_table() if e.name in CHEAP]


def test_retime_times_each_row_in_a_fresh_process_and_keeps_the_rest(tmp_path):
    rows = _rows()
    assert len(rows) == len(CHEAP)
    path = tmp_path / "table.txt"
    stale = [jitwarm.Entry(e.module, e.name, 99.0, e.caller, e.sig) for e in rows]
    write_table(stale, path)
    before = jitwarm.SIGNATURES.read_bytes()
    said: list[str] = []
    timed = retime(path, progress=said.append)
    back = jitwarm.load_table(path)
    assert back == timed
    # same rows in the same order, only the seconds new: each a real compile (a cached
    # kernel would load in milliseconds; the child's cache is a new empty folder)
    assert [(e.key, e.caller, e.sig) for e in back] == [(e.key, e.caller, e.sig) for e in rows]
    assert all(0.01 < e.seconds < 30.0 for e in back), back
    assert len(said) == 2 and "3 rows" in said[0]
    assert jitwarm.SIGNATURES.read_bytes() == before  # the package's table untouched
    assert path.read_text().startswith("# module\tfunction\tCPU s")


def test_merge_keeps_the_old_rows_first_and_adds_only_new_ones():
    a, b, c = _rows()
    again = jitwarm.Entry(a.module, a.name, 5.0, "x.y", a.sig)  # same kernel and types
    other = jitwarm.Entry(a.module, a.name, 1.0, "-", "(int64,)")  # another specialisation
    merged = _merge([a, b], [c, again, other, c])
    assert merged == [a, b, c, other]


def test_record_and_retime_are_reached_through_jitwarm(monkeypatch):
    import subprocess
    import sys

    calls = []
    monkeypatch.setattr(subprocess, "call", lambda cmd: calls.append(cmd) or 0)
    assert jitwarm.main(["record", "--", "plan", "paper"]) == 0
    assert jitwarm.main(["retime"]) == 0
    module = [sys.executable, "-m", "mawdo.jit.record"]
    assert calls == [[*module, "record", "--", "plan", "paper"], [*module, "retime"]]


def test_the_command_line_runs_record_then_retime(monkeypatch):
    import mawdo.jit.record as jr

    calls = []
    monkeypatch.setattr(jr, "record", lambda argv, path=None: calls.append(("record", argv)))
    monkeypatch.setattr(jr, "retime", lambda path=None: calls.append(("retime",)))
    assert jr.main(["record", "--", "plan", "paper"]) == 0
    assert jr.main(["retime"]) == 0
    assert calls == [("record", ["plan", "paper"]), ("retime",), ("retime",)]
