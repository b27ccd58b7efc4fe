"""Scenario schema, validation messages, loaders, registry and the built-in `paper` map."""

import copy
import json

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from mawdo.planning import (
    SCENARIOS,
    PathCost,
    ScenarioError,
    check_static_path,
    check_trajectory,
    get_scenario,
    load_scenario,
    scenario_from_dict,
    scenario_optimum,
)
from mawdo.planning.world.scenario import CircleObstacle, PolygonObstacle
from mawdo.registry import UnknownNameError


def base() -> dict:
    return {
        "schema_version": 1,
        "name": "t",
        "width": 200.0,
        "height": 100.0,
        "start": [10.0, 10.0],
        "goal": [190.0, 90.0],
        "robot": {"radius": 2.0, "speed": 3.0},
        "obstacles": [
            {"shape": "circle", "center": [100.0, 50.0], "radius": 10.0},
            {"shape": "polygon", "vertices": [[40, 40], [60, 40], [50, 70]]},
            {"shape": "circle", "center": [150, 30], "radius": 5, "motion": {"velocity": [1, 0]}},
        ],
    }


def errors_of(data) -> list[tuple[str, str]]:
    with pytest.raises(ScenarioError) as info:
        scenario_from_dict(data)
    return info.value.errors


def test_a_valid_dict_builds_a_scenario_that_round_trips():
    sc = scenario_from_dict(base())
    assert (sc.width, sc.height) == (200.0, 100.0)
    assert sc.robot_radius == 2.0 and sc.robot_speed == 3.0
    assert [o.id for o in sc.obstacles] == ["obstacle-0", "obstacle-1", "obstacle-2"]
    assert sc.static_indices == [0, 1] and sc.moving_indices == [2]
    again = scenario_from_dict(sc.to_dict())
    assert again.spec == sc.spec
    # a motion table without `model` is the default moving model
    assert sc.spec.obstacles[2].motion.model == "constant_velocity"


@pytest.mark.parametrize(
    ("mutate", "path", "fragment"),
    [
        (lambda d: d["obstacles"][0].update(radius=0), "obstacles[0].radius", "must be > 0"),
        (lambda d: d["obstacles"][0].update(radius=-3), "obstacles[0].radius", "must be > 0"),
        (lambda d: d.update(width=0), "width", "must be > 0"),
        (lambda d: d.update(height=-5), "height", "must be > 0"),
        (lambda d: d["robot"].update(speed=0), "robot.speed", "must be > 0"),
        (lambda d: d["robot"].update(radius=-1), "robot.radius", "must be >= 0"),
        (lambda d: d.update(start=[-1.0, 10.0]), "start", "outside the map"),
        (lambda d: d.update(goal=[10.0, 101.0]), "goal", "outside the map"),
        (lambda d: d.update(goal=[100.0, 55.0]), "goal", "inside obstacles[0]"),
        # within the robot radius of the circle's edge counts as inside the inflated obstacle
        (lambda d: d.update(start=[100.0, 61.5]), "start", "inflated by the robot radius"),
        (lambda d: d.update(start=[50.0, 50.0]), "start", "inside obstacles[1]"),
        (lambda d: d.update(start=[151.0, 30.0]), "start", "inside obstacles[2]"),
        (
            lambda d: d["obstacles"][1].update(vertices=[[1, 1], [2, 2]]),
            "obstacles[1].vertices",
            "at least 3",
        ),
        (
            lambda d: d["obstacles"][1].update(vertices=[[0, 0], [10, 10], [10, 0], [0, 10]]),
            "obstacles[1].vertices",
            "not simple",
        ),
        (
            lambda d: d["obstacles"][1].update(vertices=[[0, 0], [5, 5], [10, 10]]),
            "obstacles[1].vertices",
            "not simple",
        ),
        (
            lambda d: d["obstacles"][2].update(
                motion={"model": "patrol", "waypoints": [[1, 1]], "speed": -1}
            ),
            "obstacles[2].motion.speed",
            "must be >= 0",
        ),
        (
            lambda d: d["obstacles"][2].update(motion={"model": "teleport"}),
            "obstacles[2].motion",
            "model must be one of",
        ),
        (lambda d: d["obstacles"][0].update(shape="blob"), "obstacles[0]", "circle"),
        (lambda d: d["obstacles"][0].update(colour="red"), "obstacles[0].colour", "unknown field"),
        (lambda d: d.update(schema_version=2), "schema_version", "unsupported schema version"),
        (lambda d: d.pop("start"), "start", "required"),
        (lambda d: d.update(width=float("nan")), "width", "finite"),
        (lambda d: d["obstacles"][2].update(center=[197, 30]), "obstacles[2]", "inside the map"),
        (
            lambda d: d["obstacles"][2].update(
                motion={"model": "patrol", "waypoints": [[100, 0]], "speed": 1}
            ),
            "obstacles[2].motion.waypoints[0]",
            "outside the map",
        ),
        (
            lambda d: [o.update(id="same") for o in d["obstacles"][:2]],
            "obstacles[1].id",
            "duplicate id",
        ),
    ],
)
def test_bad_input_names_the_field(mutate, path, fragment):
    data = base()
    mutate(data)
    errors = errors_of(data)
    assert any(p == path and fragment in m for p, m in errors), errors
    # the message carries the path too, in the documented "path: message" form
    with pytest.raises(ValueError, match=path.replace("[", r"\[").replace("]", r"\]")):
        scenario_from_dict(data)


