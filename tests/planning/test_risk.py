"""The collision-risk term: the contact probability against hand values and Monte Carlo, the
compiled table against scipy's exact CDF, the compiled sum against a NumPy walk of the same
paths, the cost's bookkeeping, the checks of its input, and the planner handing a prediction's
uncertainty to it."""

import math

import numpy as np
import pytest

from mawdo.planning.refine.comfort import ComfortPathCost
from mawdo.planning.refine.cost import PathCost
from mawdo.planning.refine.kernel.risk import contact_probability, expected_contacts, rice_table
from mawdo.planning.refine.risk import RiskPathCost, overlap_probability
from mawdo.planning.refine.terms import ComfortRiskPathCost, cost_class
from mawdo.planning.run.config import PlannerConfig
from mawdo.planning.world.scenario import scenario_from_dict
from mawdo.planning.world.stepped import with_movers
from mawdo.planning.world.uncertainty import Uncertainty, centre_sd


@pytest.fixture(scope="module")
def table():
    return rice_table()


def test_the_probability_has_the_hand_values():
    # at d = 0 the Rice CDF is the Rayleigh CDF 1 - exp(-R^2 / (2 s^2))
    for r, s in [(1.0, 1.0), (3.0, 2.0), (0.5, 4.0)]:
        assert overlap_probability(0.0, r, s) == pytest.approx(1 - math.exp(-(r * r) / (2 * s * s)))
    assert overlap_probability(9.9, 10.0, 0.0) == 1.0  # certainty: inside
    assert overlap_probability(10.1, 10.0, 0.0) == 0.0  # and outside
    assert overlap_probability(10.0 + 7 * 2.0, 10.0, 2.0) == 0.0  # beyond 6 s.d.s
    # far inside the disc the point is there for sure; on a long straight edge, half the time
    assert overlap_probability(0.0, 60.0, 1.0) == pytest.approx(1.0)
    assert overlap_probability(1000.0, 1000.0, 1.0) == pytest.approx(0.5, abs=1e-3)


def test_the_probability_matches_monte_carlo():
    rng = np.random.default_rng(5)
    n = 400_000
    for d, r, s in [(3.0, 2.0, 1.5), (8.0, 5.0, 2.0), (1.0, 0.5, 3.0), (12.0, 10.0, 0.7)]:
        pts = rng.normal(0.0, s, size=(n, 2)) + [d, 0.0]
        mc = np.mean(np.hypot(*pts.T) < r)
        assert overlap_probability(d, r, s) == pytest.approx(mc, abs=4 * math.sqrt(0.25 / n))


def test_the_compiled_table_reads_the_exact_cdf_to_a_thousandth(table):
    rng = np.random.default_rng(2)
    d = rng.random(20_000) * 60.0
    r = rng.random(20_000) * 15.0 + 0.5
    s = rng.random(20_000) ** 2 * 20.0  # from far sharper than the disc (R / s > 40) to vaguer
    exact = overlap_probability(d, r, s)
    read = np.array([contact_probability(*v, table) for v in zip(d, r, s, strict=True)])
    assert (r / s).max() > 100.0 and (r / s).min() < 0.1
    assert np.abs(read - exact).max() < 1e-3
    assert contact_probability(4.0, 5.0, 0.0, table) == 1.0
    assert contact_probability(6.0, 5.0, 0.0, table) == 0.0


def _walk(paths, speed, k):
    """Where the robot is after 1..k steps on each path, and whether it is still driving
    (a NumPy walk: arc lengths, segment by search)."""
    seg = np.diff(paths, axis=1)
    length = np.hypot(seg[..., 0], seg[..., 1])
    cum = np.concatenate([np.zeros((len(paths), 1)), np.cumsum(length, axis=1)], axis=1)
    arc = speed * np.arange(1.0, k + 1.0)
    pos = np.empty((len(paths), k, 2))
    for i in range(len(paths)):
        for j, a in enumerate(arc):
            x = np.interp(a, cum[i], paths[i, :, 0])
            y = np.interp(a, cum[i], paths[i, :, 1])
            pos[i, j] = x, y
    return pos, arc[None, :] < cum[:, -1:]


