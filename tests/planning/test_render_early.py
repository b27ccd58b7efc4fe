"""Figures begun at a command's start (issue 28, item 2): the same pixels, errors said, Ctrl-C.

The snapshot grid laid out before the run (placeholder titles, static parts only) and filled
after it must be the grid a single pass draws; a panel drawn in two calls (what stands, then
what moves) the panel one call draws; and the process that does it early must hand back its
value or its error, end when the command stops, and stop with the command on Ctrl-C.
"""

from __future__ import annotations

import os
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest
from PIL import Image

from mawdo.planning import render
from mawdo.planning.guide.visgraph import component_labels
from mawdo.planning.render.early import EarlyFigures, run_figures
from mawdo.planning.render.snapshots import TIME_NOTE, GridFrame, grid_blocks, save_grid
from mawdo.planning.render.world import draw_world, move_world, moving_layers
from mawdo.planning.run.planner import plan
from tests.cli_run import children, ctrl_c, group_gone, interruptible

SRC = str(Path(__file__).resolve().parents[2] / "src")
ENV = {**os.environ, "PYTHONPATH": SRC, "PYTHONUNBUFFERED": "1"}


@pytest.fixture(scope="module")
def run():
    return plan("paper", "mawdo", seed=0, config="quick", max_steps=40)


def pixels(path) -> np.ndarray:
    with Image.open(path) as im:
        return np.asarray(im.convert("RGB"))


def assert_same_picture(a: np.ndarray, b: np.ndarray) -> None:
    """The same figure up to anti-aliasing: equal size, and at most 0.1 % of the values off by
    at most 3 levels (a figure drawn in a forked process, or laid out twice, now and then rounds a
    few edge pixels of text one level apart; a moved line, panel or label changes far more, far
    further)."""
    assert a.shape == b.shape
    diff = np.abs(a.astype(int) - b.astype(int))
    assert diff.max() <= 3, f"values differ by up to {diff.max()} levels"
    assert np.count_nonzero(diff) <= 1e-3 * diff.size, f"{np.count_nonzero(diff)} values differ"


def canvas(fig) -> np.ndarray:
    fig.canvas.draw()
    return np.asarray(fig.canvas.buffer_rgba())[..., :3].copy()


def test_a_panel_drawn_in_two_calls_is_the_panel_one_call_draws(run):
    from mawdo.planning.render.style import new_figure, optimum_path

    opt = optimum_path(run.scenario, {})
    images = []
    for parts in ([dict()], [dict(moving=False), dict(static=False)]):
        fig = new_figure((4, 4), 80, layout=None)
        ax = fig.add_subplot()
        for kw in parts:
            draw_world(ax, run.scenario, 20.0, result=run, optimum=opt, clear=False, **kw)
        images.append(canvas(fig))
    np.testing.assert_array_equal(images[0], images[1])
    assert (images[0] != 255).any(axis=-1).mean() > 0.05  # something was drawn


def test_what_moves_placed_on_layers_made_before_is_what_draw_world_adds(run):
    """The grid makes its moving artists before the run and places them after it: the panel
    must be the one drawn by adding them then, at any time, the same layers placed again."""
    from mawdo.planning.render.style import new_figure, optimum_path

    opt = optimum_path(run.scenario, {})
    end = float(run.route_times[-1])
    for times in ([0.0], [20.0], [end + 5.0], [30.0, 0.0], [0.0, 12.5, end]):
        images = []
        for placed in (False, True):
            fig = new_figure((4, 4), 80, layout=None)
            ax = fig.add_subplot()
            draw_world(ax, run.scenario, 0.0, optimum=opt, clear=False, moving=False)
            layers = moving_layers(ax, run.scenario) if placed else None
            for t in times:  # the last time is the one shown
                if placed:
                    move_world(ax, layers, run.scenario, t, run, opt)
                else:
                    draw_world(ax, run.scenario, t, run, opt, clear=False, static=False)
            images.append(canvas(fig))
        np.testing.assert_array_equal(images[0], images[1], err_msg=f"times {times}")


def test_layers_made_for_another_scenario_are_dropped_and_what_moves_drawn_anew(run):
    """A panel's layers that do not fit the scenario placed (other obstacles) must not hide
    an obstacle: move_world then draws as draw_world does, on this call and the next."""
    from mawdo.planning.render.style import new_figure, optimum_path
    from mawdo.planning.scenes import generate_scene

    other = generate_scene("forest", 0, seed=0).scenario
    opt = optimum_path(run.scenario, {})
    images = []
    for placed in (False, True):
        fig = new_figure((4, 4), 80, layout=None)
        ax = fig.add_subplot()
        draw_world(ax, run.scenario, 0.0, optimum=opt, clear=False, moving=False)
        layers = moving_layers(ax, other)
        for t in (30.0, 12.0):
            if placed:
                move_world(ax, layers, run.scenario, t, run, opt)
            else:
                draw_world(ax, run.scenario, t, run, opt, clear=False, static=False)
        images.append(canvas(fig))  # (the reference's other layers: hidden, or removed)
    np.testing.assert_array_equal(images[0], images[1])


