"""Which steps of a trajectory a moving obstacle can come near: the checker's index.

Among thousands of moving obstacles the checker's exact test (one shapely polyline per step and
obstacle, :mod:`mawdo.planning.judge.check`) spends nearly all its time on pairs that are far
apart. Before it, each obstacle's swept box over each step is compared with the robot's: the
obstacle's offset is piecewise linear in time, so over a step it stays in the box of its offsets
at the step's two ends and at the knots in between; its shape adds its own box at offset zero.
The robot's centre stays in the box of the step's two ends. Where the two boxes are more than
``pad`` apart, the robot's centre is more than ``pad`` from the obstacle throughout the step,
and the exact test can be skipped: its clearance would exceed ``pad`` minus the robot radius.

Vectorised over steps: one knot query per obstacle for the whole trajectory instead of one per
step, so the Python work grows with the number of obstacles, not with obstacles x steps.
"""

from __future__ import annotations

import numpy as np

#: Room (pixels) added to the boxes for rounding: the knots of one query over the whole
#: trajectory and of one query per step may differ in their last bits.
ROUNDING = 1e-6


def robot_boxes(p: np.ndarray, pad: float) -> np.ndarray:
    """Per step ``p[s] -> p[s + 1]`` the box of the robot's centre grown by ``pad`` (pixels):
    shape ``(n_steps, 4)``, ``(xmin, ymin, xmax, ymax)``."""
    lo = np.minimum(p[:-1], p[1:]) - pad
    hi = np.maximum(p[:-1], p[1:]) + pad
    return np.hstack([lo, hi])


def swept_boxes(obstacle, times: np.ndarray) -> np.ndarray:
    """Per step ``times[s] -> times[s + 1]`` the box (pixels) the moving ``obstacle`` stays in:
    shape ``(n_steps, 4)``. Its offset is piecewise linear between the knots of its motion, so
    the box of the offsets at the step's ends and at the knots inside it holds it throughout."""
    at = obstacle.offset(times)  # (k, 2), one vectorised call
    lo = np.minimum(at[:-1], at[1:])
    hi = np.maximum(at[:-1], at[1:])
    kt, ko = obstacle.knots(float(times[0]), float(times[-1]))
    step = np.searchsorted(times, kt, side="right") - 1
    inside = (step >= 0) & (step < len(times) - 1)
    inside[inside] &= kt[inside] > times[step[inside]]
    np.minimum.at(lo, step[inside], ko[inside])
    np.maximum.at(hi, step[inside], ko[inside])
    x0, y0, x1, y1 = obstacle.shape.bounds()
    return np.hstack([lo + (x0, y0), hi + (x1, y1)])


def near_steps(obstacle, p: np.ndarray, times: np.ndarray, robot: np.ndarray) -> np.ndarray:
    """The steps (ascending indices) over which ``obstacle``'s swept box meets ``robot`` (the
    robot's grown boxes of :func:`robot_boxes`); the exact test must see these and no other."""
    box = swept_boxes(obstacle, times)
    pad = ROUNDING
    meets = (
        (box[:, 0] <= robot[:, 2] + pad)
        & (robot[:, 0] <= box[:, 2] + pad)
        & (box[:, 1] <= robot[:, 3] + pad)
        & (robot[:, 1] <= box[:, 3] + pad)
    )
    return np.flatnonzero(meets)
