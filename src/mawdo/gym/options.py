"""The environments' options: names, defaults, checks, and the sensor they describe."""

from __future__ import annotations

import math
from typing import Any

from mawdo.util.validate import check_bool, check_int, check_real

__all__ = ["COMMON", "check_options", "sensor_of"]

#: Options every environment takes, with their defaults (lengths in metres, speeds in m/s for a
#: metre scenario; pixels and steps for a pixel one).
COMMON: dict[str, Any] = {
    "k": 10,  # agent rows of the observation
    "n_rays": 16,  # range rays against walls and the map border
    "max_range": 4.0,  # ray length (m)
    "sensor_range": None,  # detection range (m); None: unlimited
    "sensor_noise": 0.0,  # s.d. of detected centres (m)
    "miss_rate": 0.0,  # probability of missing an agent in sight, in [0, 1)
    "strays": False,  # the observation's tracker pairs strays (Tracker's strays)
    "max_steps": None,  # step limit (truncation); None: the scene's or scenario's rule
    "success_reward": 1.0,
    "collision_penalty": -0.25,
    "discomfort_dist": 0.2,  # m
    "discomfort_penalty_factor": 0.5,  # per metre inside discomfort_dist, per second
}


def check_options(env_id: str, given: dict[str, Any], extra: dict[str, Any]) -> dict[str, Any]:
    """``given`` completed with the defaults of :data:`COMMON` and ``extra``; an unknown name
    is a ``ValueError`` listing the known ones."""
    known = {**COMMON, **extra}
    unknown = sorted(set(given) - set(known))
    if unknown:
        raise ValueError(
            f"unknown option {unknown[0]!r} for {env_id}; known options: {', '.join(known)}"
        )
    out = {**known, **given}
    check_int("k", out["k"], 0)
    check_int("n_rays", out["n_rays"], 0)
    check_real("max_range", out["max_range"], 0.0, low_open=True)
    if out["sensor_range"] is not None:
        check_real("sensor_range", out["sensor_range"], 0.0, low_open=True)
    check_real("sensor_noise", out["sensor_noise"], 0.0)
    check_real("miss_rate", out["miss_rate"], 0.0, 1.0, high_open=True)
    check_bool("strays", out["strays"])
    if out["max_steps"] is not None:
        check_int("max_steps", out["max_steps"], 1)
    for name in ("success_reward", "collision_penalty"):
        check_real(name, out[name])
    check_real("discomfort_dist", out["discomfort_dist"], 0.0)
    check_real("discomfort_penalty_factor", out["discomfort_penalty_factor"], 0.0)
    return out


def sensor_of(options: dict[str, Any], res: float):
    """The :class:`~mawdo.planning.sense.sensor.Sensor` of the options at ``res`` (metres per
    pixel), or ``None`` for a perfect one (every agent, exactly, as
    :func:`~mawdo.planning.run.episode.run_episode` reads without a sensor)."""
    reach, noise, miss = options["sensor_range"], options["sensor_noise"], options["miss_rate"]
    if reach is None and noise == 0 and miss == 0:
        return None
    from mawdo.planning.sense.sensor import Sensor

    return Sensor(range=math.inf if reach is None else reach / res, noise=noise / res,
                  miss_rate=miss)  # fmt: skip