def test_the_compiled_sum_is_the_walk_of_the_path(table):
    rng = np.random.default_rng(3)
    n, m, k, a = 30, 6, 32, 4
    X = rng.random((n, 2 * m)) * 160.0
    X[:4, 4:8] = X[:4, 0:4]  # repeated waypoints: segments of zero length
    X[5] = np.linspace(12.0, 148.0, 2 * m)  # a short path: it arrives within the steps
    start, goal = np.array([10.0, 10.0]), np.array([150.0, 150.0])
    centres = rng.random((k, a, 2)) * 160.0
    sd = np.linspace(0.3, 15.0, k)[:, None] * rng.random(a)[None, :]
    reach = rng.random(a) * 8.0 + 6.0
    out = np.zeros(n)
    expected_contacts(X, start, goal, 7.0, centres, reach, sd, table, out)
    paths = np.concatenate([start[None, None].repeat(n, 0), X.reshape(n, m, 2),
                            goal[None, None].repeat(n, 0)], axis=1)  # fmt: skip
    pos, driving = _walk(paths, 7.0, k)
    dist = np.hypot(*(pos[:, :, None, :] - centres[None]).transpose(3, 0, 1, 2))
    ref = np.where(driving[..., None], overlap_probability(dist, reach, sd[None]), 0.0)
    assert not driving[5].all() and driving[6:].all()
    np.testing.assert_allclose(out, ref.sum(axis=(1, 2)), atol=1e-3 * k * a)
    assert out.max() > 0.5  # the paths do meet the agents
    X[7, 3] = np.nan
    expected_contacts(X, start, goal, 7.0, centres, reach, sd, table, out)
    assert math.isnan(out[7]) and np.isfinite(np.delete(out, 7)).all()


def _scene():
    return scenario_from_dict({
        "schema_version": 1, "name": "risk", "width": 200.0, "height": 140.0,
        "start": [20.0, 70.0], "goal": [180.0, 70.0], "robot": {"radius": 4.0, "speed": 4.0},
        "obstacles": [],
    })  # fmt: skip


def _predicted(spread=(5.0, 1.0, 0.2, 0.2), y=101.0):
    """A person standing at (100, y), predicted with the given spread, in the empty scene."""
    times, centres = np.array([0.0, 200.0]), np.array([[100.0, y], [100.0, y]])
    return with_movers(_scene(), [6.0], [(times, centres)], spreads=[spread])


def test_a_prediction_scenario_carries_its_movers_spread():
    sc = _predicted()
    u = sc.uncertainty
    assert list(u.index) == [0] and u.radius[0] == 5.0 and u.origin == 0.0
    tau = np.array([0.0, 1.0, 4.0, 30.0])
    np.testing.assert_array_equal(u.sd(tau)[:, 0], centre_sd(1.0, 0.2, 0.2, tau))
    # the bound by hand at 4 steps: 1 + 4 (0.2) + 0.2 sqrt(64 / 3 - 1 / 3)
    assert u.sd([4.0])[0, 0] == pytest.approx(1.8 + 0.2 * math.sqrt(21.0))
    assert (
        with_movers(_scene(), [6.0], [(np.array([0.0, 1.0]), np.zeros((2, 2)))]).uncertainty is None
    )
    with pytest.raises(ValueError, match="radius must be > 0"):
        Uncertainty([0], [0.0], [1.0], [1.0], [1.0])
    with pytest.raises(ValueError, match="position_sd must be finite and >= 0"):
        Uncertainty([0], [1.0], [-1.0], [1.0], [1.0])


def test_the_risk_costs_its_weight_per_expected_contact_and_nothing_else_changes():
    sc = _predicted()
    paper = PathCost(sc, "spacetime", n_waypoints=1, clearance=0.5)
    risky = RiskPathCost(sc, "spacetime", n_waypoints=1, clearance=0.5, risk_weight=50.0)
    # one waypoint above the straight line (toward the person, 13 px from its centre) or
    # below (the mirror image, 49 px away): equally long, both clear of the predicted disc
    X = np.array([[100.0, 88.0], [100.0, 52.0]])
    e = risky.expected_contacts(X)
    assert e[0] > 0.5 and e[1] < 0.2 * e[0]  # (far ahead, the spread reaches below too)
    np.testing.assert_allclose(risky(X) - paper(X), 0.45 * 50.0 * e, rtol=1e-12)
    for a, b in zip(paper.parts(X), risky.parts(X), strict=True):  # the paper's terms
        assert np.array_equal(a, b)
    assert risky.expected_contacts(X[0]) == pytest.approx(e[0])  # one candidate: a float
    assert isinstance(risky(X[0]), float)
    # a sharper prediction of the same person is a smaller risk for the pass above
    sharp = RiskPathCost(_predicted((5.0, 0.2, 0.0, 0.0)), n_waypoints=1, risk_weight=50.0)
    assert sharp.expected_contacts(X[0]) < e[0]
    # known motions carry no risk: the paper's cost
    plain = RiskPathCost(_scene(), n_waypoints=1, risk_weight=50.0)
    assert np.array_equal(plain(X), PathCost(_scene(), "spacetime", n_waypoints=1)(X))


