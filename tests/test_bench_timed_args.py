"""``benchmarks/bench_timed.py --latency``'s scene, planner and thread choices: a value it does
not know is refused before anything is timed, naming the choices."""

import subprocess
import sys
from pathlib import Path

import pytest

SCRIPT = Path(__file__).resolve().parents[1] / "benchmarks" / "bench_timed.py"


def _refused(option, value):
    """The script run with ``--latency option value``: exit 2 with a usage error, before the
    warm-up runs print the load."""
    proc = subprocess.run(
        [sys.executable, str(SCRIPT), "--latency", option, value],
        capture_output=True,
        text=True,
        timeout=60,
    )
    assert proc.returncode == 2
    assert "Traceback" not in proc.stderr
    assert proc.stdout == ""
    return proc


@pytest.mark.parametrize(
    ("option", "value", "choices"),
    [
        ("--cases", "paper,krowd", "paper, crowd"),
        ("--latency-planners", "mawdo_time,woa", "mawdo, mawdo_time"),
    ],
)
def test_unknown_case_or_planner_is_refused(option, value, choices):
    bad = value.split(",")[1]
    proc = _refused(option, value)
    assert f"unknown {bad!r}: choose from {choices}" in proc.stderr


@pytest.mark.parametrize("value", ["1,x", "0", "2,-1", ""])
def test_a_bad_thread_count_is_refused(value):
    proc = _refused("--threads", value)
    assert f"--threads {value!r}: give thread counts >= 1, like 1,2" in proc.stderr
