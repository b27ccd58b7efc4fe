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


def test_seed_rows_are_the_densified_routes_and_made_once_per_position(monkeypatch):
    from mawdo.planning.world import path

    sc = get_scenario("paper")
    plain, kept = Guide(sc, clearance=0.5, k=6), RunGuide(sc, clearance=0.5, k=6)
    a, b = np.array([30.0, 40.0]), np.array([120.5, 200.25])
    made = []
    assembled = Guide.routes

    def counted(self, pos):
        made.append(np.asarray(pos, dtype=float).tobytes())
        return assembled(self, pos)

    monkeypatch.setattr(Guide, "routes", counted)
    for p, m in ((a, 10), (a, 10), (a, 12), (b, 10), (b, 10)):
        rows = kept.seed_rows(p, m)
        want = [path.densify(r, m).reshape(-1) for r in assembled(plain, p)]
        assert len(rows) == len(want) > 0
        assert all(np.array_equal(x, y) for x, y in zip(rows, want, strict=True))
    # the routes are assembled once per position (a new m densifies them again)
    assert made == [a.tobytes(), b.tobytes()]
