"""``mawdo study run/report/presets``: one command group for every registered study kind, and the
older per-kind commands as aliases that say so in one line (issue 26, item 3).

Through the real command in a subprocess, except the throw-away ``coin`` kind: it is registered
in this test process, so the Typer app is called in-process for it.
"""

from __future__ import annotations

import dataclasses
import json
import re
from pathlib import Path
from typing import Any, ClassVar, Literal

import numpy as np
import pytest
from pydantic import Field
from typer.testing import CliRunner

from mawdo.cli.study import ALIAS_RELEASE
from mawdo.experiments import (
    STUDY_KINDS,
    PlanError,
    RunRow,
    Store,
    StudyKind,
    StudyPlanBase,
    Task,
    column,
    register_kind,
)
from mawdo.experiments.protocol import find_preset, load_plan_file
from mawdo.streams import name_word, seed_word

from .cli_run import mawdo

NOTE = re.compile(
    r"^note: '(mawdo [a-z ]+)' is now '(mawdo study [a-z]+)'; this alias goes in "
    + re.escape(ALIAS_RELEASE)
    + "$"
)
TINY_BENCH = ("--set", "algorithms=gwo", "--set", "functions=sphere,rastrigin", "--set", "runs=2",
              "--set", "max_iter=5")  # fmt: skip
TINY_SUITE = ("--set", "algorithms=random", "--set", "functions=1", "--set", "instances=1",
              "--set", "dims=2,3", "--set", "budget=20", "--set", "runs=2")  # fmt: skip


def notes(stderr: str) -> list[tuple[str, str]]:
    """The alias notes of a command's stderr, as (old, new) pairs."""
    return [m.groups() for line in stderr.splitlines() if (m := NOTE.match(line))]


def stored(db: Path, *fields: str) -> dict[tuple, tuple]:
    """``(algorithm, problem, run) -> (field values)`` of a store (arrays as tuples)."""
    out = {}
    with Store.read(db) as store:
        for a, p, r in store.rows():
            vals = [getattr(r, f) for f in fields]
            out[a, p, r.run] = tuple(tuple(np.ravel(v)) if isinstance(v, np.ndarray) else v
                                     for v in vals)  # fmt: skip
    return out


def stored_rows(db: Path, problem: str) -> list:
    with Store.read(db) as store:
        return [r for _, p, r in store.rows() if p == problem]


# ---------------------------------------------------------------------- presets
def test_presets_lists_every_kinds_presets_with_their_runs():
    res = mawdo("study", "presets")
    assert res.returncode == 0, res.stderr
    for kind in ("benchmark", "planning", "suite", "arena"):
        assert f"{kind}: {STUDY_KINDS[kind].description}" in res.stdout
        for name in STUDY_KINDS[kind].presets:
            assert re.search(rf"^  {re.escape(name)} ", res.stdout, re.M), name
    # counted by hand: smoke is 4 algorithms x 3 functions x 4 runs; study-smoke 3 algorithms
    # x 2 runs + the one deterministic oracle run
    line = {ln.split()[0]: ln for ln in res.stdout.splitlines() if ln.startswith("  ")}
    assert line["smoke"].endswith("(48 runs)") and line["study-smoke"].endswith("(7 runs)")


def test_preset_names_are_unique_across_kinds():
    plan = STUDY_KINDS["benchmark"].plan
    twin = StudyKind("benchmark_twin", type("Twin", (plan,), {"study_kind": "benchmark_twin"}),
                     STUDY_KINDS["benchmark"].execute, STUDY_KINDS["benchmark"].row,
                     presets={"smoke": {}})  # fmt: skip
    with pytest.raises(ValueError, match="preset 'smoke' is already a preset of the 'benchmark'"):
        register_kind(twin)
    assert "benchmark_twin" not in STUDY_KINDS


