"""The run loop's guide keeps its last query (:class:`mawdo.planning.refine.seeding.RunGuide`): the
answers are the plain guide's, and a repeated position is not searched again."""

import numpy as np

from mawdo.planning import get_scenario
from mawdo.planning.guide.homotopy import Guide
from mawdo.planning.refine.seeding import RunGuide


def test_run_guide_answers_as_the_guide_and_searches_a_repeat_once(monkeypatch):
    sc = get_scenario("paper")
    plain, kept = Guide(sc, clearance=0.5, k=6), RunGuide(sc, clearance=0.5, k=6)
    searched = []
    query = Guide.query

    def counted(self, pos):
        searched.append(np.asarray(pos, dtype=float).tobytes())
        return query(self, pos)

    a, b = np.array([30.0, 40.0]), np.array([120.5, 200.25])
    asks = [a, a, b, a.copy(), b, b]
    expected_routes = [plain.routes(p) for p in asks]
    expected_short = [plain.shortest(p) for p in asks]
    monkeypatch.setattr(Guide, "query", counted)
    for p, routes, short in zip(asks, expected_routes, expected_short, strict=True):
        assert kept.shortest(p) == short
        got = kept.routes(p)
        assert len(got) == len(routes) > 0
        assert all(np.array_equal(x, y) for x, y in zip(got, routes, strict=True))
    # a new search only when the position changes: a, b, a, b
    assert searched == [a.tobytes(), b.tobytes(), a.tobytes(), b.tobytes()]
