"""A grid of a block's segments, so that each standing obstacle is measured against the
segments that can come near it, not against all of them.

Per call (:func:`standing_table`): each standing obstacle gets its centre, its *reach* (the
larger of its bounding and accept radii, plus the pass's room twice and room for rounding up to
the sane range) and the square of that reach about its centre. Per block
(:func:`indexed_standing_pass`, sane blocks only): the real segments are listed in the cells of
a uniform grid that their boxes meet (:func:`segment_grid`, cells twice the squares' typical
side); each obstacle looks in the cells its square meets and measures every segment listed
there whose box meets the square, once.

A pair left out has the segment farther from the centre than the reach: the branch-free pass
(:func:`~mawdo.planning.refine.kernel.passes.static_pass`) would find it neither a hit nor near,
so it would count nothing for it. A pair measured gets that pass's very arithmetic: the
division-free distance against the four radii, the exact distance where it falls within the
room of one of them, and the near ones the exact polygon verdicts
(:func:`~mawdo.planning.refine.kernel.passes.near_verdicts`), one obstacle at a time. Every
number is per pair, so the counts are those of the pass over every segment, bit for bit.

Measured on the planner's calls (``benchmarks/log/scaling.md``, 1000 x 1000 px, 200 movers,
populations of 240): the standing obstacles' share of a call falls from 6.3 to 1.6 ms with 1000
of them, from 2.1 to 1.3 ms with 300 and from 1.1 to 0.8 ms with 200; at 100 the two cost
the same, hence :data:`~mawdo.planning.refine.kernel.constants.INDEX_STANDING`. The pass over
every segment is branch-free and vectorised, under a nanosecond per pair.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from mawdo.planning.refine.kernel.constants import MARGIN
from mawdo.planning.refine.kernel.passes import near_verdicts, scaled_d2
from mawdo.planning.refine.kernel.primitives import point_segment_d2
from mawdo.util.cells import cell_lists
from mawdo.util.cells import cell_of as _cell

#: Cells per axis at most.
_CELLS = 256


@njit(cache=True, fastmath=False, error_model="numpy")
def standing_table(moving, ox, oy, obs, acc2, margin):
    """The standing obstacles (``moving[i]`` false) at offsets ``ox, oy`` (pixels), for
    :func:`indexed_standing_pass` with the pass's room ``margin`` (pixels): ``(ids, off, box,
    radii, cell)``. ``off[k]`` is obstacle ``ids[k]``'s offset, ``box[k]`` the square ``(x0,
    y0, x1, y1)`` of its reach about its centre and the centre ``(cx, cy)``, ``radii[k]`` the
    squares of the pass's radii ``(in, out, lo, hi, accept, bounding)``; ``cell`` the side of
    the blocks' grid cells (pixels): twice the squares' geometric mean side."""
    bound = obs[4]
    n = 0
    for i in range(len(moving)):
        n += 0 if moving[i] else 1
    ids = np.empty(n, np.int64)
    off, box, radii = np.empty((n, 2)), np.empty((n, 6)), np.empty((n, 6))
    side = np.empty(n)
    k = 0
    for i in range(len(moving)):
        if moving[i]:
            continue
        ids[k], off[k, 0], off[k, 1] = i, ox[i], oy[i]
        cx, cy, rho, a2 = bound[i, 4] + ox[i], bound[i, 5] + oy[i], bound[i, 6], acc2[i]
        acc = math.sqrt(a2) if a2 > 0.0 else -np.inf  # (as static_pass's radii)
        radii[k, 0] = (acc - margin) * (acc - margin) if acc > margin else -1.0
        radii[k, 1] = (acc + margin) * (acc + margin) if acc > 0.0 else -1.0
        radii[k, 2] = (rho - margin) * (rho - margin) if rho > margin else -1.0
        radii[k, 3] = (rho + margin) * (rho + margin)
        radii[k, 4], radii[k, 5] = a2, rho * rho
        reach = (max(rho, acc) + 2.0 * margin) * (1.0 + MARGIN) + MARGIN * (1.0 + abs(cx) + abs(cy))
        box[k, 0], box[k, 1], box[k, 2], box[k, 3] = cx - reach, cy - reach, cx + reach, cy + reach
        box[k, 4], box[k, 5] = cx, cy
        side[k] = 2.0 * reach
        k += 1
    # cells twice the squares' typical side, their geometric mean (robust to a few long walls;
    # twice it measured best of 0.5, 1, 2 and 4 times; a median costs a sort to compile)
    logs = 0.0
    for k in range(n):
        logs += math.log(side[k])
    return ids, off, box, radii, 2.0 * math.exp(logs / n) if n > 0 else 1.0


@njit(cache=True, fastmath=False, error_model="numpy")
def no_standing_table(moving, ox, oy, obs, acc2, margin):
    """:func:`standing_table`'s empty table (for the kernel without the grid)."""
    return (np.empty(0, np.int64), np.empty((0, 2)), np.empty((0, 6)), np.empty((0, 6)), 1.0)


