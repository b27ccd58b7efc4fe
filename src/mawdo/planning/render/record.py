"""A planning run recorded as an MCAP file, for Foxglove (https://foxglove.dev).

Topics (JSON encoding, JSON schemas following Foxglove's: :mod:`.foxglove_schemas`), one
message per step ``k = 0, 1, ..., steps`` on each, log and publish time ``k * dt`` seconds
(nanoseconds in the file):

* ``/robot`` (``foxglove.SceneUpdate``): the robot's disc at its step position, a cylinder.
* ``/agents`` (``foxglove.SceneUpdate``): every moving obstacle at time ``k`` (people and other
  moving discs as cylinders, moving polygons as closed lines), one entity each.
* ``/static_map`` (``foxglove.SceneUpdate``): the map box (a flat cube and its border) and the
  static obstacles (polygons as closed lines, discs as cylinders); the same at every step, so
  a seek anywhere shows it.
* ``/plan`` (``foxglove.PosesInFrame``): the plan in force at step ``k`` (from where it was made,
  through its waypoints, to the goal), each pose facing the next.
* ``/metrics`` (``mawdo.StepMetrics``): the step's time, position, speed and clearance.

Units: a metre scenario is recorded in metres and seconds; a pixel scenario in its pixels (the
3D panel's metres) with ``dt = 1`` second per time step. Everything is in the frame ``map``,
the scenario's: ``(0, 0)`` is the map's lower-left corner, ``z`` points up.
"""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np

from mawdo.planning.render.foxglove_schemas import (
    LINE_LOOP,
    POSES_IN_FRAME,
    SCENE_UPDATE,
    STEP_METRICS,
)

__all__ = ["FRAME", "TOPICS", "record_mcap", "step_metrics"]

#: The frame every message is in: the scenario's map.
FRAME = "map"
#: Topic -> schema name, in the order the channels are registered.
TOPICS = {
    "/robot": "foxglove.SceneUpdate",
    "/agents": "foxglove.SceneUpdate",
    "/static_map": "foxglove.SceneUpdate",
    "/plan": "foxglove.PosesInFrame",
    "/metrics": "mawdo.StepMetrics",
}
_SCHEMAS = {s["title"]: s for s in (SCENE_UPDATE, POSES_IN_FRAME, STEP_METRICS)}
_COLOURS = {
    "robot": (0.12, 0.47, 0.71, 0.9),
    "agent": (0.84, 0.15, 0.16, 0.8),
    "static": (0.2, 0.2, 0.2, 1.0),
    "floor": (0.95, 0.95, 0.95, 0.3),
}
_STAMP = "@stamp@"  # stands for the timestamp in the static map's message, set per step


