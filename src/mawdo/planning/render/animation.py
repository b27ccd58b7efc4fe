"""An animated GIF of one planning run (Pillow, no ffmpeg)."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from mawdo.planning.planner import PlanResult
from mawdo.planning.render.style import (
    _display,
    _new_figure,
    _optimum_path,
    _output_path,
    _route,
)
from mawdo.planning.render.world import _draw_world, _legend_handles


def animation_times(result: PlanResult, every: int = 1, max_frames: int = 200) -> np.ndarray:
    """Frame times of :func:`animate`: every ``every`` steps, thinned to ``max_frames``.

    The end of the run is always the last frame.
    """
    if not isinstance(every, int | np.integer) or every < 1:
        raise ValueError(f"every={every!r} must be a positive integer")
    if not isinstance(max_frames, int | np.integer) or max_frames < 2:
        raise ValueError(f"max_frames={max_frames!r} must be an integer >= 2")
    end = float(_route(result)[1][-1])
    ts = np.arange(0.0, end + 1e-9, every)
    if ts[-1] < end - 1e-9:
        ts = np.append(ts, end)
    if ts.size > max_frames:
        ts = ts[np.unique(np.linspace(0, ts.size - 1, max_frames).round().astype(int))]
    return ts


def animate(
    result: PlanResult,
    path,
    fps: int = 12,
    every: int = 1,
    max_frames: int = 200,
    optimum: bool = True,
    dpi: int = 80,
    label: str | None = None,
) -> Path:
    """Animated GIF of one run: the snapshot panel of :func:`snapshot_grid`, one frame per time.

    Parameters
    ----------
    result : PlanResult
    path : str or Path
        Output ``.gif``; missing directories are created.
    fps : int
        Frames per second.
    every : int
        Time steps between frames.
    max_frames : int
        Upper bound on frames (the times are thinned evenly, the last one kept).
    optimum : bool
        Draw the static optimum path.
    dpi : int
        Resolution of the 5 x 5.6 in figure (80 dpi: 400 x 448 px, a few MB at most).
    label : str, optional
        Title (default the algorithm's display label).

    Returns
    -------
    Path
        The written GIF.
    """
    from matplotlib.animation import PillowWriter

    if not isinstance(result, PlanResult):
        raise TypeError(f"animate needs a PlanResult, got {type(result).__name__}")
    if not (isinstance(fps, int | np.integer | float) and fps > 0):
        raise ValueError(f"fps={fps!r} must be > 0")
    out = _output_path(path, (".gif",))
    ts = animation_times(result, every, max_frames)
    sc = result.scenario
    opt = _optimum_path(sc, {}) if optimum else None
    fig = _new_figure((5.0, 5.6), dpi)
    fig.get_layout_engine().set(w_pad=0.02, h_pad=0.02)
    fig.suptitle(f"{label or _display(result.algorithm)}  (seed {result.seed})", fontsize=10)
    ax = fig.add_subplot()
    handles = _legend_handles(sc.robot_radius)
    fig.legend(
        handles=handles,
        loc="outside lower center",
        ncols=3,
        fontsize=6.5,
        frameon=False,
        handlelength=2.0,
        columnspacing=1.0,
    )

    def frame(i):
        _draw_world(ax, sc, float(ts[i]), result=result, optimum=opt, clear=False)

    frame(0)
    ax.set_xlabel("x (px)", fontsize=7)
    ax.set_ylabel("y (px)", fontsize=7)
    fig.draw_without_rendering()  # fix the constrained layout once; frames keep it
    fig.set_layout_engine("none")
    # PillowWriter driven frame by frame: FuncAnimation.save would draw every frame twice
    # (once for the writer, once more in its post-draw hook) for the same GIF.
    writer = PillowWriter(fps=fps)
    try:
        with writer.saving(fig, out, dpi):
            for i in range(len(ts)):
                if i:
                    frame(i)
                writer.grab_frame()
    except OSError as exc:
        raise OSError(f"cannot write {str(out)!r}: {exc.strerror or exc}") from exc
    return out


# --------------------------------------------------------------------------------------------
# statistics across runs
