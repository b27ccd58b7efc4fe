"""`mawdo reproduce` on a tiny budget: every part runs, one report gathers them, resume works."""

import re

from typer.testing import CliRunner

from mawdo.cli import app
from mawdo.reproduce import reproduce

TINY = {
    "runs": 2,
    "max_iter": 8,
    "pop_size": 8,
    "functions": ["sphere", "six_hump_camel"],
    "name": "tiny",
}


def test_reproduce_gathers_every_part_and_resumes(tmp_path):
    said = []
    path = reproduce(
        tmp_path,
        workers=1,
        progress=False,
        say=said.append,
        bench_overrides=TINY,
        study="study-smoke",
    )
    text = path.read_text()
    for title in (
        "Benchmark functions (paper Table 3)",
        "Shifted suite",
        "Ablation (paper Table 5)",
        "Path planning (paper Table 6)",
    ):
        assert f"## {title}" in text
    # every image the gathered report links exists (links are re-rooted to the part folders)
    for link in re.findall(r"!\[[^\]]*\]\(([^)]+)\)", text):
        assert (tmp_path / link).is_file(), link
    assert (tmp_path / "paper-table6" / "table6.csv").is_file()
    # the preamble says what was run, from the plans: a tiny budget is not the paper's protocol
    assert "tiny: 2 runs x 8 iterations, pop 8; not the paper's protocol:" in text
    assert "runs 2 (paper 30)" in text and "shifted suite, ours" in text
    assert "study-smoke: 2 planning runs per algorithm" in text
    assert "the planner is not the paper's: first plan 80 particles x 60 iterations" in text
    assert "the paper's protocol (30 runs" not in text and "SPEC" not in text
    # a second call computes nothing
    said.clear()
    reproduce(
        tmp_path,
        workers=1,
        progress=False,
        say=said.append,
        bench_overrides=TINY,
        study="study-smoke",
    )
    done = [s for s in said if s.strip().startswith(("complete", "partial"))]
    assert len(done) == 4 and all("0 runs computed" in s for s in done)


def test_cli_lists_and_rejects_clearly():
    r = CliRunner().invoke(app, ["list", "algorithms"])
    assert r.exit_code == 0 and "MEWDO (reconstructed)" in r.output
    r = CliRunner().invoke(app, ["optimize", "F1", "-a", "mawod", "--runs", "2", "--iters", "3"])
    assert r.exit_code == 2 and "Did you mean 'mawdo'" in r.output
    r = CliRunner().invoke(
        app, ["optimize", "F1", "-a", "gwo", "--runs", "3", "--iters", "20", "--no-progress"]
    )
    assert r.exit_code == 0 and "GWO" in r.output and "Ave" in r.output
    r = CliRunner().invoke(app, ["plan", "papr"])
    assert r.exit_code == 2 and "paper" in r.output