def test_all_errors_are_reported_at_once():
    data = base()
    data["obstacles"][0]["radius"] = 0
    data["obstacles"][1]["vertices"] = [[1, 1]]
    data["width"] = -1
    paths = {p for p, _ in errors_of(data)}
    assert {"obstacles[0].radius", "obstacles[1].vertices", "width"} <= paths


def test_non_dict_input_is_a_scenario_error():
    assert errors_of([1, 2, 3])[0][1].startswith("expected a table")


def test_load_toml_and_json(tmp_path):
    toml = tmp_path / "s.toml"
    toml.write_text(
        "schema_version = 1\nstart = [5.0, 5.0]\ngoal = [300.0, 300.0]\n"
        '[[obstacles]]\nshape = "circle"\ncenter = [100.0, 100.0]\nradius = 20.0\n'
    )
    sc = load_scenario(toml)
    assert sc.width == 366.0 and len(sc.obstacles) == 1
    js = tmp_path / "s.json"
    js.write_text(json.dumps(sc.to_dict()))
    assert load_scenario(js).spec == sc.spec


def test_loader_errors_are_clear(tmp_path):
    bad = tmp_path / "bad.toml"
    bad.write_text("schema_version = = 1")
    with pytest.raises(ScenarioError, match="cannot parse TOML"):
        load_scenario(bad)
    other = tmp_path / "s.yaml"
    other.write_text("a: 1")
    with pytest.raises(ScenarioError, match="unsupported file type"):
        load_scenario(other)
    with pytest.raises(FileNotFoundError, match="no such scenario file"):
        load_scenario(tmp_path / "missing.toml")
    invalid = tmp_path / "invalid.json"
    invalid.write_text(json.dumps({**base(), "width": 0}))
    with pytest.raises(ScenarioError, match=r"invalid\.json.*\n  width: must be > 0"):
        load_scenario(invalid)


def test_registry_and_unknown_names():
    assert "paper" in SCENARIOS
    assert get_scenario("PAPER").name == "paper"
    with pytest.raises(UnknownNameError, match="Did you mean 'paper'"):
        get_scenario("papr")


def test_get_scenario_also_takes_a_path(tmp_path):
    path = tmp_path / "mine.json"
    path.write_text(json.dumps(base()))
    assert get_scenario(str(path)).width == 200.0
    assert get_scenario(path).width == 200.0
    with pytest.raises(TypeError, match="must be a string"):
        get_scenario(3)


# --- property tests: malformed input never crashes, it raises ScenarioError ----------------

json_values = st.recursive(
    st.none()
    | st.booleans()
    | st.integers(-(10**20), 10**20)
    | st.floats(allow_nan=True, allow_infinity=True)
    | st.text(max_size=8),
    lambda children: (
        st.lists(children, max_size=4) | st.dictionaries(st.text(max_size=8), children, max_size=4)
    ),
    max_leaves=12,
)
keys = st.sampled_from(
    ["schema_version", "start", "goal", "width", "height", "robot", "obstacles", "seed", "x"]
)


@given(st.dictionaries(keys, json_values, max_size=8))
@settings(max_examples=150, deadline=None)
def test_random_dicts_raise_a_validation_error_not_a_crash(data):
    try:
        scenario_from_dict(data)
    except ScenarioError as exc:
        assert exc.errors and all(isinstance(p, str) and m for p, m in exc.errors)


def _leaf_paths(obj, prefix=()):
    if isinstance(obj, dict):
        for k, v in obj.items():
            yield from _leaf_paths(v, (*prefix, k))
    elif isinstance(obj, list):
        for i, v in enumerate(obj):
            yield from _leaf_paths(v, (*prefix, i))
    yield prefix


PAPER = get_scenario("paper").to_dict()
PAPER_PATHS = [p for p in _leaf_paths(PAPER) if p]


@given(
    where=st.sampled_from(PAPER_PATHS),
    value=json_values,
    delete=st.booleans(),
)
@settings(max_examples=200, deadline=None, suppress_health_check=[HealthCheck.too_slow])
def test_mutated_paper_file_raises_a_validation_error_not_a_crash(
    tmp_path_factory, where, value, delete
):
    data = copy.deepcopy(PAPER)
    node = data
    for key in where[:-1]:
        node = node[key]
    if delete and isinstance(node, dict):
        del node[where[-1]]
    else:
        node[where[-1]] = value
    path = tmp_path_factory.mktemp("mut") / "s.json"
    path.write_text(json.dumps(data))  # NaN/inf become non-standard JSON literals: still parsed
    try:
        load_scenario(path)
    except ScenarioError as exc:
        assert exc.errors


