"""The gallery of timed scene families (docs/img/families_time.png)."""

from __future__ import annotations

import numpy as np
import pytest

from mawdo.planning.render.families import timed_gallery
from mawdo.planning.scenes import generate_scene


def test_gallery_draws_each_scene_route_and_writes_a_png(tmp_path):
    scenes = [generate_scene(f, 0, seed=3) for f in ("parked", "doorway")]
    fig = timed_gallery(scenes=scenes, cols=3)
    axes = [ax for ax in fig.axes if ax.axison]
    assert len(axes) == 2
    for ax, scene in zip(axes, scenes, strict=True):
        (line,) = [ln for ln in ax.lines if ln.get_gid() == "time-route"]
        np.testing.assert_allclose(np.column_stack(line.get_data()), scene.time_route.points)
        assert ax.get_title().startswith(f"{scene.family}: T* {scene.t_star:.1f}")
    out = timed_gallery(tmp_path / "g.png", scenes=scenes)
    assert out.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_gallery_refuses_untimed_scenes_and_bad_paths(tmp_path):
    with pytest.raises(ValueError, match="timed families"):
        timed_gallery(scenes=[generate_scene("open", 0, seed=1)])
    with pytest.raises(ValueError, match="must end in one of"):
        timed_gallery(tmp_path / "g.txt", scenes=[generate_scene("parked", 0, seed=1)])