def test_comfort_and_risk_add_up():
    sc = _predicted()
    opts = {"n_waypoints": 1, "clearance": 0.5}
    X = np.array([[100.0, 88.0], [100.0, 52.0], [60.0, 75.0]])
    base = PathCost(sc, "spacetime", **opts)(X)
    comfy = ComfortPathCost(sc, "spacetime", comfort=6.0, comfort_weight=8.0, **opts)(X)
    risky = RiskPathCost(sc, "spacetime", risk_weight=50.0, **opts)(X)
    both = ComfortRiskPathCost(sc, "spacetime", comfort=6.0, comfort_weight=8.0,
                               risk_weight=50.0, **opts)(X)  # fmt: skip
    np.testing.assert_allclose(both, comfy + risky - base, rtol=1e-12)
    assert cost_class() is PathCost and cost_class(comfort=1.0) is ComfortPathCost
    assert cost_class(risk_weight=1.0) is RiskPathCost
    assert cost_class(comfort=1.0, risk_weight=1.0) is ComfortRiskPathCost


def test_risk_input_is_checked():
    sc = _predicted()
    with pytest.raises(ValueError, match="risk term needs mode='spacetime'"):
        RiskPathCost(sc, "snapshot", risk_weight=1.0)
    with pytest.raises(ValueError, match="risk_weight must be finite and >= 0"):
        RiskPathCost(sc, risk_weight=-1.0)
    with pytest.raises(ValueError, match="risk_reach must be an integer >= 1"):
        RiskPathCost(sc, risk_weight=1.0, risk_reach=0)
    with pytest.raises(ValueError, match="PlannerConfig.risk=-1"):
        PlannerConfig(risk=-1.0)
    with pytest.raises(ValueError, match="PlannerConfig.risk_reach"):
        PlannerConfig(risk_reach=0)


def test_the_horizon_bounds_the_steps_summed():
    sc = _predicted()
    X = np.array([[100.0, 88.0]])
    full = RiskPathCost(sc, n_waypoints=1, risk_weight=1.0).expected_contacts(X)
    # the pass above the person comes at about 20 steps (80 px at 4 px per step)
    early = RiskPathCost(sc, n_waypoints=1, risk_weight=1.0, horizon=10.0)
    assert early.expected_contacts(X)[0] < 0.01 * full[0]


def test_the_refiner_passes_an_uncertain_person_on_the_far_side_when_asked():
    # two equally short ways round a block; a person predicted standing above it, vaguely
    from mawdo.planning.run.planner import plan

    block = {"shape": "polygon", "vertices": [[90, 55], [110, 55], [110, 85], [90, 85]]}
    base = _scene()
    sc0 = scenario_from_dict({**base.to_dict(), "obstacles": [block]})
    times, centres = np.array([0.0, 200.0]), np.array([[100.0, 101.0], [100.0, 101.0]])
    sc = with_movers(sc0, [6.0], [(times, centres)], spreads=[(5.0, 1.0, 0.2, 0.2)])
    for seed in (0, 1):
        plain = plan(sc, "mawdo", seed=seed, config="quick")
        wary = plan(sc, "mawdo", seed=seed, config="quick", risk=50.0)
        assert plain.success and wary.success and wary.collision_free
        height = [float(np.interp(100.0, r.route[:, 0], r.route[:, 1])) for r in (plain, wary)]
        assert height[0] > 85.0  # above: by the person, clear of its predicted disc
        assert height[1] < 55.0  # below: the far side


def test_the_observing_planner_hands_its_prediction_spread_to_the_cost():
    from mawdo.planning.run.policy import PlannerPolicy
    from mawdo.planning.sense.predict import K_SD
    from mawdo.planning.sense.reading import Reading

    walker = {"shape": "circle", "center": [150.0, 60.0], "radius": 8.0,
              "motion": {"velocity": [-2.5, 0.0]}}  # fmt: skip
    sc = scenario_from_dict({**_scene().to_dict(), "obstacles": [walker]})
    policy = PlannerPolicy("mawdo", "quick", "observed", time_guide=True, risk=50.0)
    policy.reset(sc, 0)
    for step, x in enumerate((150.0, 147.5)):
        reading = Reading(step, np.array([20.0, 70.0]), np.zeros(2), np.array([180.0, 70.0]),
                          np.array([[x, 60.0]]), np.array([8.0]))  # fmt: skip
        pred = policy.prediction(reading)
    u = pred.uncertainty
    mover = pred.obstacles[int(u.index[0])]
    assert mover.id.startswith("track-") and u.radius[0] == 8.0
    # the predicted disc is the agent grown by k_sd s.d.s at the tube's look-ahead (5 steps)
    assert mover.shape.radius == pytest.approx(8.0 + K_SD * u.sd([5.0])[0, 0], rel=1e-12)
    assert u.velocity_sd[0] > 0.0 and u.accel_sd[0] == 0.2
