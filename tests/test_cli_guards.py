"""Issue 12 through the real command (``python -m mawdo.cli`` in a subprocess): each case ends
in a message on stderr and a non-zero exit code, and nothing stored is lost or changed."""

from __future__ import annotations

import json
import os
import signal
import sqlite3
import subprocess
import sys
import time
import tomllib
from pathlib import Path

import pytest

from tests.cli_run import ENV, mawdo

PAPER_TOML = Path(__file__).parents[1] / "src" / "mawdo" / "planning" / "data" / "paper.toml"


def start(*args: str, cwd=None) -> subprocess.Popen:
    return subprocess.Popen(
        [sys.executable, "-m", "mawdo.cli", *args],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        env=ENV,
        cwd=cwd,
    )


def assert_refused(res: subprocess.CompletedProcess, *words: str) -> None:
    assert res.returncode != 0, res.stdout
    assert "Traceback" not in res.stdout + res.stderr, res.stderr
    assert "│" not in res.stderr and "╭" not in res.stderr, res.stderr  # plain lines, no panel
    text = " ".join(res.stderr.split())  # a plan's several errors come on several lines
    for w in words:
        assert w in text, res.stderr


def rows(db: Path) -> list[tuple]:
    conn = sqlite3.connect(f"{db.resolve().as_uri()}?mode=ro", uri=True)
    try:
        return conn.execute(
            "SELECT plan_hash, algorithm, problem, run FROM runs ORDER BY 2, 3, 4"
        ).fetchall()
    finally:
        conn.close()


def meta_hash(db: Path) -> str:
    conn = sqlite3.connect(f"{db.resolve().as_uri()}?mode=ro", uri=True)
    try:
        return conn.execute("SELECT plan_hash FROM meta").fetchone()[0]
    finally:
        conn.close()


def smoke_store(tmp_path: Path) -> Path:
    res = mawdo("bench", "run", "--preset", "smoke", "--out", "s.db", "--no-progress", cwd=tmp_path)
    assert res.returncode == 0, res.stderr
    return tmp_path / "s.db"


# ------------------------------------------------------------------ defect 1: two writers
def wait_for(cond, timeout: float = 60.0) -> None:
    t0 = time.monotonic()
    while not cond():
        assert time.monotonic() - t0 < timeout, "timed out"
        time.sleep(0.05)


@pytest.mark.slow
def test_two_concurrent_writers_one_refused_rows_of_one_plan(tmp_path):
    db = tmp_path / "cg.db"
    first = start(
        "bench", "run", "--preset", "smoke", "--iters", "600", "--batch-size", "1",
        "--out", "cg.db", "--no-progress", cwd=tmp_path,
    )  # fmt: skip
    try:
        wait_for(lambda: (tmp_path / "cg.db.lock").exists() and first.poll() is None)
        # held while the second tries, however fast the machine: the first cannot finish
        # (and release its lock) while it is stopped
        os.kill(first.pid, signal.SIGSTOP)
        try:
            second = mawdo(
                "bench", "run", "--preset", "smoke", "--iters", "20", "--batch-size", "1",
                "--out", "cg.db", "--force", "--no-progress", cwd=tmp_path,
            )  # fmt: skip
            still_running = first.poll() is None
        finally:
            os.kill(first.pid, signal.SIGCONT)
        out, err = first.communicate(timeout=300)
    finally:
        if first.poll() is None:
            first.kill()
    assert still_running, "the first run ended before the second started; test is void"
    assert_refused(second, "being written by another process", f"pid {first.pid}", "command:")
    assert first.returncode == 0, err
    assert "complete" in out and "48/48" in out
    stored = rows(db)
    assert len(stored) == 48
    assert {h for h, *_ in stored} == {meta_hash(db)}
    resumed = mawdo(
        "bench", "run", "--preset", "smoke", "--iters", "600", "--batch-size", "1",
        "--out", "cg.db", "--no-progress", cwd=tmp_path,
    )  # fmt: skip
    assert "0 runs computed" in resumed.stdout and "48 already stored" in resumed.stdout
    conn = sqlite3.connect(db)
    nfev = [n for (n,) in conn.execute("SELECT nfev FROM runs")]
    conn.close()
    # every run has the first run's 600 iterations of pop 10, none the intruder's 20
    assert min(nfev) >= 10 * 600, sorted(set(nfev))
    report = mawdo("bench", "report", "cg.db", "--out", "rep", "--no-plots", cwd=tmp_path)
    assert report.returncode == 0, report.stderr


