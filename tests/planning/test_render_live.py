"""GIF frames drawn while the run goes on (issue 28, item 2): the same GIF, nothing lost.

The command's process hands the run's steps to the figures' process as they are made
(:class:`RunStream` -> :meth:`EarlyFigures.feed`); that process draws each frame once the run
has passed its time (:meth:`GifFrame.draw_ready`). The GIF must be, byte for byte, the one
:func:`animate` writes from the finished run, however the steps were grouped on the way (a
figures' process that falls behind gets several steps at once) and when the frames are thinned.
"""

from __future__ import annotations

import os
import sys
import time
from pathlib import Path

import numpy as np
import pytest

from mawdo.planning import render
from mawdo.planning.render.animation import GifFrame
from mawdo.planning.render.early import EarlyFigures
from mawdo.planning.render.live import PartialRun, RunStream
from mawdo.planning.run.planner import prepare
from tests.cli_run import ENV as CLI_ENV
from tests.cli_run import children, ctrl_c, interruptible, mawdo

SRC = str(Path(__file__).resolve().parents[2] / "src")
ENV = {**CLI_ENV, "PYTHONPATH": SRC, "PYTHONUNBUFFERED": "1"}


class _Here:
    """An EarlyFigures stand-in in this process: takes the news of every ``take``-th step (a
    figures' process busy drawing takes the rest with a later message)."""

    def __init__(self, take: int) -> None:
        self.take, self.calls, self.news = take, 0, []

    def feed(self, make) -> None:
        self.calls += 1
        if self.calls % self.take == 0:
            news = make()
            if news is not None:
                self.news.append(news)


def _streamed_run(take: int, max_steps: int = 40):
    """A quick paper run with its news as the figures' process would get them, and per news
    the time the run had reached (the end of the route sent so far)."""
    run = prepare("paper", "mawdo", seed=0, config="quick", max_steps=max_steps)
    job = _Here(take)
    result = run.execute(RunStream(run, job))
    return result, job.news


@pytest.mark.parametrize(
    "take, max_frames, stop_after", [(1, 200, 0), (3, 200, 0), (1, 6, 0), (4, 200, 5)]
)
def test_frames_drawn_during_the_run_give_the_gif_of_the_finished_run(
    take, max_frames, stop_after, tmp_path
):
    result, news = _streamed_run(take)
    assert len(news) > 3
    movie = GifFrame(result.scenario, "MAWDO", result.seed)
    partial = PartialRun()
    asked = []

    def stop():  # the run ended while frames were drawn: stop after stop_after frames
        asked.append(1)
        return bool(stop_after) and len(movie.drawn) >= stop_after

    for item in news:
        partial.add(item)
        movie.draw_ready(partial, every=2, max_frames=max_frames, stop=stop)
        if stop_after:
            assert len(movie.drawn) <= stop_after
        # only frames the run has passed: their time is before the end of the route so far
        assert all(t < partial.end for t in movie.drawn)
    assert 0 < len(movie.drawn) <= max_frames
    if stop_after:  # asked before each frame; the frames it stopped are drawn by write()
        assert len(movie.drawn) == stop_after and len(asked) > stop_after
    streamed = movie.write(result, tmp_path / "streamed.gif", max_frames=max_frames)
    direct = render.animate(result, tmp_path / "direct.gif", max_frames=max_frames)
    assert streamed.read_bytes() == direct.read_bytes()


def test_the_run_sent_in_pieces_is_the_run(tmp_path):
    result, news = _streamed_run(take=2)
    partial = PartialRun()
    for item in news:
        partial.add(item)
    n = len(partial.route)
    # the pieces are the finished run's route and plans, up to the last step sent
    np.testing.assert_array_equal(partial.route, result.route[:n])
    np.testing.assert_array_equal(partial.route_times, result.route_times[:n])
    assert 0 < n <= len(result.route)
    sent = partial.replans
    assert [p.step for p in sent] == [r.step for r in result.replans[: len(sent)]]
    for p, r in zip(sent, result.replans, strict=False):
        np.testing.assert_array_equal(p.waypoints, r.waypoints)
        np.testing.assert_array_equal(p.position, r.position)


