"""Planning runs recorded as MCAP: read back with the mcap library's own reader."""

import json

import numpy as np
import pytest
from mcap.reader import make_reader

from mawdo.planning import plan
from mawdo.planning.render.foxglove_schemas import schema_of
from mawdo.planning.render.record import TOPICS, record_mcap
from mawdo.planning.run.config import PlannerConfig
from mawdo.planning.run.result import Drive, Replan
from mawdo.planning.world.scenario import scenario_from_dict
from tests.cli_run import mawdo

#: Field names of Foxglove's schemas, as its documentation lists them.
FOXGLOVE_FIELDS = {
    "foxglove.SceneUpdate": {"deletions", "entities"},
    "foxglove.SceneEntity": {"timestamp", "frame_id", "id", "lifetime", "frame_locked",
                             "metadata", "arrows", "cubes", "spheres", "cylinders", "lines",
                             "triangles", "texts", "models"},
    "foxglove.CylinderPrimitive": {"pose", "size", "bottom_scale", "top_scale", "color"},
    "foxglove.CubePrimitive": {"pose", "size", "color"},
    "foxglove.LinePrimitive": {"type", "pose", "thickness", "scale_invariant", "points", "color",
                               "colors", "indices"},
    "foxglove.PosesInFrame": {"timestamp", "frame_id", "poses"},
    "foxglove.Pose": {"position", "orientation"},
}  # fmt: skip
_TYPES = {"number": (int, float), "integer": int, "string": str, "boolean": bool,
          "array": list, "object": dict, "null": type(None)}  # fmt: skip


def conforms(value, schema: dict, seen: set) -> None:
    """Assert ``value`` has exactly the schema's fields, of its types, all the way down;
    collect the titles of the objects met in ``seen``."""
    if "oneOf" in schema:
        assert value in [c["const"] for c in schema["oneOf"]], (schema["title"], value)
        return
    kinds = schema["type"] if isinstance(schema["type"], list) else [schema["type"]]
    ok = any(isinstance(value, _TYPES[k]) and not (k != "boolean" and isinstance(value, bool))
             for k in kinds)  # fmt: skip
    assert ok, (schema.get("title"), value)
    if isinstance(value, dict):
        seen.add(schema["title"])
        assert set(value) == set(schema["properties"]) == set(schema["required"])
        for key, sub in schema["properties"].items():
            conforms(value[key], sub, seen)
    elif isinstance(value, list):
        for item in value:
            conforms(item, schema["items"], seen)


def read(path) -> dict:
    """topic -> [(log_time, publish_time, sequence, decoded message, schema)]."""
    out = {}
    with open(path, "rb") as f:
        for sch, ch, msg in make_reader(f).iter_messages():
            assert (sch.encoding, ch.message_encoding) == ("jsonschema", "json")
            out.setdefault(ch.topic, []).append(
                (msg.log_time, msg.publish_time, msg.sequence, json.loads(msg.data),
                 json.loads(sch.data))
            )  # fmt: skip
    return out


def check_file(path, n_steps: int, step_ns: int) -> dict:
    topics = read(path)
    assert list(topics) == list(TOPICS)
    seen = set()
    for topic, messages in topics.items():
        assert len(messages) == n_steps, topic
        for k, (log, pub, seq, data, schema) in enumerate(messages):
            assert log == pub == k * step_ns and seq == k
            assert schema["title"] == TOPICS[topic] and schema == schema_of(TOPICS[topic])
            conforms(data, schema, seen)
    for title, fields in FOXGLOVE_FIELDS.items():
        assert title in seen
        props = _find(schema_of("foxglove.SceneUpdate"), title) or _find(
            schema_of("foxglove.PosesInFrame"), title
        )
        assert set(props) == fields, title
    return {t: [m[3] for m in ms] for t, ms in topics.items()}


def _find(schema, title):
    """The properties of the object schema named ``title`` inside ``schema``."""
    if schema.get("title") == title and "properties" in schema:
        return schema["properties"]
    subs = list(schema.get("properties", {}).values()) + [schema.get("items")]
    for sub in subs:
        if isinstance(sub, dict) and (hit := _find(sub, title)):
            return hit
    return None


def metre_run():
    """A hand-made run in metres (dt 0.25 s): the robot drives +x at 1 m/s beside a person
    walking the same way 1 m away, towards a static box."""
    sc = scenario_from_dict({
        "schema_version": 1, "name": "hand", "units": "m", "dt": 0.25, "resolution": 0.05,
        "width": 4.0, "height": 2.0, "start": [0.5, 0.5], "goal": [1.5, 0.5],
        "robot": {"radius": 0.3, "speed": 1.0},
        "obstacles": [
            {"shape": "circle", "center": [0.5, 1.5], "radius": 0.2, "id": "person",
             "motion": {"velocity": [1.0, 0.0]}},
            {"shape": "polygon", "vertices": [[2.0, 0.2], [2.5, 0.2], [2.5, 0.8], [2.0, 0.8]]},
        ],
    })  # fmt: skip
    px = sc.units.length_to_px
    drive = Drive(sc.start)
    for k in range(4):
        drive.move(k, px(np.array([0.75 + 0.25 * k, 0.5])))

    def replan(step, wp):
        return Replan(step, drive.traj[step], px(np.array(wp)), 0.0, 0.0, 0, 0.0, 0, np.zeros(0))

    plans = [replan(0, [[1.0, 0.5]]), replan(2, [[1.25, 0.6]])]
    res = drive.result("goal reached", sc, algorithm="hand", seed=0, config=PlannerConfig(),
                       replans=plans)  # fmt: skip
    return res


