"""The visibility test of the tangent graph skips the rings whose box lies wholly on one side of
the segment's line: its answers are those of the test of every edge of every ring (a plain loop
here), on random polygon maps, for random segments, corner-to-corner segments (the graph's own,
touching at both ends) and segments sliding along an edge or through a corner."""

from __future__ import annotations

import numpy as np
import pytest
import shapely

from mawdo.planning.guide.visgraph import build
from mawdo.planning.guide.visgraph_kernels import _seg_hits, segment_visible


def _plain(p, q, edges) -> bool:
    """Every edge, no box tests."""
    return not any(_seg_hits(p[0], p[1], q[0], q[1], *e) for e in edges)


def _map(seed: int, n: int = 12, radii=(8, 25), walls=()):
    """A map of ``n`` random convex polygons (radii in ``radii``, pixels) and ``walls``."""
    rng = np.random.default_rng([9, seed] if walls else seed)
    polys = list(walls)
    for _ in range(n):
        c = rng.uniform(30, 270, 2) if not walls else rng.uniform(10, 290, 2)
        ang = np.sort(rng.uniform(0, 2 * np.pi, int(rng.integers(3, 7 if not walls else 6))))
        r = rng.uniform(*radii, len(ang))
        polys.append(shapely.Polygon(c + np.c_[r * np.cos(ang), r * np.sin(ang)]).convex_hull)
    return build(polys, (0.0, 0.0, 300.0, 300.0))


def _against_plain_loop(g, rng, segs, grid=None) -> None:
    """``segs`` plus corner-to-corner segments and segments along a blocking edge (extended
    past it) and through one end of it (touching cases): each answer equals the plain loop's,
    and both answers occur."""
    segs = segs + [(g.nodes[i], g.nodes[j]) for i, j in rng.integers(0, len(g.nodes), (1500, 2))]
    for e in g.edges[rng.integers(0, len(g.edges), 300)]:
        a, b = e[:2], e[2:]
        segs += [(a - 0.5 * (b - a), b + 0.5 * (b - a)), (a, a + rng.uniform(-30, 30, 2))]
    blocked = 0
    for p, q in segs:
        p, q = np.asarray(p, float), np.asarray(q, float)
        got = segment_visible(p[0], p[1], q[0], q[1], g.edges, g.ring_ptr, g.ring_box, grid)
        assert got == _plain(p, q, g.edges), (p, q)
        blocked += not got
    assert 0.2 * len(segs) < blocked < 0.9 * len(segs)  # both answers are exercised


@pytest.mark.parametrize("seed", range(3))
def test_ring_line_test_keeps_every_answer_of_the_plain_loop(seed):
    g = _map(seed)
    rng = np.random.default_rng(50 + seed)
    _against_plain_loop(
        g, rng, [(rng.uniform(0, 300, 2), rng.uniform(0, 300, 2)) for _ in range(1500)]
    )


def _many(seed: int):
    """Many small rings (past RING_GRID), touching ones merged, and one long wall."""
    return _map(seed, 150, (2, 9), walls=[shapely.box(40, 148, 260, 152)])


@pytest.mark.parametrize("seed", range(2))
def test_the_rings_grid_keeps_every_answer_of_the_plain_loop(seed):
    # from RING_GRID rings on a segment asks only the rings listed in the cells it crosses:
    # random, corner-to-corner, axis-parallel and edge-sliding segments, and a whole graph's
    # edges, against the plain loop and against the test of every ring
    from mawdo.planning.guide.visgraph import RING_GRID
    from mawdo.planning.guide.visgraph_kernels import tangent_edges, visible_from_point

    g = _many(seed)
    assert g.grid is not None and len(g.ring_box) >= RING_GRID
    rng = np.random.default_rng(70 + seed)
    segs = [(rng.uniform(-5, 305, 2), rng.uniform(-5, 305, 2)) for _ in range(1500)]
    for _ in range(300):  # horizontal and vertical, on and off the cells' lines
        a = rng.uniform(0, 300, 2)
        segs += [(a, np.array([rng.uniform(0, 300), a[1]])), (a, np.array([a[0], 150.0]))]
    _against_plain_loop(g, rng, segs, g.grid)
    args = (g.nodes, g.prev, g.nxt, g.corner, g.edges, g.ring_ptr, g.ring_box, g.eps2)
    with_grid, without = tangent_edges(*args, g.grid), tangent_edges(*args)
    for a, b in zip(with_grid, without, strict=True):
        assert np.array_equal(a, b)
    for p in rng.uniform(0, 300, (40, 2)):
        assert np.array_equal(visible_from_point(p, *args, g.grid), visible_from_point(p, *args))
