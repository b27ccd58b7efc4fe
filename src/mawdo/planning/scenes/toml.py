"""Write scenarios as TOML files in the scenario schema (the reader is :mod:`tomllib`).

The standard library reads TOML but does not write it, and the schema is small: top-level
scalars, an inline ``robot`` table and an array of ``[[obstacles]]`` tables whose values are
numbers, strings, lists of points and an inline ``motion`` table. Floats are written with
``repr`` (the shortest text that reads back to the same double), strings as TOML basic strings,
so ``load_scenario(write_scenario(s, path))`` equals ``s``.
"""

from __future__ import annotations

import json
import math
from pathlib import Path

from mawdo.planning.world.scenario import Scenario

__all__ = ["scenario_to_toml", "toml_value", "write_scenario"]

_TOP_ORDER = ("schema_version", "name", "description", "seed", "width", "height", "start", "goal")


def toml_value(value) -> str:
    """One TOML value: bool, int, finite float, str, list or (inline) table."""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, int):
        return str(value)
    if isinstance(value, float):
        if not math.isfinite(value):
            raise ValueError(f"cannot write the non-finite number {value!r} to a scenario")
        return repr(value)
    if isinstance(value, str):
        # JSON's escapes (\" \\ \n \uXXXX ...) are a subset of TOML basic strings
        return json.dumps(value, ensure_ascii=True)
    if isinstance(value, list | tuple):
        return "[" + ", ".join(toml_value(v) for v in value) + "]"
    if isinstance(value, dict):
        return "{ " + ", ".join(f"{k} = {toml_value(v)}" for k, v in value.items()) + " }"
    raise TypeError(f"cannot write a {type(value).__name__} to TOML")


def scenario_to_toml(scenario: Scenario | dict) -> str:
    """The scenario (or its dict) as TOML text that :func:`load_scenario` reads back equal."""
    data = scenario.to_dict() if isinstance(scenario, Scenario) else dict(scenario)
    obstacles = data.pop("obstacles", [])
    keys = [k for k in _TOP_ORDER if k in data] + [k for k in data if k not in _TOP_ORDER]
    lines = [f"{k} = {toml_value(data[k])}" for k in keys]
    for ob in obstacles:
        lines += ["", "[[obstacles]]"]
        lines += [f"{k} = {toml_value(v)}" for k, v in ob.items()]
    return "\n".join(lines) + "\n"


def write_scenario(scenario: Scenario, path) -> Path:
    """Write ``scenario`` as TOML to ``path``; a folder gets ``<scenario name>.toml``.

    Returns
    -------
    pathlib.Path
        The file written.
    """
    path = Path(path)
    if path.suffix.lower() != ".toml":
        path.mkdir(parents=True, exist_ok=True)
        path = path / f"{scenario.name}.toml"
    path.write_text(scenario_to_toml(scenario), encoding="utf-8")
    return path