def test_a_run_without_moves_to_read_feeds_nothing():
    class Blind:  # a planner that keeps no drive (single-shot baselines)
        replans: list = []

    job = _Here(1)
    stream = RunStream(Blind(), job)
    for step in range(5):
        stream(step, 10, 0)
    assert job.calls == 5 and job.news == []


def _counting_prepare(delay: float):
    def prepare():
        got = []

        def finish(payload):
            return got, payload

        def feed(data, run_over):
            time.sleep(delay)  # drawing frames
            got.append(data)

        finish.feed = feed
        return finish

    return prepare


def test_feed_sends_only_what_the_child_took_and_loses_nothing():
    made = {"items": 0, "sent": 0, "messages": 0}  # items the run has made / sent so far

    def make():  # what is new since the last call
        new = list(range(made["sent"], made["items"]))
        made["sent"] = made["items"]
        made["messages"] += bool(new)
        return new or None

    with EarlyFigures(_counting_prepare(0.05)) as job:
        for _ in range(100):
            made["items"] += 1
            job.feed(make)
        deadline = time.monotonic() + 60
        while job.early and made["sent"] < 100 and time.monotonic() < deadline:
            job.feed(make)  # the run's last steps, once the child took the message before
            time.sleep(0.005)
        job.send("end")
        got, payload = job.result()
    assert payload == "end"
    if not job.early:  # no fork: nothing goes early, the payload alone
        assert got == []
        return
    # every item sent arrived once, in order, in as many messages as were sent: fewer than the
    # feed calls, since a busy child had not taken the last one
    assert sum(got, []) == list(range(100))
    assert len(got) == made["messages"] < 100


def test_the_child_learns_that_the_run_is_over_while_it_draws():
    def prepare():
        def finish(payload):
            return payload, seen

        seen = []

        def feed(data, run_over):
            deadline = time.monotonic() + 30
            while not run_over() and time.monotonic() < deadline:
                time.sleep(0.01)  # drawing frames until the run's end is waiting
            seen.append(run_over())

        finish.feed = feed
        return finish

    with EarlyFigures(prepare) as job:
        job.feed(lambda: "steps 0-9")
        job.send("run")  # without waiting for the child to take the steps
        payload, seen = job.result()
    assert payload == "run"
    assert seen == ([True] if job.early else [])


def test_an_error_while_fed_is_raised_by_result():
    def prepare():
        def finish(payload):
            return payload

        def feed(data, run_over):
            raise ValueError(f"cannot draw {data}")

        finish.feed = feed
        return finish

    with EarlyFigures(prepare) as job:
        if not job.early:
            pytest.skip("figures are drawn early only with fork")
        job.feed(lambda: "frame 0")
        deadline = time.monotonic() + 30
        while job.waiting and time.monotonic() < deadline:
            job.feed(lambda: "frame 1")  # the child's error arrives in place of its answer
            time.sleep(0.01)
        job.send("end")
        with pytest.raises(ValueError, match="cannot draw frame 0"):
            job.result()


def test_a_frame_packed_from_the_canvas_rgba_is_its_rgb_packed_by_hand():
    from mawdo.planning.render.animation import _packed_rgba, _Shot

    rng = np.random.default_rng(5)
    rgba = rng.integers(0, 256, (37, 23, 4), dtype=np.uint8)  # any alpha: it is dropped
    r, g, b = (rgba[..., k].astype(np.int64) for k in range(3))
    packed = _packed_rgba(rgba)
    np.testing.assert_array_equal(packed, r * 65536 + g * 256 + b)
    seen = np.zeros(1 << 24, dtype=bool)
    shot = _Shot(packed, seen=seen)
    np.testing.assert_array_equal(shot.rgb, rgba[..., :3])  # unpacked: the same pixels
    assert set(np.flatnonzero(seen)) == set((r * 65536 + g * 256 + b).ravel())


