"""``mawdo plan run map.yaml --start x,y --goal x,y``: a ROS ``map_server`` map as the run's
scenario (:func:`mawdo.planning.world.rosmap.load_ros_map`), and the options it takes."""

from __future__ import annotations

import math
from pathlib import Path

import typer

#: The suffixes of a ROS map's YAML file.
ROS_SUFFIXES = (".yaml", ".yml")
START = typer.Option(None, "--start", help="start x,y in ROS world metres (a ROS map .yaml)")
GOAL = typer.Option(None, "--goal", help="goal x,y in ROS world metres (a ROS map .yaml)")
ROBOT_RADIUS = typer.Option(None, help="robot radius in metres (a ROS map; default 0.3)")
ROBOT_SPEED = typer.Option(None, help="robot speed in m/s (a ROS map; default 1.0)")


def ros_map_scenario(name: str, start, goal, robot_radius, robot_speed):
    """The scenario of a ROS map file (``.yaml``/``.yml``), or None for any other scenario,
    which then takes none of these options.

    Raises
    ------
    ValueError
        For a missing or malformed ``--start``/``--goal``, these options given with another
        scenario, or a bad map (:class:`~mawdo.planning.world.scenario.ScenarioError`).
    FileNotFoundError
        For a missing map file or image.
    """
    options = {"--start": start, "--goal": goal, "--robot-radius": robot_radius,
               "--robot-speed": robot_speed}  # fmt: skip
    if Path(name).suffix.lower() not in ROS_SUFFIXES:
        given = [flag for flag, v in options.items() if v is not None]
        if given:
            raise ValueError(
                f"{', '.join(given)}: only for a ROS map (.yaml); the scenario {name!r} gives "
                "its own start, goal and robot"
            )
        return None
    missing = [flag for flag in ("--start", "--goal") if options[flag] is None]
    if missing:
        raise ValueError(
            f"a ROS map needs {' and '.join(missing)} as x,y in ROS world metres, e.g. "
            f"{missing[0]} 1.5,-2.0"
        )
    from mawdo.planning.world.rosmap import load_ros_map

    return load_ros_map(
        name,
        point(start, "--start"),
        point(goal, "--goal"),
        0.3 if robot_radius is None else robot_radius,
        1.0 if robot_speed is None else robot_speed,
    )


def point(text: str, flag: str) -> tuple[float, float]:
    """``"x,y"`` as two finite floats; ``ValueError`` naming ``flag`` otherwise."""
    try:
        x, y = (float(v) for v in text.split(","))
    except ValueError:
        x = y = math.nan
    if not (math.isfinite(x) and math.isfinite(y)):
        raise ValueError(f"{flag} {text!r}: give x,y in metres, e.g. {flag} 1.5,-2.0")
    return x, y