@njit(cache=True, fastmath=False, error_model="numpy", inline="always")
def _measure(px, py, p, cx, cy, radii, k):
    """Segment p (points p, p + 1) against the radii of obstacle k centred at ``(cx, cy)``:
    ``(hit, near)`` as the branch-free pass decides them (the exact distance within room)."""
    num, den = scaled_d2(px[p] - cx, py[p] - cy, px[p + 1] - cx, py[p + 1] - cy)
    in2, out2, lo2, hi2 = radii[k, 0], radii[k, 1], radii[k, 2], radii[k, 3]
    if (num > in2 * den) & ((num <= out2 * den) | (num > lo2 * den) & (num <= hi2 * den)):
        d = point_segment_d2(cx, cy, px[p], py[p], px[p + 1], py[p + 1])
        return d <= radii[k, 4], d <= radii[k, 5] and not d <= radii[k, 4]
    return num <= in2 * den, (num > out2 * den) & (num <= lo2 * den)


@njit(cache=True, fastmath=False, error_model="numpy")
def segment_grid(npt, px, py, real, cell, grid):
    """The block's real segments (points ``p, p + 1`` of ``px, py``, pixels) listed in the
    cells of ``cell`` pixels (more where there would be over :data:`_CELLS` a side) that their
    boxes meet. ``grid`` is ``(head, ents, sbox)`` from the last block (grown and returned
    where too short): ``head`` the start of each cell's list in ``ents``, ``sbox`` each
    segment's box. Returns ``((gx, gy, ginv, nx, ny), head, ents, sbox)``."""
    head, ents, sbox = grid
    if len(sbox) < npt:
        sbox = np.empty((npt, 4))
    gx, gy, xhi, yhi = np.inf, np.inf, -np.inf, -np.inf
    for p in range(npt - 1):
        sbox[p, 0], sbox[p, 2] = min(px[p], px[p + 1]), max(px[p], px[p + 1])
        sbox[p, 1], sbox[p, 3] = min(py[p], py[p + 1]), max(py[p], py[p + 1])
        if real[p]:
            gx, gy = min(gx, sbox[p, 0]), min(gy, sbox[p, 1])
            xhi, yhi = max(xhi, sbox[p, 2]), max(yhi, sbox[p, 3])
    g = max(cell, max(xhi - gx, yhi - gy) / _CELLS)
    ginv = 1.0 / g
    nx, ny = int((xhi - gx) * ginv) + 1, int((yhi - gy) * ginv) + 1
    if len(head) < nx * ny + 1:
        head = np.empty(nx * ny + 1, np.int64)
    head, ents = cell_lists(sbox, real[: npt - 1], (gx, gy, ginv, nx, ny), head, ents)
    return (gx, gy, ginv, nx, ny), head, ents, sbox


@njit(cache=True, fastmath=False, error_model="numpy")
def indexed_standing_pass(npt, path, work, cls, obs, extra, margin, hits, ncol, table, grid):
    """The hits of a sane block's ``npt`` points' segments on every standing obstacle of
    ``table`` (:func:`standing_table`): sure hits added to ``hits`` per segment, the exact
    polygon verdicts of the near ones to ``ncol`` per candidate, as
    :func:`~mawdo.planning.refine.kernel.passes.static_pass` adds them obstacle by obstacle.
    ``grid`` is the work space of :func:`segment_grid` (``(head, ents, sbox, seen)``); returns
    it, grown where it had to."""
    px, py, flagged, real, cand = path[0], path[1], work[1], work[2], work[3]
    ids, off, box, radii, cell = table
    geo, head, ents, sbox = segment_grid(npt, px, py, real, cell, grid[:3])
    gx, gy, ginv, nx, ny = geo
    seen = grid[3] if len(grid[3]) >= npt else np.empty(npt, np.int64)
    for p in range(npt):
        seen[p] = -1
    for k in range(len(ids)):
        x0, y0, x1, y1, cx0, cy0 = box[k, 0], box[k, 1], box[k, 2], box[k, 3], box[k, 4], box[k, 5]
        if x1 < gx or y1 < gy:
            continue
        nf = np.int64(0)
        for cy in range(_cell(y0, gy, ginv, ny), _cell(y1, gy, ginv, ny) + 1):
            for cx in range(_cell(x0, gx, ginv, nx), _cell(x1, gx, ginv, nx) + 1):
                c = cy * nx + cx
                for e in range(head[c], head[c + 1]):
                    p = ents[e]
                    if seen[p] == k:  # (met in an earlier cell)
                        continue
                    seen[p] = k
                    if sbox[p, 2] < x0 or sbox[p, 0] > x1 or sbox[p, 3] < y0 or sbox[p, 1] > y1:
                        continue
                    hit, near = _measure(px, py, p, cx0, cy0, radii, k)
                    hits[p] += 1 if hit else 0
                    flagged[nf] = p
                    nf += 1 if near else 0
        if nf > 0:
            near_verdicts(ids[k], off[k, 0], off[k, 1], nf, flagged, px, py, cand, cls, obs,
                          extra, margin, ncol)  # fmt: skip
    return head, ents, sbox, seen
