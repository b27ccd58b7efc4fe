"""The cost kernel's collision counts, pinned before its speed work (issue 15).

The counts themselves are checked against shapely in ``test_cost.py`` on smaller samples; this
test pins *every* count of a large sample (random and near-optimal populations of the paper
scenario, both modes, several planning times) by a sha256 of the count arrays as the verified
kernel produced them, so that a faster kernel must give the very same counts, not merely
counts that agree with shapely where it was sampled. Regenerate the digest only after a change
that is meant to alter counts, and say why in the commit.

Issue 30 made the map's border a wall: segments whose disc leaves the map now count too. The
digest still pins the obstacle counts of the verified kernel: the border's share, counted
independently by shapely (``reference.border_hits``), is taken off first, and must be a part of
the sample (random candidates put waypoints within the radius of the border).
"""

import hashlib

import numpy as np

from mawdo.planning import PathCost, get_scenario, scenario_optimum
from mawdo.planning.refine.cost import assemble_paths
from mawdo.planning.world.path import densify

from .reference import border_hits

# sha256 of the n_collisions arrays (int64, little-endian) in the order of _count_arrays()
PINNED = "4d9402e0a9e5061a19e38d9a16cd87c65d9c622f03e1518d39c8b4b5f34d73d0"


def _count_arrays():
    sc = get_scenario("paper")
    route = densify(scenario_optimum(sc).path, 20).reshape(-1)
    costs = {mode: PathCost(sc, mode=mode) for mode in ("snapshot", "spacetime")}
    for seed in range(3):
        rng = np.random.default_rng(seed)
        pops = (
            rng.uniform(0, 366, (1360, 40)),  # random
            route + rng.normal(0, 3.0, (1360, 40)),  # near the optimum
            route + rng.normal(0, 15.0, (500, 40)),  # around it
        )
        for mode, cost in costs.items():
            for X in pops:
                border = border_hits(sc, assemble_paths(X, sc.start, sc.goal))
                for t0 in (0.0, 5.0, 37.5, 120.0):
                    _, ncol, _ = cost.parts(X, t0=t0)
                    yield mode, ncol - border, border


def test_collision_counts_are_those_of_the_verified_kernel():
    h = hashlib.sha256()
    values = set()
    at_border = 0
    for _mode, ncol, border in _count_arrays():
        h.update(np.ascontiguousarray(ncol, dtype="<i8").tobytes())
        values.update(np.unique(ncol).tolist())
        at_border += int(np.count_nonzero(border))
    assert len(values) > 10  # a sample with few hits and many, not one count everywhere
    assert at_border > 1000  # and the border's share was there to take off
    assert h.hexdigest() == PINNED
