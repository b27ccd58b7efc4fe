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


def _map(seed: int):
    rng = np.random.default_rng(seed)
    polys = []
    for _ in range(12):
        c = rng.uniform(30, 270, 2)
        ang = np.sort(rng.uniform(0, 2 * np.pi, int(rng.integers(3, 7))))
        r = rng.uniform(8, 25, len(ang))
        polys.append(shapely.Polygon(c + np.c_[r * np.cos(ang), r * np.sin(ang)]).convex_hull)
    return build(polys, (0.0, 0.0, 300.0, 300.0))


@pytest.mark.parametrize("seed", range(3))
def test_ring_line_test_keeps_every_answer_of_the_plain_loop(seed):
    g = _map(seed)
    rng = np.random.default_rng(50 + seed)
    corners = g.nodes
    segs = [(rng.uniform(0, 300, 2), rng.uniform(0, 300, 2)) for _ in range(1500)]
    pairs = rng.integers(0, len(corners), (1500, 2))
    segs += [(corners[i], corners[j]) for i, j in pairs]
    # along a blocking edge (extended past it) and through one end of it: touching cases
    for e in g.edges[rng.integers(0, len(g.edges), 300)]:
        a, b = e[:2], e[2:]
        segs += [(a - 0.5 * (b - a), b + 0.5 * (b - a)), (a, a + rng.uniform(-30, 30, 2))]
    blocked = 0
    for p, q in segs:
        p, q = np.asarray(p, float), np.asarray(q, float)
        got = segment_visible(p[0], p[1], q[0], q[1], g.edges, g.ring_ptr, g.ring_box)
        assert got == _plain(p, q, g.edges), (p, q)
        blocked += not got
    assert 0.2 * len(segs) < blocked < 0.9 * len(segs)  # both answers are exercised
