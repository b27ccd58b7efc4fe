"""Figures and animations of planning runs: valid files of the right size, the right content."""

import matplotlib
import numpy as np
import pytest
from PIL import Image

from mawdo.planning import render
from mawdo.planning.run.planner import plan

PNG_SIGNATURE = b"\x89PNG\r\n\x1a\n"


@pytest.fixture(scope="module")
def runs():
    """Two short runs (30 steps, quick preset), one per algorithm."""
    return {a: plan("paper", a, seed=0, config="quick", max_steps=30) for a in ("mawdo", "woa")}


def assert_png(path):
    assert path.read_bytes()[:8] == PNG_SIGNATURE
    with Image.open(path) as im:
        im.verify()
    with Image.open(path) as im:
        return im.size


def by_gid(ax, gid):
    return [a for a in [*ax.lines, *ax.patches] if a.get_gid() == gid]


def test_grid_png_has_the_figure_size_and_one_block_of_panels_per_algorithm(runs, tmp_path):
    out = render.snapshot_grid(runs, tmp_path / "sub" / "grid.png")
    assert out == tmp_path / "sub" / "grid.png"
    size = assert_png(out)
    fig = render.snapshot_figure(runs)
    expected = fig.get_size_inches() * fig.dpi
    assert abs(size[0] - expected[0]) <= 3 and abs(size[1] - expected[1]) <= 3
    assert 1400 <= size[0] <= 1800  # four panels of a row, ~1600 px
    assert render.panel_count(fig) == 2 * 2 * 4
    titles = [sub.get_suptitle() for sub in fig.subfigs if sub.get_suptitle()]
    assert len(titles) == 2
    assert titles[0].startswith("MAWDO") and titles[1].startswith("WOA")
    # one legend for the whole figure, none per panel
    legends = [leg for sub in fig.subfigs for leg in sub.legends]
    assert len(legends) == 1
    assert all(ax.get_legend() is None for ax in fig.axes)
    # outer panels carry the axis labels
    xlabels = [ax.get_xlabel() for ax in fig.axes if ax.get_xlabel()]
    ylabels = [ax.get_ylabel() for ax in fig.axes if ax.get_ylabel()]
    assert xlabels.count("x (px)") == 2 * 4 and ylabels.count("y (px)") == 2 * 2


def test_panel_shows_the_run_at_its_time(runs):
    res = runs["mawdo"]
    times = [0, 10, 25]
    fig = render.snapshot_figure({"mawdo": res}, times=times, rows=1, cols=4)
    panels = [ax for ax in fig.axes if ax.get_visible() and ax.get_title().startswith("t = ")]
    assert [ax.get_title() for ax in panels] == ["t = 0", "t = 10", "t = 25"]
    sc = res.scenario
    for ax, t in zip(panels, times, strict=True):
        (robot,) = by_gid(ax, "robot")
        np.testing.assert_allclose(robot.center, res.trajectory[t], atol=1e-9)
        assert robot.radius == sc.robot_radius
        (trail,) = by_gid(ax, "trail")
        np.testing.assert_allclose(trail.get_xydata()[-1], res.trajectory[t], atol=1e-9)
        (planned,) = by_gid(ax, "plan")
        active = [rp for rp in res.replans if rp.step <= t][-1]
        xy = planned.get_xydata()
        np.testing.assert_allclose(xy[0], active.position)
        np.testing.assert_allclose(xy[-1], sc.goal)
        assert len(xy) == len(active.waypoints) + 2
        assert len(by_gid(ax, "optimum")) == 1
        # moving obstacles are drawn where they are at t
        ob = sc.obstacles[sc.moving_indices[0]]
        (disc,) = by_gid(ax, f"moving:{ob.id}")
        if ob.is_circle:
            np.testing.assert_allclose(disc.center, np.add(ob.shape.center, ob.offset(t)))
    assert render.panel_count(fig) == 3


def test_headline_metrics_and_registered_labels(runs):
    metrics = {"mewdo-run": {"length_px": 123.45, "gap": float("nan"), "smoothness_rad": 2.5}}
    fig = render.snapshot_figure(
        {"mewdo": runs["mawdo"], "mewdo-run": runs["woa"]},
        metrics=metrics,
        times=[0],
        rows=1,
        cols=1,
        optimum=False,
    )
    first, second = (sub.get_suptitle() for sub in fig.subfigs[:2])
    assert first.startswith("MEWDO (reconstructed)")  # registered name -> display label
    assert second.startswith("mewdo-run")
    assert "123.5 px" in second and "gap n/a" in second and "2.50 rad" in second
    assert "goal not reached" in second  # 30 steps are not enough
    assert not any(by_gid(ax, "optimum") for ax in fig.axes)