def test_a_plan_file_finds_its_kind_by_preset_kind_or_fields(tmp_path):
    (tmp_path / "a.toml").write_text('preset = "study-smoke"\nruns = 1\n')
    (tmp_path / "b.toml").write_text('suite = "bbob"\nalgorithms = ["random"]\nfunctions = [1]\n')
    (tmp_path / "c.toml").write_text('kind = "arena"\nfamilies = ["forest"]\nn = 2\n')
    a, b, c = (load_plan_file(tmp_path / f"{x}.toml") for x in "abc")
    assert (a.kind, a.runs, a.algorithms) == ("planning", 1, find_preset("study-smoke").algorithms)
    assert (b.kind, b.functions, c.kind, c.n) == ("suite", (1,), "arena", 2)
    (tmp_path / "d.toml").write_text('preset = "smoke"\nkind = "arena"\n')
    with pytest.raises(PlanError, match="d.toml: kind: must be one of 'benchmark' .got 'arena'"):
        load_plan_file(tmp_path / "d.toml")


# ---------------------------------------------------------------------- run, resume, report
def run_tiny_bench(cwd: Path, out: str = "new.db"):
    return mawdo("study", "run", "smoke", *TINY_BENCH, "--out", out, "--no-progress", cwd=cwd)


def test_run_resume_and_report_a_benchmark_preset(tmp_path):
    run = run_tiny_bench(tmp_path)
    assert run.returncode == 0, run.stderr
    assert "complete: 4 runs computed" in run.stdout and notes(run.stderr) == []
    with Store.read(tmp_path / "new.db") as store:
        plan = store.plan
        assert store.count() == 4
    assert (plan.algorithms, plan.functions, plan.runs, plan.max_iter, plan.pop_size) == (
        ("gwo",), ("sphere", "rastrigin"), 2, 5, 10,  # pop 10: the smoke preset's, kept
    )  # fmt: skip
    again = run_tiny_bench(tmp_path)
    assert "0 runs computed" in again.stdout and "4 already stored" in again.stdout
    rep = mawdo("study", "report", "new.db", "--out", "rep", "--option", "plots=false",
                cwd=tmp_path)  # fmt: skip
    assert rep.returncode == 0, rep.stderr
    assert rep.stdout.strip() == f"report: {Path('rep') / 'report.md'}"
    # issue 28: what a report spends its seconds on is said on stderr, with how long it took
    assert "writing the report of the benchmark study ..." in rep.stderr
    assert "writing the report of the benchmark study: done in " in rep.stderr
    table = (tmp_path / "rep" / "results_raw.csv").read_text().splitlines()
    sphere = [r.fun for r in stored_rows(tmp_path / "new.db", "sphere")]
    assert f"F1,Ave,{float(np.mean(sphere))!r}" in table  # F1 is sphere: mean of stored runs
    bad = mawdo("study", "report", "new.db", "--out", "r2", "--option", "plotz=false",
                cwd=tmp_path)  # fmt: skip
    assert bad.returncode == 2 and "plotz" in bad.stderr and "plots, svg, reference" in bad.stderr


@pytest.mark.slow
def test_run_and_report_a_suite_study_of_two_stores(tmp_path):
    for dims in ("2", "3"):
        res = mawdo("study", "run", "bbob-quick", *TINY_SUITE, "--set", f"dims={dims}",
                    "--out", f"d{dims}.db", "--no-progress", cwd=tmp_path)  # fmt: skip
        assert res.returncode == 0, res.stderr
        assert "complete: 2 runs computed" in res.stdout
    with Store.read(tmp_path / "d3.db") as store:
        assert (store.plan.kind, store.plan.dims, store.plan.budget) == ("suite", (3,), 20.0)
        assert {r.nfev for _, _, r in store.rows()} == {60}  # ceil(20 x D) evaluations
    rep = mawdo("study", "report", "d2.db", "d3.db", "--out", "rep", "--option", "plots=false",
                cwd=tmp_path)  # fmt: skip
    assert rep.returncode == 0, rep.stderr
    assert {p.name for p in (tmp_path / "rep").glob("art_d*.csv")} == {"art_d2.csv", "art_d3.csv"}
    mixed = mawdo("bench", "run", "--preset", "smoke", *("--algorithms", "gwo", "--functions",
                  "sphere", "--runs", "1", "--iters", "2", "--out", "b.db", "--no-progress"),
                  cwd=tmp_path)  # fmt: skip
    assert mixed.returncode == 0, mixed.stderr
    both = mawdo("study", "report", "d2.db", "b.db", "--out", "r2", cwd=tmp_path)
    assert both.returncode == 2 and "these hold benchmark, suite" in both.stderr


