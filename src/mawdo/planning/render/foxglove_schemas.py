"""JSON schemas of the Foxglove messages a recording holds (:mod:`.record`).

They follow Foxglove's own schemas (https://docs.foxglove.dev/docs/visualization/message-schemas):
the same names (``foxglove.SceneUpdate``, ``foxglove.PosesInFrame`` ...), fields and enums, every
field required (a recording writes them all). The scene entity's primitive lists that mawdo
never fills (arrows, spheres, triangles, texts, models) are written empty and described here by
their item's name only. ``mawdo.StepMetrics`` is mawdo's own: the numbers of one step.
"""

from __future__ import annotations

__all__ = ["POSES_IN_FRAME", "SCENE_UPDATE", "STEP_METRICS", "schema_of"]

_NUM = {"type": "number"}
_INT = {"type": "integer", "minimum": 0}
_STR = {"type": "string"}
_BOOL = {"type": "boolean"}


def _obj(title: str, description: str, properties: dict) -> dict:
    return {
        "title": title,
        "description": description,
        "type": "object",
        "properties": properties,
        "required": list(properties),
    }


def _list(items: dict) -> dict:
    return {"type": "array", "items": items}


def _enum(title: str, description: str, values: dict[str, int]) -> dict:
    return {
        "title": title,
        "description": description,
        "oneOf": [{"title": k, "const": v} for k, v in values.items()],
    }


_TIME = _obj("time", "Timestamp", {"sec": _INT, "nsec": {**_INT, "maximum": 999_999_999}})
_DURATION = _obj("duration", "Duration (0: forever)", {"sec": _INT, "nsec": _INT})
_XYZ = {"x": _NUM, "y": _NUM, "z": _NUM}
_VECTOR3 = _obj("foxglove.Vector3", "A vector in 3D space", _XYZ)
_POINT3 = _obj("foxglove.Point3", "A point in 3D space", _XYZ)
_QUATERNION = _obj("foxglove.Quaternion", "An orientation", {**_XYZ, "w": _NUM})
_POSE = _obj("foxglove.Pose", "A position and orientation", {
    "position": _VECTOR3, "orientation": _QUATERNION})  # fmt: skip
_COLOR = _obj("foxglove.Color", "A colour, components in [0, 1]", {
    "r": _NUM, "g": _NUM, "b": _NUM, "a": _NUM})  # fmt: skip
_CUBE = _obj("foxglove.CubePrimitive", "A box", {
    "pose": _POSE, "size": _VECTOR3, "color": _COLOR})  # fmt: skip
_CYLINDER = _obj("foxglove.CylinderPrimitive", "A cylinder", {
    "pose": _POSE, "size": _VECTOR3, "bottom_scale": _NUM, "top_scale": _NUM,
    "color": _COLOR})  # fmt: skip
#: ``LinePrimitive.type`` values.
LINE_STRIP, LINE_LOOP, LINE_LIST = 0, 1, 2
_LINE = _obj("foxglove.LinePrimitive", "A series of points connected by lines", {
    "type": _enum("foxglove.LineType", "Drawing primitive to use for lines",
                  {"LINE_STRIP": LINE_STRIP, "LINE_LOOP": LINE_LOOP, "LINE_LIST": LINE_LIST}),
    "pose": _POSE, "thickness": _NUM, "scale_invariant": _BOOL, "points": _list(_POINT3),
    "color": _COLOR, "colors": _list(_COLOR), "indices": _list(_INT)})  # fmt: skip
_KEY_VALUE = _obj("foxglove.KeyValuePair", "A key with its value", {"key": _STR, "value": _STR})


def _unused(title: str) -> dict:
    return _list({"title": title, "type": "object"})


_ENTITY = _obj("foxglove.SceneEntity", "A visual element in a 3D scene", {
    "timestamp": _TIME, "frame_id": _STR, "id": _STR, "lifetime": _DURATION,
    "frame_locked": _BOOL, "metadata": _list(_KEY_VALUE),
    "arrows": _unused("foxglove.ArrowPrimitive"), "cubes": _list(_CUBE),
    "spheres": _unused("foxglove.SpherePrimitive"), "cylinders": _list(_CYLINDER),
    "lines": _list(_LINE), "triangles": _unused("foxglove.TriangleListPrimitive"),
    "texts": _unused("foxglove.TextPrimitive"),
    "models": _unused("foxglove.ModelPrimitive")})  # fmt: skip
_DELETION = _obj("foxglove.SceneEntityDeletion", "Removes entities from a 3D scene", {
    "timestamp": _TIME,
    "type": _enum("foxglove.SceneEntityDeletionType", "Which entities to delete",
                  {"MATCHING_ID": 0, "ALL": 1}),
    "id": _STR})  # fmt: skip

#: ``foxglove.SceneUpdate``: the robot, the moving agents, the static map.
SCENE_UPDATE = _obj("foxglove.SceneUpdate", "An update to the entities of a 3D scene", {
    "deletions": _list(_DELETION), "entities": _list(_ENTITY)})  # fmt: skip
#: ``foxglove.PosesInFrame``: the plan the robot follows.
POSES_IN_FRAME = _obj("foxglove.PosesInFrame", "An array of timestamped poses in a frame", {
    "timestamp": _TIME, "frame_id": _STR, "poses": _list(_POSE)})  # fmt: skip
#: ``mawdo.StepMetrics``: one step's numbers, in the scenario's units.
STEP_METRICS = _obj("mawdo.StepMetrics", "The numbers of one step of a planning run", {
    "step": _INT,
    "time": {**_NUM, "description": "time of the step (s; a pixel scenario: 1 s per step)"},
    "x": {**_NUM, "description": "robot position (m; a pixel scenario: px)"},
    "y": _NUM,
    "speed": {**_NUM, "description": "distance driven along the route during the step over "
              "its duration (m/s; a pixel scenario: px per step); 0 at step 0"},
    "clearance": {"type": ["number", "null"], "description": "smallest distance between the "
                  "robot's disc and an obstacle during the step (m; px), the checker's; null "
                  "without obstacles"},
    "replans": {**_INT, "description": "plans made so far, the first included"}})  # fmt: skip

_BY_NAME = {s["title"]: s for s in (SCENE_UPDATE, POSES_IN_FRAME, STEP_METRICS)}


def schema_of(name: str) -> dict:
    """The JSON schema (a dict) named ``name`` (``foxglove.SceneUpdate`` ...)."""
    return _BY_NAME[name]