def test_gif_is_animated_and_small(runs, tmp_path):
    res = runs["woa"]
    out = render.animate(res, tmp_path / "run.gif", fps=10, every=2)
    data = out.read_bytes()
    assert data[:6] in (b"GIF87a", b"GIF89a")
    assert len(data) < 8 * 2**20
    with Image.open(out) as im:
        assert im.n_frames == len(render.animation_times(res, every=2)) == 16
        assert im.size == (400, 448)
        assert im.info["duration"] == pytest.approx(100, abs=1)


def test_animation_times_are_thinned_and_keep_the_end(runs):
    res = runs["mawdo"]
    ts = render.animation_times(res, every=1, max_frames=5)
    assert len(ts) == 5 and ts[0] == 0 and ts[-1] == res.route_times[-1]
    assert np.all(np.diff(ts) > 0)
    assert len(render.animation_times(res, every=7)) == 6  # 0, 7, ..., 28, then the end (30)
    with pytest.raises(ValueError, match="max_frames"):
        render.animation_times(res, max_frames=1)


def test_convergence_and_box_plots_write_pngs(runs, tmp_path):
    curves = {name: np.vstack([r.replans[0].history] * 3) for name, r in runs.items()}
    curves["ragged"] = [np.array([5.0, 4.0, 3.0]), np.array([6.0, 2.0])]
    out = render.plot_cost_convergence(curves, tmp_path / "conv.png")
    w, h = assert_png(out)
    assert (w, h) == (768, 504)
    values = {"mawdo": np.array([1.02, 1.05, np.nan]), "woa": [1.01, 1.1, 1.2]}
    w, h = assert_png(render.plot_metric_boxes(values, tmp_path / "box.png", "gap L / L*"))
    assert w >= 480 and h == 504


def test_ragged_curves_are_padded_with_their_last_value():
    arr = render.as_runs([[5.0, 4.0, 3.0], [6.0, 2.0]], "x")
    np.testing.assert_array_equal(arr, [[5.0, 4.0, 3.0], [6.0, 2.0, 2.0]])


def test_no_global_matplotlib_state_is_changed(runs, tmp_path):
    import matplotlib.pyplot as plt

    backend, figs = matplotlib.get_backend(), plt.get_fignums()
    render.snapshot_grid(runs, tmp_path / "g.png", times=[3], rows=1, cols=1)
    render.plot_metric_boxes({"a": [1.0, 2.0]}, tmp_path / "b.png", "m")
    assert matplotlib.get_backend() == backend
    assert plt.get_fignums() == figs  # nothing registered with (or leaked into) pyplot


@pytest.mark.parametrize("empty", [[], {}])
def test_empty_results_are_refused(empty, tmp_path):
    with pytest.raises(ValueError, match="no results to draw"):
        render.snapshot_grid(empty, tmp_path / "g.png")
    assert not (tmp_path / "g.png").exists()


def test_bad_inputs_get_clear_errors(runs, tmp_path):
    with pytest.raises(TypeError, match="not a PlanResult"):
        render.snapshot_figure({"x": "not a run"})
    with pytest.raises(ValueError, match="do not fit"):
        render.snapshot_figure(runs, times=range(9))
    with pytest.raises(ValueError, match="no curves"):
        render.plot_cost_convergence({}, tmp_path / "c.png")
    with pytest.raises(ValueError, match="no finite values"):
        render.plot_metric_boxes({"a": [np.nan]}, tmp_path / "b.png", "gap")
    with pytest.raises(ValueError, match=r"must end in one of \.gif"):
        render.animate(runs["mawdo"], tmp_path / "run.png")


def test_unwritable_path_names_the_path(runs, tmp_path):
    blocker = tmp_path / "a-file"
    blocker.write_text("not a directory")
    for call, name in [
        (lambda p: render.snapshot_grid(runs, p), "grid.png"),
        (lambda p: render.animate(runs["mawdo"], p), "run.gif"),
        (lambda p: render.plot_cost_convergence({"a": [[3.0, 2.0]]}, p), "conv.png"),
        (lambda p: render.plot_metric_boxes({"a": [1.0]}, p, "m"), "box.png"),
    ]:
        target = blocker / name
        with pytest.raises(OSError, match="cannot write") as info:
            call(target)
        assert str(target) in str(info.value)
    folder = tmp_path / "looks-like.png"
    folder.mkdir()
    with pytest.raises(IsADirectoryError, match="is a directory") as info:
        render.snapshot_grid(runs, folder)
    assert str(folder) in str(info.value)


