"""The sensor: range, occlusion by walls, misses, noise, order, and its parameter checks."""

import math

import numpy as np
import pytest

from mawdo.planning.sense.sensor import Sensor, Walls, sight_points, visible

ROBOT = np.zeros(2)
# a box wall between the robot at the origin and agents around x = 50
WALL = np.array([[20.0, -5.0], [30.0, -5.0], [30.0, 5.0], [20.0, 5.0]])


def read(sensor, centers, radii, walls=(), seed=0, position=ROBOT):
    rng = np.random.default_rng(seed)
    return sensor.read(3, position, (1.0, 0.5), (90.0, 90.0), centers, radii, walls, rng)


def as_set(points):
    return sorted(map(tuple, np.round(np.asarray(points), 9)))


def test_range_counts_the_nearest_point_of_the_disc():
    centers = np.array([[10.0, 0.0], [0.0, -13.0], [14.0, 0.0]])  # gaps 8, 11, 12
    got = read(Sensor(range=11.0), centers, [2.0, 2.0, 2.0])
    assert as_set(got.centers) == as_set(centers[:2])
    assert np.array_equal(np.sort(got.radii), [2.0, 2.0])
    assert len(read(Sensor(), centers, [2.0, 2.0, 2.0]).centers) == 3  # no range limit


def test_the_robot_state_passes_through_exactly():
    got = read(Sensor(noise=3.0), [[10.0, 0.0]], [2.0], position=(1.0, 2.0))
    assert got.step == 3
    assert np.array_equal(got.position, [1.0, 2.0])
    assert np.array_equal(got.velocity, [1.0, 0.5])
    assert np.array_equal(got.goal, [90.0, 90.0])


def test_sight_points_are_the_centre_and_the_two_tangent_points():
    p = np.array([3.0, -2.0])
    c = np.array([[40.0, 17.0], [-25.0, 4.0]])
    r = np.array([4.0, 9.0])
    pts = sight_points(p, c, r)
    assert np.allclose(pts[:, 0], c)
    for i in range(2):
        for t in pts[i, 1:]:
            assert math.isclose(np.hypot(*(t - c[i])), r[i], rel_tol=1e-12)  # on the circle
            assert abs(np.dot(t - p, t - c[i])) < 1e-9  # the sight line grazes it there
        # the two tangents are the extreme directions: the centre's bearing +- asin(r / d)
        d = c[i] - p
        half = math.asin(r[i] / np.hypot(*d))
        bearings = np.arctan2(pts[i, 1:, 1] - p[1], pts[i, 1:, 0] - p[0]) - math.atan2(d[1], d[0])
        bearings = np.angle(np.exp(1j * bearings))  # wrapped to (-pi, pi]
        assert np.allclose(np.sort(np.abs(bearings)), [half, half])
        assert np.sign(bearings[0]) != np.sign(bearings[1])


def test_a_robot_inside_a_disc_looks_at_its_centre():
    pts = sight_points((1.0, 1.0), [[0.0, 0.0]], [5.0])
    assert np.allclose(pts, 0.0)


def test_a_wall_hides_an_agent_unless_part_of_its_disc_shows():
    # centre line y = 0.2 x enters the wall at (20, 4); the upper tangent (slope 0.283) passes
    # above it at (20, 5.66); the lower one (slope 0.120) is blocked: only one point shows
    half = np.array([[50.0, 10.0]])
    hidden = np.array([[50.0, 0.0]])  # slopes 0, +-0.08: all three blocked
    assert visible(ROBOT, half, [4.0], [WALL]).tolist() == [True]
    assert visible(ROBOT, hidden, [4.0], [WALL]).tolist() == [False]
    assert visible(ROBOT, half, [0.5], [WALL]).tolist() == [False]  # a thin one is hidden
    both = np.vstack([half, hidden])
    assert len(read(Sensor(), both, [4.0, 4.0], [WALL]).centers) == 1
    assert len(read(Sensor(occlusion=False), both, [4.0, 4.0], [WALL]).centers) == 2


def test_an_agent_in_front_of_the_wall_is_seen():
    assert visible(ROBOT, [[15.0, 0.0], [35.0, 0.0]], [2.0, 2.0], [WALL]).tolist() == [True, False]


def test_noise_is_gaussian_with_the_given_sd():
    sensor = Sensor(noise=2.0)
    rng = np.random.default_rng(7)
    errors = np.array(
        [
            sensor.read(0, ROBOT, ROBOT, ROBOT, [[30.0, 40.0]], [3.0], [], rng).centers[0]
            for _ in range(4000)
        ]
    ) - [30.0, 40.0]
    # 8000 draws: the sample s.d.'s own s.d. is 2 / sqrt(16000) = 0.016, the mean's 0.022
    assert abs(errors.std() - 2.0) < 0.08
    assert np.all(np.abs(errors.mean(axis=0)) < 0.11)


def test_misses_happen_at_the_given_rate():
    sensor = Sensor(miss_rate=0.3)
    rng = np.random.default_rng(11)
    centers = np.column_stack([np.arange(10.0) * 10.0 + 10.0, np.zeros(10)])
    seen = sum(
        len(sensor.read(0, ROBOT, ROBOT, ROBOT, centers, np.ones(10), [], rng).centers)
        for _ in range(400)
    )
    # 4000 Bernoulli(0.7): s.d. of the share 0.0072
    assert abs(seen / 4000 - 0.7) < 0.03


def test_detections_come_in_random_order_without_losing_any():
    centers = np.array([[10.0 * k, 5.0] for k in range(1, 6)])
    orders = set()
    for seed in range(20):
        got = read(Sensor(), centers, [1.0, 2.0, 3.0, 4.0, 5.0], seed=seed)
        assert as_set(got.centers) == as_set(centers)
        # the radius stays with its agent
        assert np.array_equal(got.radii, got.centers[:, 0] / 10.0)
        orders.add(tuple(got.radii))
    assert len(orders) > 5