def test_a_frame_flagged_against_the_one_before_flags_every_colour_of_both():
    from mawdo.planning.render.animation import _Shot

    rng = np.random.default_rng(6)
    first = rng.integers(0, 1 << 24, (40, 30), dtype=np.uint32)
    second = first.copy()
    changed = rng.random(first.shape) < 0.1
    second[changed] = rng.integers(0, 1 << 24, changed.sum(), dtype=np.uint32)
    seen = np.zeros(1 << 24, dtype=bool)
    _Shot(first, seen)
    _Shot(second, seen, before=first)
    want = set(first.ravel()) | set(second.ravel())
    assert set(np.flatnonzero(seen)) == want


def test_the_palette_maps_each_colour_to_its_nearest_entry_the_first_on_a_tie():
    from mawdo.planning.render.animation import _Palette, _Shot

    rng = np.random.default_rng(3)
    frames = [rng.integers(0, 256, (40, 30, 3), dtype=np.uint8) for _ in range(3)]
    frames[0][:20] = (255, 255, 255)  # frequent colours: taken exactly
    frames[1][:10] = (200, 40, 40)
    palette = _Palette([_Shot.of(f) for f in frames])
    entries = palette.entries
    # colours halfway between two entries (ties), and random ones
    ties = [(a + b) // 2 for a, b in zip(entries[:-1], entries[1:], strict=True)]
    test = np.concatenate([np.array(ties), rng.integers(0, 256, (3000, 3))]).astype(np.uint8)
    images = np.asarray(palette(_Shot.of(test[None, :, :])))[0]
    # brute force in integers: squared distance to every entry, the first smallest
    d2 = ((test[:, None, :].astype(np.int64) - entries[None, :, :]) ** 2).sum(-1)
    np.testing.assert_array_equal(images, np.argmin(d2, axis=1))
    assert (d2 == d2.min(axis=1, keepdims=True)).sum(axis=1).max() > 1  # ties were tested


def _cpu_seconds(pid: int) -> float:
    """User + system CPU time of a process (s), from /proc."""
    fields = Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()
    return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")


@pytest.mark.slow  # a `plan paper` in a subprocess and the same run here: 20-40 s on 2 cores
def test_the_command_writes_the_gif_of_its_run(tmp_path):
    from mawdo.planning.run.planner import plan

    out = tmp_path / "out"
    args = ["plan", "paper", "--preset", "quick", "--max-steps", "40", "--no-progress"]
    proc = mawdo(*args, "--out", str(out), env={"PYTHONPATH": SRC})
    assert proc.returncode == 0, proc.stderr
    run = plan("paper", "mawdo", seed=0, config="quick", max_steps=40)
    direct = render.animate(run, tmp_path / "direct.gif")
    assert (out / "run.gif").read_bytes() == direct.read_bytes()


@pytest.mark.slow  # the `paper` preset plans for 10-30 s
@pytest.mark.skipif(not render.can_fork(), reason="frames are drawn early only with fork")
def test_ctrl_c_while_frames_are_drawn_exits_130_and_leaves_no_process(tmp_path):
    cmd = [sys.executable, "-m", "mawdo.cli", "plan", "paper", "--preset", "paper"]
    proc = interruptible([*cmd, "--no-progress", "--out", str(tmp_path / "out")], env=ENV)
    end = time.monotonic() + 180
    figures, seen = None, []  # (wall, CPU) of the figures' process
    while proc.poll() is None and time.monotonic() < end:
        kids = children(proc.pid)
        if kids:
            seen.append((time.monotonic(), _cpu_seconds(kids[0])))
            # its set-up (0.5-1.7 s of CPU by the machine) runs flat out; past it, it draws a
            # frame now and then: under 0.2 s of CPU in the last half second (a fixed CPU
            # threshold was never reached on a fast machine before the run ended)
            back = [c for w, c in seen if w <= seen[-1][0] - 0.5]
            if back and seen[-1][1] > 0.3 and seen[-1][1] - back[-1] < 0.2:
                figures = kids[0]
                break
        time.sleep(0.05)
    assert figures is not None, "the figures' process never got to the frames"
    ctrl_c(proc)
    assert not (tmp_path / "out" / "run.gif").exists()