@pytest.mark.parametrize("cols", [1, 2, 4])
def test_the_note_wrapped_once_laid_out_is_the_note_wrapped_at_each_draw(run, cols):
    frame = GridFrame([run.scenario], rows=1, cols=cols)
    note = frame.subfigs[-1].texts[-1]
    assert note.get_text().replace("\n", " ") == TIME_NOTE and not note.get_wrap()
    assert ("\n" in note.get_text()) == (cols < 3)  # narrow grids: several lines
    once = canvas(frame.fig)
    note.set_text(TIME_NOTE)  # as it was: wrapped by matplotlib at the draw
    note.set_wrap(True)
    np.testing.assert_array_equal(once, canvas(frame.fig))


def test_the_grid_set_up_before_the_run_is_the_grid_drawn_after_it(run, tmp_path):
    metrics = {"MAWDO": {"length_px": 512.25, "gap": 1.0625, "smoothness_rad": 1.5}}
    direct = render.snapshot_grid({"MAWDO": run}, tmp_path / "direct.png", metrics=metrics)
    frame = GridFrame([run.scenario])  # placeholder titles, no run yet
    blocks = grid_blocks([("MAWDO", run)], None, 8, metrics)
    early = save_grid(frame.fill(blocks), tmp_path / "early.png")
    assert_same_picture(pixels(direct), pixels(early))
    # a title of another height than the placeholder's: laid out again, still the same grid
    tall = [(run, "MAWDO (seed 0) | gap n/a | goal not reached: Timeout [qgjpy]", blocks[0][2])]
    again = save_grid(GridFrame([run.scenario]).fill(tall), tmp_path / "again.png")
    once = save_grid(GridFrame.for_blocks(tall).fill(tall), tmp_path / "once.png")
    # up to anti-aliasing: in a clean clone's first run (fresh font cache) the two layouts once
    # rounded 359 of 4.7 M text-edge values 1-2 levels apart
    assert_same_picture(pixels(again), pixels(once))


def test_the_early_figures_are_the_figures_of_the_run(run, tmp_path):
    job = EarlyFigures(
        run_figures(run.scenario, "mawdo", 0, tmp_path / "g.png", tmp_path / "a.gif")
    )
    assert job.early == render.can_fork()
    job.send((run, None, None))
    grid, gif = job.result()
    direct = render.snapshot_grid([run], tmp_path / "direct.png")
    assert_same_picture(pixels(grid), pixels(direct))
    assert gif.read_bytes() == render.animate(run, tmp_path / "direct.gif").read_bytes()


@pytest.mark.parametrize("parallel", [True, False])
def test_figures_begun_with_the_optimum_given_are_the_figures_of_the_run(run, tmp_path, parallel):
    """What ``plan`` does: the process forked before the run is set up, the static optimum
    handed to it once the parent has computed it (the figures' process loads no kernel)."""
    from mawdo.planning.render.style import optimum_path

    prepare = run_figures(run.scenario, "mawdo", 0, tmp_path / "g.png", tmp_path / "a.gif")
    with EarlyFigures(prepare, parallel=parallel) as job:
        job.begin(optimum_path(run.scenario, {}))
        job.send((run, None, None))
        grid, gif = job.result()
    direct = render.snapshot_grid([run], tmp_path / "direct.png")
    assert_same_picture(pixels(grid), pixels(direct))
    assert gif.read_bytes() == render.animate(run, tmp_path / "direct.gif").read_bytes()


def test_a_given_optimum_is_drawn_as_it_is_and_the_oracle_not_asked(run, monkeypatch):
    from mawdo.planning.guide import oracle
    from mawdo.planning.render.style import know_optimum, optimum_path

    sc = plan("paper", "mawdo", seed=0, config="quick", max_steps=2).scenario  # a new object
    path = np.array([[1.0, 2.0], [3.0, 4.0]])
    know_optimum(sc, path)
    monkeypatch.setattr(oracle, "scenario_optimum", lambda *a, **k: pytest.fail("asked"))
    assert optimum_path(sc, {}) is path


