"""Uniform grids of boxes for the compiled geometry: a coordinate's cell, and each cell's list
of the boxes that meet it (a counting sort into compressed rows)."""

from __future__ import annotations

import numpy as np
from numba import njit

__all__ = ["cell_lists", "cell_of"]


# (not inlined: Numba's inlining copies the body into every call, and the grids call it often)
@njit(cache=True, fastmath=False, error_model="numpy")
def cell_of(v, lo, inv, n):
    """Cell of coordinate ``v`` on an axis from ``lo`` in cells of side ``1 / inv``: monotone
    in ``v``, clipped to ``0 .. n - 1`` (NaN: 0)."""
    u = (v - lo) * inv
    if not u > 0.0:
        return 0
    return int(u) if u < n else n - 1


@njit(cache=True, fastmath=False, error_model="numpy")
def cell_lists(box, keep, geo, head, ents):
    """List each box ``box[i] = (x0, y0, x1, y1)`` with ``keep[i]`` in every cell of the grid
    ``geo = (gx, gy, ginv, nx, ny)`` that it meets: cell ``c = cy * nx + cx`` holds
    ``ents[head[c]:head[c + 1]]``, in increasing ``i``. ``head`` (at least ``nx * ny + 1``
    long) and ``ents`` are work space kept by the caller; returns them, ``ents`` grown (twice
    what it needs) where it was too short. Loops, not slices: a slice assignment costs Numba
    about a second to compile."""
    gx, gy, ginv, nx, ny = geo
    for c in range(nx * ny + 1):
        head[c] = 0
    for rnd in range(2):  # count, then place
        for i in range(len(keep)):
            if not keep[i]:
                continue
            for cy in range(cell_of(box[i, 1], gy, ginv, ny), cell_of(box[i, 3], gy, ginv, ny) + 1):
                for cx in range(
                    cell_of(box[i, 0], gx, ginv, nx), cell_of(box[i, 2], gx, ginv, nx) + 1
                ):
                    c = cy * nx + cx
                    if rnd == 0:
                        head[c + 1] += 1
                    else:
                        ents[head[c]] = i
                        head[c] += 1
        if rnd == 0:
            for c in range(nx * ny):
                head[c + 1] += head[c]
            if len(ents) < head[nx * ny]:
                ents = np.empty(2 * head[nx * ny], np.int64)
    for c in range(nx * ny, 0, -1):  # (placing moved each start to the next cell's)
        head[c] = head[c - 1]
    head[0] = 0
    return head, ents