@given(st.data())
@settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.too_slow])
def test_corrupted_toml_bytes_raise_a_validation_error_not_a_crash(tmp_path_factory, data):
    from importlib import resources

    raw = bytearray(resources.files("mawdo.planning").joinpath("data", "paper.toml").read_bytes())
    for _ in range(data.draw(st.integers(1, 5))):
        i = data.draw(st.integers(0, len(raw) - 1))
        raw[i] = data.draw(st.integers(0, 255))
    path = tmp_path_factory.mktemp("bytes") / "s.toml"
    path.write_bytes(bytes(raw))
    try:
        load_scenario(path)
    except ScenarioError as exc:
        assert exc.errors


# --- the built-in paper scenario ------------------------------------------------------------


def test_paper_scenario_layout():
    sc = get_scenario("paper")
    assert (sc.width, sc.height) == (366.0, 366.0)
    assert len(sc.static_indices) == 2 and len(sc.moving_indices) == 6
    assert sc.robot_radius == 4.0 and sc.robot_speed == 4.0
    # start near one corner, goal near the opposite one
    assert np.all(sc.start <= 30) and np.all(sc.goal >= 366 - 30)
    kinds = {type(o.motion).__name__ for o in sc.obstacles}
    assert {"Static", "ConstantVelocity", "Patrol", "BoundedRandomWalk"} <= kinds


def test_paper_straight_line_is_blocked_at_t0():
    sc = get_scenario("paper")
    line = np.array([sc.start, sc.goal])
    report = check_static_path(line, [o.shape for o in sc.obstacles], radius=sc.robot_radius)
    assert not report.ok
    assert {o for _, o in report.collisions} & set(sc.static_indices)
    cost = PathCost(sc)
    straight = np.linspace(sc.start, sc.goal, 22)[1:-1].ravel()
    assert cost.parts(straight)[1] > 0


def test_paper_static_optimum_is_2_to_10_percent_longer_than_the_straight_line():
    sc = get_scenario("paper")
    opt = scenario_optimum(sc)
    ratio = opt.length / sc.straight_line_length()
    assert 1.02 <= ratio <= 1.10, ratio
    assert opt.length == pytest.approx(478.787, abs=0.01)  # documented in docs/planning.md
    assert sc.straight_line_length() == pytest.approx(326 * np.sqrt(2))


# A collision-free spacetime plan from t = 0 found offline (CMA-ES on the spacetime cost with the
# robot radius raised to 5.5 px); 484.7 px, 1.2 % above the static optimum.
WITNESS = [
    [29.897, 42.919], [39.261, 64.592], [45.36, 78.664], [57.597, 106.868], [67.279, 129.162],
    [76.707, 150.792], [87.41, 175.236], [98.847, 186.022], [115.117, 201.174],
    [129.572, 214.569], [148.689, 232.246], [165.9, 248.125], [175.087, 256.533],
    [203.452, 282.24], [223.526, 299.941], [243.995, 307.706], [271.228, 317.923],
    [296.149, 327.275], [308.506, 331.918], [327.837, 339.179],
]  # fmt: skip


def _timed(path, speed):
    cum = np.concatenate([[0.0], np.cumsum(np.hypot(*np.diff(path, axis=0).T))])
    return cum / speed


def test_paper_moving_obstacles_block_the_static_optimum_but_a_path_exists():
    sc = get_scenario("paper")
    opt = scenario_optimum(sc).path
    # interesting: following the static optimum from t = 0 runs into a moving obstacle
    report = check_trajectory(opt, sc, times=_timed(opt, sc.robot_speed))
    assert {o for _, o in report.collisions} & set(sc.moving_indices)
    # solvable: the witness is collision-free for the kernel and the independent checker
    path = np.vstack([sc.start, WITNESS, sc.goal])
    length, ncol, _ = PathCost(sc, mode="spacetime").parts(np.ravel(WITNESS))
    assert ncol == 0
    assert length < 1.02 * scenario_optimum(sc).length
    witness = check_trajectory(path, sc, times=_timed(path, sc.robot_speed))
    assert witness.ok and witness.min_clearance > 1.0


def test_shapes_expose_bounds_and_distance():
    c = CircleObstacle(shape="circle", center=(10, 20), radius=5)
    assert c.bounds() == (5, 15, 15, 25)
    assert c.distance((10, 30)) == pytest.approx(5.0) and c.distance((10, 20)) == 0.0
    p = PolygonObstacle(shape="polygon", vertices=[(0, 0), (4, 0), (4, 3)])
    assert p.bounds() == (0, 0, 4, 3)
    assert p.distance((4, 5)) == pytest.approx(2.0)


def test_the_documented_example_file_is_valid(tmp_path):
    # the file layout is documented in the schema module, where the fields are
    import mawdo.planning.world.scenario_schema as module

    doc = module.__doc__
    block = doc.split("File layout (TOML)::\n")[1].split("\nOther motions")[0]
    text = "\n".join(line[4:] for line in block.splitlines())
    path = tmp_path / "example.toml"
    path.write_text(text)
    sc = load_scenario(path)
    assert sc.name == "example" and len(sc.obstacles) == 2
    assert sc.moving_indices == [1]