# ------------------------------------------------------------------ defects 2, 10: scenarios
def _edited_paper(tmp_path: Path, name: str) -> tuple[Path, dict]:
    text = PAPER_TOML.read_text()
    start = tomllib.loads(text)["start"]
    new_start = [start[0] + 7.0, start[1] + 3.0]
    text = text.replace('name = "paper"', f'name = "{name}"', 1)
    text = text.replace(f"start = [{start[0]}, {start[1]}]", f"start = {new_start}", 1)
    path = tmp_path / f"{name}-edited.toml"
    path.write_text(text)
    edited = tomllib.loads(path.read_text())
    assert edited["start"] == new_start and edited["name"] == name
    return path, edited


@pytest.mark.parametrize("name", ["paper", "mymap"])
def test_study_scenario_file_is_stored_and_run_as_edited(tmp_path, name):
    from mawdo.experiments import Store
    from mawdo.planning.run.planner import result_from_bytes

    scen, edited = _edited_paper(tmp_path, name)
    res = mawdo(
        "plan", "study", "--preset", "study-smoke", "--algorithms", "gwo", "--runs", "1",
        "--scenario", str(scen), "--out", "st.db", "--no-progress", cwd=tmp_path,
    )  # fmt: skip
    assert res.returncode == 0, res.stderr
    scen.unlink()  # the store must not need the file any more
    with Store.read(tmp_path / "st.db") as store:
        assert store.plan.scenario == name
        assert store.plan.scenario_spec["start"] == edited["start"]
        ((algo, problem, row),) = store.rows()
        route = result_from_bytes(row.route, store.plan.scenario_object())
    assert (algo, problem) == ("gwo", name)
    # the executed route starts where the edited file puts the robot, not the built-in map
    assert route.route[0].tolist() == pytest.approx(edited["start"])


def test_a_crafted_store_cannot_point_report_at_a_file(tmp_path):
    res = mawdo(
        "plan", "study", "--preset", "study-smoke", "--algorithms", "gwo", "--runs", "1",
        "--out", "st.db", "--no-progress", cwd=tmp_path,
    )  # fmt: skip
    assert res.returncode == 0, res.stderr
    db = tmp_path / "st.db"
    # a valid scenario file elsewhere: were it looked up, the report would succeed with it
    elsewhere = tmp_path / "elsewhere.toml"
    elsewhere.write_text(PAPER_TOML.read_text())
    conn = sqlite3.connect(db)
    plan = json.loads(conn.execute("SELECT plan_json FROM meta").fetchone()[0])
    plan.pop("scenario_spec")
    plan.pop("scenario_sha256")
    plan["scenario"] = str(elsewhere)
    with conn:
        conn.execute("UPDATE meta SET plan_json = ?", (json.dumps(plan),))
    conn.close()
    before = db.read_bytes()
    rep = mawdo("plan", "report", "st.db", "--out", "rep", "--no-gif", cwd=tmp_path)
    assert_refused(rep, "no scenario contents", "never refer to files")
    assert db.read_bytes() == before
    assert not (tmp_path / "rep" / "report.md").exists()


