"""The README's Command line section, run top to bottom as a new user would.

Every command of the section's ``bash`` block is run through the real CLI in a fresh folder, in
the README's order (a report reads the store that the command before it wrote). The long ones run
in a small form: :data:`SMALL` lists each change, and the test fails when a README command is
not what the table expects, so an edit of the README cannot silently escape the test.
"""

from __future__ import annotations

import os
import re
import shlex
import subprocess
import sys
from pathlib import Path

import pytest

README = Path(__file__).resolve().parents[1] / "README.md"

# README command (as written, comments stripped) -> the same command in a small form: fewer runs,
# iterations, scenes or functions; every flag the README shows is kept.
SMALL = {
    "--runs 30 --seed 0 --iters 500 --pop 50": "--runs 2 --seed 0 --iters 20 --pop 10",
    "paper-table3 --out results/t3.db": "paper-table3 --set runs=2 --set max_iter=20 "
    "--set functions=F1,F7 --out results/t3.db",
    "--out report/ [--quick]": "--out report/ --quick",
}


def readme_commands(text: str) -> list[str]:
    """The ``mawdo`` commands of the README's Command line block, continuation lines joined."""
    section = text.split("## Command line", 1)[1]
    block = section.split("```bash", 1)[1].split("```", 1)[0]
    joined = re.sub(r"\\\n\s*", "", block)
    lines = [re.sub(r"\s+#.*$", "", line).strip() for line in joined.splitlines()]
    return [" ".join(line.split()) for line in lines if line.startswith("mawdo ")]


def small_form(command: str) -> str:
    for long, short in SMALL.items():
        command = command.replace(long, short)
    return command


def test_the_block_is_read_and_every_long_command_has_a_small_form():
    commands = readme_commands(README.read_text("utf-8"))
    assert commands[0] == "mawdo list" and len(commands) >= 7
    joined = "\n".join(commands)
    unused = [long for long in SMALL if long not in joined]
    assert not unused, f"README commands changed; update SMALL for: {unused}"
    for c in map(small_form, commands):
        assert "[" not in c and "--runs 30" not in c, c


@pytest.mark.slow
def test_every_readme_command_exits_0_in_its_small_form(tmp_path):
    env = {**os.environ, "MPLBACKEND": "Agg"}
    for command in map(small_form, readme_commands(README.read_text("utf-8"))):
        argv = [sys.executable, "-m", "mawdo.cli", *shlex.split(command)[1:]]
        done = subprocess.run(argv, cwd=tmp_path, env=env, capture_output=True, text=True)
        assert done.returncode == 0, f"{command}\n{done.stdout[-2000:]}\n{done.stderr[-2000:]}"
    assert (tmp_path / "report" / "report.md").is_file()
    assert (tmp_path / "report" / "t3" / "report.md").is_file()
