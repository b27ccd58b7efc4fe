"""Units of a scenario: pixels and time steps (the planner's own), or metres and seconds.

A scenario file may declare ``units = "m"`` with ``dt`` (seconds per time step, > 0) and
``resolution`` (metres per pixel, > 0): its positions, sizes and radii are then metres, its
speeds metres per second and its times (patrol ``waits``, random-walk ``hold``) seconds.

Where the conversion happens
----------------------------
The planner, the guard, the checker and every other caller read ``scenario.spec`` and the
:class:`~mawdo.planning.world.scenario.Scenario` properties in pixels and time steps. So the
metre file is validated as written (its spec keeps the file's values and round-trips with
:meth:`Scenario.to_dict`, bit for bit), and
:func:`~mawdo.planning.world.scenario.scenario_from_spec` converts it once, with
:func:`spec_to_pixels`, into the pixel spec that becomes ``Scenario.spec``; the whole-scenario
checks run on that pixel spec, the one the planner uses. The other way (converting to pixels
when the file is read and converting back when it is written) would not round-trip:
``0.3 / 0.05 * 0.05`` is not ``0.3`` in binary floating point, so a metre scenario written out
and read back could plan differently. Here a scenario rebuilt from its ``to_dict()`` has the
same pixel values, bit for bit, as the one it came from.

What the user reads (metrics, figure axes) is converted back with :class:`Units`, which
``Scenario.units`` returns; for a pixel scenario every conversion is the identity (the value
itself, not a product with 1.0) and the labels are "px" and "steps".

Conversions (``res`` metres per pixel, ``dt`` seconds per step), metres to pixels:
length ``x / res``; speed ``v * dt / res`` (left to right); time ``t / dt``; acceleration
``a * dt * dt / res``; angular rate ``w * dt``; and the inverse the other way.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any, Literal

import numpy as np

__all__ = ["PIXELS", "Units", "spec_to_pixels", "spec_units", "units_errors", "whole_steps"]

#: How far from a whole number of steps a time in seconds may be (relative), after ``t / dt``:
#: ``0.3 / 0.1`` is ``2.9999999999999996``.
WHOLE_STEPS_RTOL = 1e-9


@dataclass(frozen=True)
class Units:
    """The units a scenario's user reads and writes.

    Parameters
    ----------
    name : {"px", "m"}
        ``"px"``: pixels and time steps (the planner's units); ``"m"``: metres and seconds.
    dt : float or None
        Seconds per time step (> 0) for ``"m"``; None for ``"px"``.
    resolution : float or None
        Metres per pixel (> 0) for ``"m"``; None for ``"px"``.

    Raises
    ------
    ValueError
        For another name, or ``dt``/``resolution`` missing, not finite or <= 0 for ``"m"``,
        or given for ``"px"``.
    """

    name: Literal["px", "m"] = "px"
    dt: float | None = None
    resolution: float | None = None

    def __post_init__(self) -> None:
        if self.name == "px":
            if self.dt is not None or self.resolution is not None:
                raise ValueError("pixel units take no dt or resolution")
        elif self.name == "m":
            for field in ("dt", "resolution"):
                v = getattr(self, field)
                if v is None or not (isinstance(v, int | float) and math.isfinite(v) and v > 0):
                    raise ValueError(f"metre units need a finite {field} > 0, got {v!r}")
        else:
            raise ValueError(f"units must be 'px' or 'm', got {self.name!r}")

    @property
    def is_pixels(self) -> bool:
        """True for pixels and time steps (every conversion is the identity)."""
        return self.name == "px"

    # -- labels ------------------------------------------------------------------------------
    @property
    def length_label(self) -> str:
        """``"px"`` or ``"m"``."""
        return "px" if self.is_pixels else "m"

    @property
    def time_label(self) -> str:
        """``"steps"`` or ``"s"``."""
        return "steps" if self.is_pixels else "s"

    @property
    def speed_label(self) -> str:
        """``"px/step"`` or ``"m/s"``."""
        return "px/step" if self.is_pixels else "m/s"

    @property
    def accel_label(self) -> str:
        """``"px/step^2"`` or ``"m/s^2"``."""
        return "px/step^2" if self.is_pixels else "m/s^2"

    @property
    def rate_label(self) -> str:
        """``"rad/step"`` or ``"rad/s"``."""
        return "rad/step" if self.is_pixels else "rad/s"

    # -- internal (px, steps) -> user --------------------------------------------------------
    def length(self, px):
        """Length or position: pixels -> the user's unit (metres: ``px * res``)."""
        return px if self.is_pixels else _times(px, self.resolution)

    def time(self, steps):
        """Time: time steps -> the user's unit (seconds: ``steps * dt``)."""
        return steps if self.is_pixels else _times(steps, self.dt)

    def speed(self, px_per_step):
        """Speed: px per step -> the user's unit (m/s: ``v * res / dt``)."""
        if self.is_pixels:
            return px_per_step
        return _over(_times(px_per_step, self.resolution), self.dt)

    def accel(self, px_per_step2):
        """Acceleration: px per step^2 -> the user's unit (m/s^2: ``a * res / dt / dt``)."""
        if self.is_pixels:
            return px_per_step2
        return _over(_over(_times(px_per_step2, self.resolution), self.dt), self.dt)

    def rate(self, rad_per_step):
        """Angular rate: radians per step -> the user's unit (rad/s: ``w / dt``)."""
        return rad_per_step if self.is_pixels else _over(rad_per_step, self.dt)

    # -- user -> internal (px, steps) --------------------------------------------------------
    def length_to_px(self, value):
        """Length or position: the user's unit -> pixels (metres: ``x / res``)."""
        return value if self.is_pixels else _over(value, self.resolution)

    def time_to_steps(self, value):
        """Time: the user's unit -> time steps (seconds: ``t / dt``)."""
        return value if self.is_pixels else _over(value, self.dt)

    def speed_to_px(self, value):
        """Speed: the user's unit -> px per step (m/s: ``v * dt / res``)."""
        return value if self.is_pixels else _over(_times(value, self.dt), self.resolution)

    def accel_to_px(self, value):
        """Acceleration: the user's unit -> px per step^2 (m/s^2: ``a * dt * dt / res``)."""
        if self.is_pixels:
            return value
        return _over(_times(_times(value, self.dt), self.dt), self.resolution)

    def rate_to_step(self, value):
        """Angular rate: the user's unit -> radians per step (rad/s: ``w * dt``)."""
        return value if self.is_pixels else _times(value, self.dt)

    def describe(self) -> str:
        """One line: ``"pixels and time steps"`` or ``"metres and seconds (dt ..., res ...)"``."""
        if self.is_pixels:
            return "pixels and time steps"
        return f"metres and seconds (dt {self.dt:g} s per step, resolution {self.resolution:g} m)"


#: Pixels and time steps, the planner's own units.
PIXELS = Units()


def _times(value, factor: float):
    if isinstance(value, int | float):
        return value * factor
    return np.asarray(value, dtype=float) * factor


def _over(value, factor: float):
    if isinstance(value, int | float):
        return value / factor
    return np.asarray(value, dtype=float) / factor


def spec_units(spec) -> Units:
    """The :class:`Units` a validated scenario spec is written in (``units``, ``dt``,
    ``resolution``); raises ``ValueError`` if they do not form one (see
    :func:`~mawdo.planning.world.scenario_schema.units_errors` for the file's messages)."""
    return Units(spec.units, spec.dt, spec.resolution)


# --------------------------------------------------------------------------------------------
# a metre file's contents in pixels


def spec_to_pixels(data: dict[str, Any], units: Units) -> dict[str, Any]:
    """A scenario's contents (the validated spec as a plain dict, ``model_dump()``) in pixels
    and time steps, without ``units``, ``dt`` and ``resolution``.

    Parameters
    ----------
    data : dict
        The spec's fields in ``units``.
    units : Units

    Returns
    -------
    dict
        A new dict to validate as a pixel spec. A random walk's ``hold`` (seconds) becomes a
        whole number of steps when it is one within :data:`WHOLE_STEPS_RTOL`; otherwise its
        ``t / dt`` is kept, for the pixel schema to refuse.
    """
    L, V, T = units.length_to_px, units.speed_to_px, units.time_to_steps
    out = {k: v for k, v in data.items() if k not in ("units", "dt", "resolution")}
    for key in ("width", "height"):
        out[key] = L(data[key])
    for key in ("start", "goal"):
        out[key] = _points(data[key], L)
    if data.get("spots") is not None:
        out["spots"] = [_points(p, L) for p in data["spots"]]
    robot = data["robot"]
    out["robot"] = {**robot, "radius": L(robot["radius"]), "speed": V(robot["speed"])}
    out["obstacles"] = [_obstacle(ob, L, V, T) for ob in data.get("obstacles", [])]
    if data.get("crowd") is not None:
        people = [
            {**p, "start": _points(p["start"], L), "goal": _points(p["goal"], L),
             "radius": L(p["radius"]), "speed": V(p["speed"])}
            for p in data["crowd"]["people"]
        ]  # fmt: skip
        out["crowd"] = {**data["crowd"], "people": people}
    return out


def _points(p, fn: Callable) -> list:
    return [fn(float(c)) for c in p]


def _obstacle(ob: dict, L: Callable, V: Callable, T: Callable) -> dict:
    ob = dict(ob)
    if "center" in ob:
        ob["center"] = _points(ob["center"], L)
        ob["radius"] = L(ob["radius"])
    if "vertices" in ob:
        ob["vertices"] = [_points(v, L) for v in ob["vertices"]]
    m = dict(ob.get("motion") or {"model": "static"})
    if "velocity" in m:
        m["velocity"] = _points(m["velocity"], V)
    if "waypoints" in m:
        m["waypoints"] = [_points(w, L) for w in m["waypoints"]]
    if m.get("model") == "patrol":
        m["speed"] = V(m["speed"])
        if m.get("waits") is not None:
            m["waits"] = [T(float(w)) for w in m["waits"]]
    if m.get("model") == "bounded_random_walk":
        m["step"] = V(m["step"])
        m["hold"] = whole_steps(T(float(m["hold"])))
    ob["motion"] = m
    return ob


def whole_steps(steps: float) -> int | float:
    """``steps`` as an ``int`` when it is a whole number within :data:`WHOLE_STEPS_RTOL`;
    otherwise unchanged."""
    n = round(steps)
    return int(n) if abs(steps - n) <= WHOLE_STEPS_RTOL * max(1.0, abs(steps)) else steps


# --------------------------------------------------------------------------------------------
# the file's unit fields

_UNIT_FIELDS = (("dt", "seconds per time step", "0.1"), ("resolution", "metres per pixel", "0.05"))


def units_errors(spec) -> list[tuple[str, str]]:
    """``(field, message)`` for each problem of a validated spec's unit fields: ``dt`` and
    ``resolution`` missing or <= 0 with ``units = "m"``, or given without it; a metre file that
    leaves ``width``, ``height``, ``robot.radius`` or ``robot.speed`` to their pixel defaults; a
    random walk's ``hold`` that is not a whole number of time steps. None of the other checks
    run while one of these stands (the conversion to pixels needs them)."""
    if spec.units == "px":
        return [
            (f, f'only for units = "m" (metres and seconds); a pixel scenario has none: remove '
                f'{f}, or add units = "m" and give the file in metres and seconds')
            for f, _, _ in _UNIT_FIELDS
            if getattr(spec, f) is not None
        ]  # fmt: skip
    errors = []
    for f, what, example in _UNIT_FIELDS:
        v = getattr(spec, f)
        if v is None:
            errors.append((f, f'required with units = "m" ({what}, > 0), e.g. {f} = {example}'))
        elif not v > 0:
            errors.append((f, f"must be > 0 ({what}), got {v:g}"))
    unset = [f for f in ("width", "height", "robot") if f not in spec.model_fields_set]
    if "robot" not in unset:
        unset += [f"robot.{f}" for f in ("radius", "speed") if f not in spec.robot.model_fields_set]
    errors += [
        (f, 'required with units = "m": its default is in pixels; give it in metres (metres '
            "per second for a speed)")
        for f in unset
    ]  # fmt: skip
    if errors:
        return errors
    return _hold_errors(spec, spec.dt)


def _hold_errors(spec, dt: float) -> list[tuple[str, str]]:
    errors = []
    for i, ob in enumerate(spec.obstacles):
        m = ob.motion
        if m.model != "bounded_random_walk" or isinstance(whole_steps(m.hold / dt), int):
            continue
        n = math.floor(m.hold / dt)
        near = " or ".join(f"{k * dt:g}" for k in sorted({max(n, 1), n + 1}))
        errors.append(
            (f"obstacles[{i}].motion.hold", f"{m.hold:g} s is not a whole number of time steps "
                f"of dt = {dt:g} s; give a multiple of dt (e.g. {near} s)")
        )  # fmt: skip
    return errors