def test_a_failing_write_names_the_path(tmp_path, monkeypatch):
    from matplotlib.figure import Figure

    def refuse(self, *args, **kwargs):
        raise PermissionError(13, "Permission denied")

    monkeypatch.setattr(Figure, "savefig", refuse)
    target = tmp_path / "box.png"
    with pytest.raises(OSError, match="Permission denied") as info:
        render.plot_metric_boxes({"a": [1.0, 2.0]}, target, "m")
    assert str(target) in str(info.value)


def test_grid_says_obstacles_are_drawn_at_t_while_the_lines_span_all_times(runs):
    """Issue 28: the red plan at t = 0 seemed to cross obstacles drawn where they are at t = 0."""
    fig = render.snapshot_figure(runs, times=[0, 10], rows=1, cols=2)
    legend_block = fig.subfigs[-1]
    # (wrapped into lines once laid out: a narrow grid's note is several lines)
    notes = [t.get_text().replace("\n", " ") for t in legend_block.texts]
    assert notes == [render.TIME_NOTE]
    for words in (
        "obstacles where they are at its time t",
        "all times",
        "plan the times from t on",
    ):
        assert words in render.TIME_NOTE
    # the note sits inside the figure, below the legend
    fig.canvas.draw()
    renderer = fig.canvas.get_renderer()
    note = legend_block.texts[0].get_window_extent(renderer)
    legend = legend_block.legends[0].get_window_extent(renderer)
    page = fig.bbox
    assert note.x0 >= page.x0 and note.x1 <= page.x1 and note.y0 >= page.y0
    assert note.y1 <= legend.y0 + 1


def gif_frames(path) -> list[np.ndarray]:
    with Image.open(path) as im:
        out = []
        for k in range(im.n_frames):
            im.seek(k)
            out.append(np.asarray(im.convert("RGB")).astype(int))
        return out


def test_gif_frames_are_the_panel_drawn_afresh_and_the_robot_is_where_the_run_puts_it(
    runs, tmp_path
):
    """Each frame (blitted, on the shared palette) is the panel a fresh figure draws at the
    frame's time, up to the palette's rounding of anti-aliased pixels; the robot's centre pixel
    has the robot's colour exactly, at the run's position of that time."""
    from matplotlib.colors import to_rgb

    from mawdo.planning.render import animation

    res = runs["mawdo"]
    out = render.animate(res, tmp_path / "run.gif", every=3)
    ts = render.animation_times(res, every=3)
    frames = gif_frames(out)
    assert len(frames) == len(ts) == 11 and frames[0].shape == (448, 400, 3)
    opt = render.optimum_path(res.scenario, {})
    robot = np.round(np.multiply(to_rgb(render.STYLE["robot"]["facecolor"]), 255)).astype(int)
    route, times = render.route_of(res)
    for k in (0, 4, 10):
        fig, ax = animation._panel(res, float(ts[k]), opt, 80, None)
        fig.canvas.draw()
        fresh = np.asarray(fig.canvas.buffer_rgba())[..., :3].astype(int)
        off = np.abs(fresh - frames[k]).max(axis=-1)
        assert np.mean(off > 40) < 0.002, (k, np.mean(off > 40))  # palette rounding only
        assert np.mean(off == 0) > 0.9
        x, y = ax.transData.transform(render.position_at(route, times, float(ts[k])))
        row, col = int(fresh.shape[0] - y), int(x)
        np.testing.assert_array_equal(frames[k][row, col], robot)
        if k:  # where the robot was at the start it is no longer
            x0, y0 = ax.transData.transform(route[0])
            assert not np.array_equal(frames[k][int(448 - y0), int(x0)], robot)
    moved = [np.any(a != b) for a, b in zip(frames, frames[1:], strict=False)]
    assert all(moved)  # the robot moves (it does not wait in this run): every frame differs
    assert np.all(frames[0][0, 0] == 255) and np.all(frames[-1][0, 0] == 255)  # pure white


def test_forked_returns_the_childs_value_and_raises_its_error():
    import os

    job = render.Forked(os.getpid)
    pid = job.result()
    assert isinstance(pid, int)
    assert (pid != os.getpid()) == render.can_fork()  # drawn in another process where it can

    def fails():
        raise OSError("cannot write '/x/run.gif': No space left on device")

    with pytest.raises(OSError, match="No space left on device"):
        render.Forked(fails).result()
    here = render.Forked(os.getpid, parallel=False)
    assert here.result() == os.getpid() and render.forked_note(here) == ""
    if render.can_fork():  # a value that cannot be pickled back: said, not lost silently
        with pytest.raises(RuntimeError, match="could not send back"):
            render.Forked(lambda: lambda: None).result()