def test_warm_runs_in_the_child_before_begin_and_prepare_takes_what_begin_gives(tmp_path):
    warmed = tmp_path / "warmed"

    def prepare(data=None):
        return lambda payload: (data, payload)

    prepare.warm = lambda: warmed.write_text(str(os.getpid()))
    with EarlyFigures(prepare) as job:
        if job.early:  # warmed at once, in the child, while the parent has not begun
            # wait for the content, not the file: write_text creates it empty first
            end = time.monotonic() + 60
            while time.monotonic() < end and not (warmed.exists() and warmed.read_text()):
                time.sleep(0.01)
            assert warmed.read_text() == str(job.proc.pid)
        job.begin("given")
        job.send(5)
        assert job.result() == ("given", 5)
    with EarlyFigures(prepare) as job:  # a parent that never begins: prepare()
        job.send(6)
        assert job.result() == (None, 6)
    here = EarlyFigures(prepare, parallel=False)
    here.begin("kept")
    here.send(7)
    assert here.result() == ("kept", 7)


def test_the_early_process_hands_back_its_value_or_its_error(tmp_path):
    def prepare():
        mine = os.getpid()
        return lambda payload: (mine, payload * 2)

    job = EarlyFigures(prepare)
    job.send(21)
    pid, value = job.result()
    assert value == 42 and (pid != os.getpid()) == render.can_fork()

    def broken():
        raise OSError("cannot write '/x/run.gif': No space left on device")

    job = EarlyFigures(broken)
    job.send(None)
    with pytest.raises(OSError, match="No space left on device"):
        job.result()

    def fails_later():
        return lambda payload: 1 / payload

    with EarlyFigures(fails_later) as job:
        job.send(0)
        with pytest.raises(ZeroDivisionError):
            job.result()

    here = EarlyFigures(prepare, parallel=False)
    here.send(1)
    assert here.result() == (os.getpid(), 2) and not here.early


def test_a_command_that_stops_early_ends_the_early_process_and_nothing_is_written(tmp_path):
    marker = tmp_path / "written"

    def prepare():
        return lambda payload: marker.write_text("drawn")

    with EarlyFigures(prepare) as job:
        pid = job.proc.pid if job.early else None
    if pid is not None:
        assert not job.proc.is_alive()
    time.sleep(0.2)
    assert not marker.exists()


def test_component_labels_number_components_as_scipy_does():
    from scipy.sparse import coo_matrix
    from scipy.sparse.csgraph import connected_components

    rng = np.random.default_rng(5)
    for n, m in [(1, 0), (5, 0), (12, 6), (40, 25), (60, 200)]:
        a, b = rng.integers(0, n, m), rng.integers(0, n, m)
        a, b = np.r_[a, np.arange(n)], np.r_[b, np.arange(n)]  # self-pairs, as STRtree gives
        _, want = connected_components(coo_matrix((np.ones(len(a)), (a, b)), shape=(n, n)))
        np.testing.assert_array_equal(component_labels(n, a, b), want)


def _start(out: Path, *extra: str, preset: str = "quick") -> subprocess.Popen:
    cmd = [sys.executable, "-m", "mawdo.cli", "plan", "paper", "--preset", preset, *extra]
    return interruptible([*cmd, "--out", str(out)], env=ENV)


@pytest.mark.skipif(not render.can_fork(), reason="figures are drawn early only with fork")
def test_ctrl_c_while_planning_stops_the_command_and_its_figures_process(tmp_path):
    # the default preset's run: planned for seconds even on a fast machine (the quick one could
    # be planned and its grid saved within a second, before a Ctrl-C sent after a fixed delay)
    out = tmp_path / "out"
    proc = _start(out, preset="realtime")
    end = time.monotonic() + 300
    # the state waited for: --out exists once the run is set up (and compiled), right before
    # it is planned; the figures' process was started before that, at the arguments' check
    while not out.exists() and proc.poll() is None and time.monotonic() < end:
        time.sleep(0.02)
    assert out.exists(), "the run was never set up"
    assert children(proc.pid), "no figures process was started"
    err = ctrl_c(proc)
    assert not (out / "snapshots.png").exists() and not (out / "metrics.json").exists()
    # what is true of a single run: nothing to resume
    assert "stopped by Ctrl-C; the run was not finished: no metrics or figures" in err, err


def test_bad_input_ends_the_figures_process_and_creates_nothing(tmp_path):
    proc = _start(tmp_path / "out", "--algorithm", "nosuch")
    _, err = proc.communicate(timeout=120)
    assert proc.returncode == 2 and err.startswith("error: "), err
    assert group_gone(proc.pid)
    assert not (tmp_path / "out").exists()