def record_mcap(result, path) -> Path:
    """Write a planning run to an MCAP file (see the module docstring for its topics).

    Parameters
    ----------
    result : PlanResult
        The run; its ``scenario`` (for a stepped run the realised world) gives the obstacles
        and the units.
    path : str or Path
        The ``.mcap`` file to write (replaced if it exists).

    Returns
    -------
    Path
        ``path``.

    Raises
    ------
    ImportError
        Without the ``mcap`` library (``pip install 'mawdo[record]'``).
    """
    try:
        from mcap.writer import Writer
    except ImportError:
        raise ImportError("recording a run needs mcap: pip install 'mawdo[record]'") from None
    from mawdo import __version__

    sc, path = result.scenario, Path(path)
    u = sc.units
    dt = 1.0 if u.is_pixels else u.dt
    metrics = step_metrics(result)
    scene = _Scene(result)
    with path.open("wb") as f:
        writer = Writer(f)
        writer.start(profile="", library=f"mawdo {__version__}")
        meta = {"units": u.length_label, "time_units": "s", "seconds_per_step": repr(dt)}
        schema_ids = {
            name: writer.register_schema(name, "jsonschema", json.dumps(schema).encode())
            for name, schema in _SCHEMAS.items()
        }
        channels = {
            topic: writer.register_channel(topic, "json", schema_ids[name], meta)
            for topic, name in TOPICS.items()
        }
        for k in range(len(result.trajectory)):
            t_ns = round(k * dt * 1e9)
            stamp = {"sec": t_ns // 1_000_000_000, "nsec": t_ns % 1_000_000_000}
            messages = {
                "/robot": scene.robot(k, stamp),
                "/agents": scene.agents(k, stamp),
                "/static_map": scene.static_map(stamp),
                "/plan": scene.plan(k, stamp),
                "/metrics": json.dumps({"step": k, "time": k * dt, **metrics[k]}),
            }
            for topic, text in messages.items():
                writer.add_message(channels[topic], t_ns, text.encode(), t_ns, sequence=k)
        writer.finish()
    return path


def step_metrics(result) -> list[dict]:
    """Per step ``k``: ``x``, ``y``, ``speed`` (route length driven during step ``k`` over its
    duration) and ``clearance`` (the independent checker's smallest clearance of the route's
    pieces during step ``k``, of the start position at ``k = 0``; None without obstacles),
    in the scenario's units, and ``replans`` (plans made by step ``k``)."""
    from mawdo.planning.judge.check import check_trajectory

    sc = result.scenario
    u = sc.units
    traj = np.asarray(result.trajectory, dtype=float)
    route, times = _route(result)
    seg = check_trajectory(route, sc, times=times).clearance
    start = check_trajectory(route[:1], sc, times=times[:1]).clearance
    n = len(traj)
    clearance = np.full(n, np.inf)
    if seg.size:
        step_of = np.clip(np.ceil(times[1:] - 1e-9).astype(int), 0, n - 1)
        np.minimum.at(clearance, step_of, seg.min(axis=1))
    if start.size:
        clearance[0] = min(clearance[0], float(start.min()))
    arc = np.concatenate([[0.0], np.cumsum(np.hypot(*np.diff(route, axis=0).T))])
    driven = np.diff(np.interp(np.arange(n, dtype=float), times, arc), prepend=0.0)
    plan_steps = np.array([r.step for r in result.replans], dtype=int)
    return [
        {
            "x": float(u.length(traj[k, 0])),
            "y": float(u.length(traj[k, 1])),
            "speed": float(u.speed(driven[k])),
            "clearance": float(u.length(clearance[k])) if np.isfinite(clearance[k]) else None,
            "replans": int(np.sum(plan_steps <= k)),
        }
        for k in range(n)
    ]


def _route(result) -> tuple[np.ndarray, np.ndarray]:
    """The executed route and its times (time steps); the step positions without one."""
    if result.route is not None and result.route_times is not None:
        return np.asarray(result.route, dtype=float), np.asarray(result.route_times, float)
    traj = np.asarray(result.trajectory, dtype=float)
    return traj, np.arange(len(traj), dtype=float)


class _Scene:
    """The JSON text of each topic's message at a step, in the scenario's units."""

    def __init__(self, result) -> None:
        sc = self.sc = result.scenario
        self.L = sc.units.length
        self.height = 2.0 * float(self.L(sc.robot_radius))  # of every cylinder and wall
        self.traj = np.asarray(result.trajectory, dtype=float)
        self.replans = sorted(result.replans, key=lambda r: r.step)
        static = _entity("static_map", _STAMP, **_static_shapes(self))
        self.static_text = json.dumps({"deletions": [], "entities": [static]})

    def robot(self, k: int, stamp: dict) -> str:
        x, y = self.L(self.traj[k])
        d = 2.0 * float(self.L(self.sc.robot_radius))
        disc = _cylinder(x, y, d, self.height, _COLOURS["robot"])
        return _update([_entity("robot", stamp, cylinders=[disc])])

    def agents(self, k: int, stamp: dict) -> str:
        entities = []
        for i in self.sc.moving_indices:
            ob = self.sc.obstacles[i]
            off = ob.offset(np.asarray(float(k)))
            entities.append(_entity(f"agent/{ob.id}", stamp, **_shape(self, ob, off, "agent")))
        return _update(entities)

    def static_map(self, stamp: dict) -> str:
        return self.static_text.replace(json.dumps(_STAMP), json.dumps(stamp), 1)  # one entity

    def plan(self, k: int, stamp: dict) -> str:
        active = [r for r in self.replans if r.step <= k]
        poses = []
        if active:
            r = active[-1]
            pts = self.L(np.vstack([r.position, r.waypoints, self.sc.goal]))
            poses = _poses(np.asarray(pts, dtype=float))
        return json.dumps({"timestamp": stamp, "frame_id": FRAME, "poses": poses})


def _static_shapes(scene: _Scene) -> dict:
    w, h = float(scene.L(scene.sc.width)), float(scene.L(scene.sc.height))
    floor = {"pose": _pose(w / 2, h / 2, -0.005), "size": {"x": w, "y": h, "z": 0.01},
             "color": _rgba(_COLOURS["floor"])}  # fmt: skip
    border = _loop([(0, 0), (w, 0), (w, h), (0, h)], _COLOURS["static"])
    shapes = {"cubes": [floor], "lines": [border], "cylinders": []}
    for i in scene.sc.static_indices:
        ob = scene.sc.obstacles[i]
        for key, prims in _shape(scene, ob, np.zeros(2), "static").items():
            shapes[key] += prims
    return shapes


def _shape(scene: _Scene, ob, offset, colour: str) -> dict:
    """An obstacle moved by ``offset`` (px): a cylinder (disc) or a closed line (polygon)."""
    rgba = _COLOURS[colour]
    if ob.is_circle:
        x, y = scene.L(np.asarray(ob.shape.center, dtype=float) + offset)
        d = 2.0 * float(scene.L(ob.shape.radius))
        return {"cylinders": [_cylinder(x, y, d, scene.height, rgba)]}
    pts = scene.L(np.asarray(ob.shape.vertices, dtype=float) + offset)
    return {"lines": [_loop(pts, rgba)]}


def _update(entities: list) -> str:
    return json.dumps({"deletions": [], "entities": entities})


def _entity(name: str, stamp, **primitives) -> dict:
    out = {"timestamp": stamp, "frame_id": FRAME, "id": name,
           "lifetime": {"sec": 0, "nsec": 0}, "frame_locked": False, "metadata": []}  # fmt: skip
    for key in ("arrows", "cubes", "spheres", "cylinders", "lines", "triangles", "texts",
                "models"):  # fmt: skip
        out[key] = primitives.get(key, [])
    return out


def _rgba(c) -> dict:
    return dict(zip("rgba", map(float, c), strict=True))


def _pose(x: float, y: float, z: float = 0.0, yaw: float = 0.0) -> dict:
    return {"position": {"x": float(x), "y": float(y), "z": float(z)},
            "orientation": {"x": 0.0, "y": 0.0, "z": float(np.sin(yaw / 2)),
                            "w": float(np.cos(yaw / 2))}}  # fmt: skip


def _cylinder(x, y, diameter: float, height: float, rgba) -> dict:
    return {"pose": _pose(x, y, height / 2), "size": {"x": diameter, "y": diameter, "z": height},
            "bottom_scale": 1.0, "top_scale": 1.0, "color": _rgba(rgba)}  # fmt: skip


def _loop(points, rgba) -> dict:
    pts = [{"x": float(x), "y": float(y), "z": 0.0} for x, y in np.asarray(points, dtype=float)]
    return {"type": LINE_LOOP, "pose": _pose(0.0, 0.0), "thickness": 2.0, "scale_invariant": True,
            "points": pts, "color": _rgba(rgba), "colors": [], "indices": []}  # fmt: skip


def _poses(points: np.ndarray) -> list[dict]:
    """Poses at ``points``, each facing the next (the last as the one before it)."""
    d = np.diff(points, axis=0)
    yaw = np.arctan2(d[:, 1], d[:, 0]) if len(d) else np.zeros(0)
    yaw = np.concatenate([yaw, yaw[-1:] if len(yaw) else [0.0]])
    return [_pose(x, y, 0.0, a) for (x, y), a in zip(points, yaw, strict=True)]
