"""``benchmarks/bench_timed.py --latency``'s scene and planner choices: a name it does not know
is refused before anything is timed, naming the choices."""

import subprocess
import sys
from pathlib import Path

import pytest

SCRIPT = Path(__file__).resolve().parents[1] / "benchmarks" / "bench_timed.py"


@pytest.mark.parametrize(
    ("option", "value", "choices"),
    [
        ("--cases", "paper,krowd", "paper, crowd"),
        ("--latency-planners", "mawdo_time,woa", "mawdo, mawdo_time"),
    ],
)
def test_unknown_case_or_planner_is_refused(option, value, choices):
    bad = value.split(",")[1]
    proc = subprocess.run(
        [sys.executable, str(SCRIPT), "--latency", option, value],
        capture_output=True,
        text=True,
        timeout=60,
    )
    assert proc.returncode == 2
    assert f"unknown {bad!r}: choose from {choices}" in proc.stderr
    assert "Traceback" not in proc.stderr
    assert proc.stdout == ""  # refused before the warm-up runs print the load
