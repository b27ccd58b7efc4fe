"""The README image is the demo's figure: drawn by the demo's code path, from the demo's run.

``docs/img/snapshots_mawdo.png`` is a copy of what ``mawdo demo`` writes (``make readme-img``);
it stores its title and caption as PNG text. Issue 28: the committed image showed 486.4 px /
gap 1.016 / 2.92 rad while the demo drew 484.6 / 1.012 / 0.98, and the README caption said
"replans every step" of a run that keeps its plan on a third of its steps.
"""

from __future__ import annotations

import json
import re
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from mawdo.planning import render
from mawdo.planning.demo import FIGURE, DemoRun, figure_text, write_figure
from mawdo.planning.judge.metrics import run_metrics
from mawdo.planning.run.planner import plan

ROOT = Path(__file__).resolve().parents[2]
README_IMAGE = ROOT / "docs" / "img" / FIGURE
TITLE_NUMBERS = r"length ([\d.]+) px  \|  gap (?:L/L\* )?([\d.]+|n/a)  \|  smoothness ([\d.]+) rad"


def title_numbers(title: str) -> tuple[str, str, str]:
    """Length (px), gap and smoothness (rad) as printed in a snapshot grid's title."""
    found = re.search(TITLE_NUMBERS, title)
    assert found, f"no length / gap / smoothness in the title {title!r}"
    return found.groups()


def printed(metrics: dict) -> tuple[str, str, str]:
    """The metrics at the title's precision, formatted here, not by the figure code."""
    return (
        f"{metrics['length_px']:.1f}",
        f"{metrics['gap']:.3f}" if np.isfinite(metrics["gap"]) else "n/a",  # goal not reached
        f"{metrics['smoothness_rad']:.2f}",
    )


@pytest.fixture(scope="module")
def short_run():
    res = plan("paper", "mawdo", seed=0, config="quick", max_steps=30)
    return DemoRun(res, run_metrics(res))


def test_the_figure_stores_the_title_it_draws_and_the_run_numbers(short_run, tmp_path):
    out = write_figure(short_run, tmp_path / "demo.png")
    text = figure_text(out)
    assert text["Title"] == short_run.title
    assert text["Description"] == short_run.caption
    fig = render.snapshot_figure({"MAWDO": short_run.result}, metrics={"MAWDO": short_run.metrics})
    assert fig.subfigs[0].get_suptitle() == text["Title"]  # what is drawn is what is stored
    assert title_numbers(text["Title"]) == printed(short_run.metrics)
    m, res = short_run.metrics, short_run.result
    assert f"replans {len(res.replans) - 1} times" in text["Description"]
    assert f"on {m['holds']} of its {m['steps']} steps" in text["Description"]
    with pytest.raises(ValueError, match=r"must be a \.png"):
        write_figure(short_run, tmp_path / "demo.svg")


def test_readme_quotes_the_caption_stored_in_its_image():
    readme = (ROOT / "README.md").read_text(encoding="utf-8")
    assert f"]({README_IMAGE.relative_to(ROOT)})" in readme
    text = figure_text(README_IMAGE)
    assert text.get("Source") == "mawdo demo", "the README image was not written by mawdo demo"
    assert text["Description"] in readme
    assert "replans every step" not in readme


@pytest.mark.slow
def test_the_readme_image_is_what_mawdo_demo_draws_now(tmp_path):
    """Runs the demo command (about a minute warm) and compares its figure with the README's."""
    done = subprocess.run(
        [sys.executable, "-m", "mawdo.cli", "demo", "--out", str(tmp_path)],
        capture_output=True,
        text=True,
        timeout=1500,
    )
    assert done.returncode == 0, done.stderr
    now, committed = figure_text(tmp_path / FIGURE), figure_text(README_IMAGE)
    metrics = json.loads((tmp_path / "metrics.json").read_text())
    assert title_numbers(now["Title"]) == printed(metrics)  # the title is the run's
    assert title_numbers(committed["Title"]) == title_numbers(now["Title"]), (
        "docs/img/snapshots_mawdo.png is not the demo's figure any more: run `make readme-img`"
    )
    assert committed["Title"] == now["Title"]
    assert committed["Description"] == now["Description"]
    assert (
        metrics["holds"] + int(re.search(r"replans (\d+) times", now["Description"])[1]) + 1
        == (metrics["steps"])
    )  # every step either kept the plan or searched one (none waited or evaded)
