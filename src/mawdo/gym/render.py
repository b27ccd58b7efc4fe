"""``render_mode="rgb_array"``: the current state of an environment's world as an image.

The frame is the snapshot panel users know from ``mawdo plan`` (:func:`~mawdo.planning.render
.world.draw_world`): static obstacles, scripted movers and people where they are now with their
recent tracks, start and goal, plus the robot's driven trail and its disc to scale. It is drawn
with Matplotlib's Agg canvas (no window, any backend), so wrappers such as Gymnasium's
``RecordVideo`` can film episodes.
"""

from __future__ import annotations

import numpy as np

__all__ = ["FRAME_PX", "frame"]

#: Longer side of a frame (pixels of the image).
FRAME_PX = 480

_DPI = 100


def frame(world, size: int = FRAME_PX) -> np.ndarray:
    """The world now, as an RGB image.

    Parameters
    ----------
    world : SteppedWorld
        The episode's world (its realised people, scripted motions, robot trajectory).
    size : int
        Longer side of the image (pixels, >= 64); the other follows the map's aspect.

    Returns
    -------
    numpy.ndarray of uint8, shape (height, width, 3)
    """
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure
    from matplotlib.patches import Circle

    from mawdo.planning.render.style import STYLE, time_title
    from mawdo.planning.render.world import draw_world

    if int(size) < 64:
        raise ValueError(f"size must be >= 64 image pixels, got {size!r}")
    sc = world.realised()  # the people as movers along their recorded steps
    t = float(world.step_index)
    scale = int(size) / max(sc.width, sc.height)
    w, h = max(int(round(sc.width * scale)), 1), max(int(round(sc.height * scale)), 1)
    fig = Figure(figsize=(w / _DPI, h / _DPI), dpi=_DPI)
    canvas = FigureCanvasAgg(fig)
    ax = fig.add_axes((0.0, 0.0, 1.0, 1.0))
    draw_world(ax, sc, t, title="")
    trail = np.asarray(world.trajectory, dtype=float)
    ax.plot(trail[:, 0], trail[:, 1], zorder=6, **STYLE["trail"])
    ax.add_patch(Circle(world.position, max(sc.robot_radius, 0.5), zorder=8, **STYLE["robot"]))
    ax.text(0.01, 0.99, time_title(sc, t), transform=ax.transAxes, va="top", fontsize=8)
    ax.set_axis_off()
    canvas.draw()
    image = np.asarray(canvas.buffer_rgba())[..., :3].copy()
    return image