def test_metre_run_in_metres_and_seconds(tmp_path):
    res = metre_run()
    msgs = check_file(record_mcap(res, tmp_path / "hand.mcap"), 5, 250_000_000)
    for k in range(5):
        (robot,) = msgs["/robot"][k]["entities"]
        (disc,) = robot["cylinders"]
        assert robot["frame_id"] == "map"
        assert robot["timestamp"] == {"sec": k // 4, "nsec": k % 4 * 250_000_000}
        pos = disc["pose"]["position"]
        assert (pos["x"], pos["y"]) == pytest.approx((0.5 + 0.25 * k, 0.5))
        assert (disc["size"]["x"], disc["size"]["y"]) == pytest.approx((0.6, 0.6))
        (person,) = msgs["/agents"][k]["entities"]
        assert person["id"] == "agent/person"
        p = person["cylinders"][0]["pose"]["position"]
        assert (p["x"], p["y"]) == pytest.approx((0.5 + 0.25 * k, 1.5))  # 1 m/s for k/4 s
        m = msgs["/metrics"][k]
        assert m["time"] == pytest.approx(0.25 * k) and m["step"] == k
        assert m["speed"] == pytest.approx(0.0 if k == 0 else 1.0)
        # the person: 1 m between centres, less 0.3 + 0.2; the box: 2.0 - x - 0.3
        assert m["clearance"] == pytest.approx(min(0.5, 1.2 - 0.25 * k))
        assert m["replans"] == (1 if k < 2 else 2)
        poses = msgs["/plan"][k]["poses"]
        way = [(1.0, 0.5)] if k < 2 else [(1.25, 0.6)]
        start = (0.5, 0.5) if k < 2 else (1.0, 0.5)
        got = [(q["position"]["x"], q["position"]["y"]) for q in poses]
        assert np.allclose(got, [start, *way, (1.5, 0.5)])
    (static,) = msgs["/static_map"][3]["entities"]
    border, box = static["lines"]
    assert [(q["x"], q["y"]) for q in border["points"]] == [(0, 0), (4, 0), (4, 2), (0, 2)]
    box_points = [(q["x"], q["y"]) for q in box["points"]]
    assert np.allclose(box_points, [(2.0, 0.2), (2.5, 0.2), (2.5, 0.8), (2.0, 0.8)])
    assert border["type"] == box["type"] == 1  # LINE_LOOP
    assert msgs["/static_map"][3]["entities"][0]["timestamp"] == {"sec": 0, "nsec": 750_000_000}
    assert min(m["clearance"] for m in msgs["/metrics"]) == pytest.approx(
        res.scenario.units.length(res.min_clearance)
    )


def test_a_planned_run(tmp_path):
    res = plan("paper", config="quick", max_steps=10)
    n = len(res.trajectory)
    msgs = check_file(record_mcap(res, tmp_path / "paper.mcap"), n, 1_000_000_000)  # 1 s a step
    for k in range(n):
        pos = msgs["/robot"][k]["entities"][0]["cylinders"][0]["pose"]["position"]
        assert (pos["x"], pos["y"]) == pytest.approx(tuple(res.trajectory[k]))
        active = [r for r in res.replans if r.step <= k][-1]
        first = msgs["/plan"][k]["poses"][0]["position"]
        assert (first["x"], first["y"]) == pytest.approx(tuple(active.position))
    assert len(msgs["/agents"][0]["entities"]) == len(res.scenario.moving_indices)
    assert min(m["clearance"] for m in msgs["/metrics"]) == pytest.approx(res.min_clearance)


def test_the_command_records_a_run(tmp_path):
    done = mawdo("plan", "run", "paper", "--preset", "quick", "--max-steps", "3",
                 "--no-figures", "--no-progress", "--out", str(tmp_path / "out"),
                 "--record", str(tmp_path / "run.mcap"))  # fmt: skip
    assert done.returncode == 0, done.stderr
    assert "recording: " in done.stdout
    assert all(len(ms) == 4 for ms in read(tmp_path / "run.mcap").values())
    bad = mawdo("plan", "run", "paper", "--record", str(tmp_path / "run.txt"),
                "--out", str(tmp_path / "o2"))  # fmt: skip
    assert bad.returncode == 2 and "--record file" in bad.stderr and ".mcap" in bad.stderr
    assert not (tmp_path / "o2").exists()