# ---------------------------------------------------------------------- bad input
@pytest.mark.parametrize(
    "args, words",
    [
        (("run", "smok", "--out", "x.db"), ["unknown preset 'smok'", "Did you mean 'smoke'"]),
        (("run", "smoke", "--set", "runz=2", "--out", "x.db"), ["runz", "Did you mean 'runs'"]),
        (("run", "smoke", "--set", "runs", "--out", "x.db"), ["--set 'runs'", "key=value"]),
        (("run", "smoke", "--set", "runs=0", "--out", "x.db"), ["runs: must be >= 1"]),
        (("run", "nope.toml", "--out", "x.db"), ["plan file nope.toml does not exist"]),
        (("run", "smoke", "--workers", "0", "--out", "x.db"), ["Invalid value for '--workers'"]),
    ],
)
def test_bad_input_is_one_error_line_and_exit_2(tmp_path, args, words):
    res = mawdo("study", *args, cwd=tmp_path)
    assert res.returncode == 2, res.stderr
    assert res.stderr.startswith("error: ") and res.stdout == ""
    assert "╭" not in res.stderr and "Traceback" not in res.stderr
    for w in words:
        assert w in res.stderr, res.stderr
    assert not (tmp_path / "x.db").exists()


def test_old_arena_command_prints_errors_on_stderr(tmp_path):
    res = mawdo("plan", "bench", "--suite", "crosing", "--out", "x.db", cwd=tmp_path)
    assert res.returncode == 2 and res.stdout == ""
    assert notes(res.stderr) == [("mawdo plan bench", "mawdo study run")]
    assert "error: families" in res.stderr and "Did you mean 'crossing'" in res.stderr


def test_old_presets_alias_still_lists_its_presets():
    res = mawdo("bench", "presets")
    assert res.returncode == 0 and notes(res.stderr) == [
        ("mawdo bench presets", "mawdo study presets")
    ]
    for name in (*STUDY_KINDS["benchmark"].presets, *STUDY_KINDS["suite"].presets):
        assert re.search(rf"^{re.escape(name)} ", res.stdout, re.M), name


# ---------------------------------------------------------------------- old commands (slow)
ALIASES = {
    "benchmark": (
        ("smoke", *TINY_BENCH),
        ("bench", "run", "--preset", "smoke", "--algorithms", "gwo", "--functions",
         "sphere,rastrigin", "--runs", "2", "--iters", "5"),
        ("fun", "nfev", "curve", "seed_entropy"), 4,
        ("plots=false", ("bench", "report", "old.db", "--no-plots")),
    ),
    "planning": (
        ("study-quick", "--set", "algorithms=oracle_follower", "--set", "runs=1"),
        ("plan", "study", "--preset", "study-quick", "--algorithms", "oracle_follower",
         "--runs", "1"),
        ("seed", "first_plan_curve", "plan_dim"), 1,  # the route: an npz with its times
        ("gif=false", ("plan", "report", "old.db", "--no-gif")),
    ),
    "arena": (
        ("arena-quick", "--set", "n=1", "--set", "algorithms="),
        ("plan", "bench", "--suite", "arena-quick", "--n", "1", "--algorithms", ""),
        ("scene_hash", "status", "success", "length", "gap", "planner_seed"), 6,
        ("figures=false", ("plan", "bench", "report", "old.db", "--no-figures")),
    ),
}  # fmt: skip