# ------------------------------------------------------------------ defects 5, 6, 8
def _overwrite_middle(db: Path, size: int = 8192) -> bytes:
    data = bytearray(db.read_bytes())
    mid = len(data) // 2
    data[mid : mid + size] = bytes(range(256)) * (size // 256)
    db.write_bytes(bytes(data))
    return bytes(data)


def test_a_corrupted_store_is_refused_by_run_and_report(tmp_path):
    db = smoke_store(tmp_path)
    damaged = _overwrite_middle(db)
    run = mawdo("bench", "run", "--preset", "smoke", "--out", "s.db", "--no-progress", cwd=tmp_path)
    assert_refused(run, "corrupt", "Recover")
    assert "complete" not in run.stdout
    rep = mawdo("bench", "report", "s.db", "--out", "rep", cwd=tmp_path)
    assert_refused(rep, "corrupt", "Recover")
    assert db.read_bytes() == damaged


def test_report_out_on_an_unwritable_path_is_refused_first(tmp_path):
    db = smoke_store(tmp_path)
    before = db.read_bytes()
    (tmp_path / "afile").write_text("x")
    for out in ("/proc/nope/rep", "afile/rep", "afile"):
        rep = mawdo("bench", "report", "s.db", "--out", out, cwd=tmp_path)
        assert_refused(rep, out)
    assert db.read_bytes() == before


def test_a_refused_run_leaves_a_clean_store_that_reads_read_only(tmp_path):
    db = smoke_store(tmp_path)
    before = db.read_bytes()
    run = mawdo(
        "bench", "run", "--preset", "smoke", "--iters", "20", "--out", "s.db", "--no-progress",
        cwd=tmp_path,
    )  # fmt: skip
    assert_refused(run, "another plan", "--force")
    assert db.read_bytes() == before
    assert before[18:20] == b"\x01\x01"  # rollback journal, not WAL
    assert sorted(p.name for p in tmp_path.iterdir()) == ["s.db"]
    db.chmod(0o444)
    rep = mawdo("bench", "report", "s.db", "--out", "rep", "--no-plots", cwd=tmp_path)
    assert rep.returncode == 0, rep.stderr


@pytest.mark.parametrize(
    "args, words",
    [
        (("optimize", "nosuchfunction", "--runs", "2", "--iters", "5"), ["nosuchfunction"]),
        (("optimize", "sphere", "-a", "nosuchalgo", "--iters", "5"), ["nosuchalgo"]),
        (("plan", "study", "--algorithms", "nosuchalgo", "--out", "x.db"), ["nosuchalgo"]),
        (("plan", "study", "--scenario", "missing.toml", "--out", "x.db"), ["missing.toml"]),
        (("plan", "missing.toml"), ["missing.toml"]),
        (("plan", "report", "missing.db"), ["missing.db"]),
        (("plan", "paper", "--threads", "0"), ["--threads", "greater than or equal to 1"]),
    ],
)
def test_optimize_and_plan_errors_go_to_stderr(tmp_path, args, words):
    res = mawdo(*args, cwd=tmp_path)
    assert_refused(res, *words)
    assert "error" in res.stderr.lower()
    assert res.stdout.strip() == ""
    assert not (tmp_path / "x.db").exists()
    assert not (tmp_path / "out").exists()  # nothing created before the input was checked


# ------------------------------------------------------------------ defect 7: orphans
def _descendants(pid: int) -> set[int]:
    children: dict[int, list[int]] = {}
    for d in Path("/proc").iterdir():
        if not d.name.isdigit():
            continue
        try:
            stat = (d / "stat").read_text()
        except OSError:
            continue
        ppid = int(stat.rsplit(")", 1)[1].split()[1])
        children.setdefault(ppid, []).append(int(d.name))
    out, todo = set(), [pid]
    while todo:
        for c in children.get(todo.pop(), []):
            if c not in out:
                out.add(c)
                todo.append(c)
    return out


def _alive(pid: int) -> bool:
    try:
        stat = Path(f"/proc/{pid}/stat").read_text()
    except OSError:
        return False
    return stat.rsplit(")", 1)[1].split()[0] != "Z"


@pytest.mark.slow
@pytest.mark.skipif(not Path("/proc/self/stat").exists(), reason="needs /proc (Linux)")
def test_workers_exit_when_the_sweep_is_killed(tmp_path):
    proc = start(
        "bench", "run", "--preset", "smoke", "--iters", "3000", "--batch-size", "1",
        "--workers", "2", "--out", "k.db", "--no-progress", cwd=tmp_path,
    )  # fmt: skip
    try:
        # forkserver + 2 workers (+ the resource tracker) running
        wait_for(lambda: len(_descendants(proc.pid)) >= 3, timeout=120)
        time.sleep(1.0)
        family = _descendants(proc.pid)
        proc.send_signal(signal.SIGKILL)
        proc.wait(timeout=10)
        t0 = time.monotonic()
        while any(_alive(p) for p in family) and time.monotonic() - t0 < 10:
            time.sleep(0.1)
        left = [p for p in family if _alive(p)]
    finally:
        if proc.poll() is None:
            proc.kill()
        proc.stdout.close()
        proc.stderr.close()
    for p in left:  # clean up before failing, so no test leaves processes behind
        os.kill(p, signal.SIGKILL)
    assert not left, f"processes still running 10 s after kill -9 of their sweep: {left}"