def test_same_seed_same_reading_and_draws_do_not_depend_on_what_is_seen():
    centers = np.array([[40.0, 0.0], [-40.0, 0.0], [0.0, 45.0]])
    sensor = Sensor(noise=1.5, range=42.0, miss_rate=0.2)
    a = read(sensor, centers, [1.0, 2.0, 3.0], seed=5)
    b = read(sensor, centers, [1.0, 2.0, 3.0], seed=5)
    assert np.array_equal(a.centers, b.centers) and np.array_equal(a.radii, b.radii)
    # a robot elsewhere sees other agents, but each agent it sees carries the same error
    near = read(sensor, centers, [1.0, 2.0, 3.0], seed=5, position=(0.0, 10.0))
    errors_a = dict(zip(a.radii, a.centers - centers[(a.radii - 1).astype(int)], strict=True))
    errors_near = near.centers - centers[(near.radii - 1).astype(int)]
    shared = [k for k, r in enumerate(near.radii) if r in errors_a]
    assert shared
    for k in shared:
        assert np.array_equal(errors_near[k], errors_a[near.radii[k]])


def test_no_agents_no_detections():
    got = read(Sensor(noise=1.0), np.empty((0, 2)), [], [WALL])
    assert got.centers.shape == (0, 2) and got.radii.shape == (0,)


@pytest.mark.parametrize(
    ("kwargs", "field"),
    [
        ({"noise": -1.0}, "noise"),
        ({"noise": float("nan")}, "noise"),
        ({"miss_rate": 1.0}, "miss_rate"),
        ({"miss_rate": -0.1}, "miss_rate"),
        ({"range": 0.0}, "range"),
        ({"range": -math.inf}, "range"),
        ({"range": "10"}, "range"),
        ({"occlusion": "yes"}, "occlusion"),
    ],
)
def test_bad_parameters_name_the_field_and_the_fix(kwargs, field):
    with pytest.raises(ValueError, match=field) as err:
        Sensor(**kwargs)
    assert "must be" in str(err.value)


def test_an_unlimited_range_is_inf():
    assert Sensor(range=math.inf).range == math.inf
    assert Sensor(range=5).range == 5.0
    assert "inf for an unlimited range" in str(pytest.raises(ValueError, Sensor, range=0).value)


def test_the_random_source_must_be_a_generator():
    with pytest.raises(TypeError, match="default_rng"):
        Sensor().read(0, ROBOT, ROBOT, ROBOT, [[1.0, 1.0]], [1.0], [], 42)


def test_radii_must_match_centres():
    with pytest.raises(ValueError, match="radii"):
        read(Sensor(), [[1.0, 2.0], [3.0, 4.0]], [1.0])


def test_prebuilt_walls_give_the_same_readings():
    ring = 30.0 + 6.0 * np.column_stack(
        [np.cos(np.arange(32) / 16 * np.pi), np.sin(np.arange(32) / 16 * np.pi)]
    )
    walls = [WALL, ring + (0.0, 30.0)]  # a box and a round pillar centred at (30, 60)
    built = Walls(walls)
    assert Walls.of(built) is built and len(built) == 2
    centers = np.array([[50.0, 10.0], [50.0, 0.0], [60.0, 120.0], [15.0, 0.0], [-40.0, 5.0]])
    radii = np.array([4.0, 4.0, 3.0, 2.0, 2.0])
    # (60, 120) is straight behind the pillar: slope 2, the pillar's centre (30, 60) on that line
    expect = [True, False, False, True, True]
    assert visible(ROBOT, centers, radii, walls).tolist() == expect
    assert visible(ROBOT, centers, radii, built).tolist() == expect
    a = read(Sensor(noise=1.0), centers, radii, walls, seed=4)
    b = read(Sensor(noise=1.0), centers, radii, built, seed=4)
    assert np.array_equal(a.centers, b.centers) and len(a.centers) == 3


def _crosses(p, q, a, b):
    """Segments pq and ab cross properly (general position: no touching, no collinearity)."""

    def side(o, s, t):
        return np.sign((s[0] - o[0]) * (t[1] - o[1]) - (s[1] - o[1]) * (t[0] - o[0]))

    return side(p, q, a) != side(p, q, b) and side(a, b, p) != side(a, b, q)


def test_visibility_agrees_with_a_loop_over_sight_lines_and_wall_edges():
    # random triangles away from the robot; a sight line is blocked when it crosses an edge
    # (its far end is never inside a wall here: the agents sit outside every triangle's box)
    rng = np.random.default_rng(9)
    walls = [rng.uniform(-60, 60, 2) + rng.uniform(-8, 8, (3, 2)) for _ in range(25)]
    walls = [w for w in walls if np.hypot(*w.mean(axis=0)) > 15]
    boxes = [(w.min(axis=0), w.max(axis=0)) for w in walls]
    centers, radii = [], []
    while len(centers) < 60:
        c, r = rng.uniform(-80, 80, 2), rng.uniform(0.5, 3.0)
        if all(np.any(c + r < lo) or np.any(c - r > hi) for lo, hi in boxes):
            centers.append(c)
            radii.append(r)
    pts = sight_points(ROBOT, centers, radii)
    expect = [
        any(
            not any(_crosses(ROBOT, end, w[k], w[(k + 1) % 3]) for w in walls for k in range(3))
            for end in pts[i]
        )
        for i in range(len(centers))
    ]
    got = visible(ROBOT, centers, radii, walls)
    assert got.tolist() == expect
    assert 5 < sum(expect) < len(expect) - 5, sum(expect)  # both outcomes are exercised