@pytest.mark.slow
@pytest.mark.parametrize("kind", list(ALIASES))
def test_each_old_command_says_where_it_went_and_stores_what_study_run_does(tmp_path, kind):
    new_args, old_args, fields, n_rows, (option, old_report) = ALIASES[kind]
    flags = ("--no-progress", "--out")
    new = mawdo("study", "run", *new_args, *flags, "new.db", cwd=tmp_path)
    old = mawdo(*old_args, *flags, "old.db", cwd=tmp_path)
    assert new.returncode == 0 and old.returncode == 0, new.stderr + old.stderr
    old_name = " ".join(old_args[:2])
    assert notes(old.stderr) == [(f"mawdo {old_name}", "mawdo study run")]
    assert sum(ln.startswith("note:") for ln in old.stderr.splitlines()) == 1
    with Store.read(tmp_path / "new.db") as a, Store.read(tmp_path / "old.db") as b:
        assert a.plan.plan_hash == b.plan.plan_hash
    rows = stored(tmp_path / "new.db", *fields)
    assert len(rows) == n_rows and stored(tmp_path / "old.db", *fields) == rows
    rep = mawdo("study", "report", "new.db", "--out", "rep", "--option", option, cwd=tmp_path)
    old_rep = mawdo(*old_report, "--out", "rep_old", cwd=tmp_path)
    assert rep.returncode == 0 and old_rep.returncode == 0, rep.stderr + old_rep.stderr
    assert notes(old_rep.stderr) == [(f"mawdo {' '.join(old_report[:-2])}", "mawdo study report")]
    tables = sorted(p.name for p in (tmp_path / "rep_old").glob("*.csv"))
    assert tables and tables == sorted(p.name for p in (tmp_path / "rep").glob("*.csv"))


# ---------------------------------------------------------------------- a throw-away kind
class CoinPlan(StudyPlanBase):
    """Each run tosses ``tosses`` coins; ``algorithms`` are labels."""

    study_kind: ClassVar[str] = "coin"
    kind: Literal["coin"] = "coin"
    algorithms: tuple[str, ...] = ("fair",)
    tosses: int = Field(10, ge=1)
    runs: int = Field(3, ge=1)
    seed: int = 11

    @property
    def total_runs(self) -> int:
        return len(self.algorithms) * self.runs

    def tasks(self, done=()) -> list[Task]:
        return [Task(a, "coin", k, 1) for a in self.algorithms for k in range(self.runs)
                if (a, "coin", k) not in set(done)]  # fmt: skip

    def task_spec(self, task: Task) -> dict[str, Any]:
        seeds = [seed_word([self.seed, name_word(task.algorithm), k]) for k in task.runs]
        return {"kind": self.kind, **task.key(), "tosses": self.tosses, "seeds": seeds}

    def describe(self) -> str:
        return f"{self.name}: {len(self.algorithms)} coins x {self.runs} runs"


@dataclasses.dataclass(frozen=True)
class CoinRow(RunRow):
    heads: int | None = column("int")


def heads(seed: int, tosses: int) -> int:
    return int(np.random.default_rng(seed).integers(0, 2, tosses).sum())


def execute_coin(spec: dict[str, Any]) -> list[CoinRow]:
    return [CoinRow(run=spec["first_run"] + i, wall_time=0.0, heads=heads(s, spec["tosses"]))
            for i, s in enumerate(spec["seeds"])]  # fmt: skip


def report_coin(store_path, out_dir, *, label: str = "heads") -> Path:
    with Store.read(store_path) as store:
        total = sum(r.heads for _, _, r in store.rows())
    path = Path(out_dir) / "coin.json"
    path.write_text(json.dumps({label: total}))
    return path


register_kind(StudyKind("coin", CoinPlan, execute_coin, CoinRow, report=report_coin,
                        description="coin tosses (test only)",
                        presets={"coin-quick": {"name": "coin-quick", "runs": 2}}))  # fmt: skip


def test_a_kind_registered_outside_the_package_is_served_without_cli_changes(tmp_path):
    from mawdo.cli import app

    cli = CliRunner()
    listing = cli.invoke(app, ["study", "presets"])
    assert listing.exit_code == 0 and "coin: coin tosses (test only)" in listing.stdout
    assert "coin-quick" in listing.stdout and "coin-quick: 1 coins x 2 runs" in listing.stdout
    db = tmp_path / "c.db"
    run = ["study", "run", "coin-quick", "--set", "tosses=50", "--out", str(db), "--no-progress"]
    first = cli.invoke(app, run)
    assert first.exit_code == 0, first.output
    assert "complete: 2 runs computed" in first.stdout
    assert "0 runs computed" in cli.invoke(app, run).stdout
    rep = cli.invoke(app, ["study", "report", str(db), "--out", str(tmp_path / "r"),
                           "--option", "label=up"])  # fmt: skip
    assert rep.exit_code == 0, rep.output
    expected = sum(heads(seed_word([11, name_word("fair"), k]), 50) for k in range(2))
    assert json.loads((tmp_path / "r" / "coin.json").read_text()) == {"up": expected}
