"""Parse the text of a scenario file (TOML or JSON) without letting its nesting crash the reader.

``tomllib`` and ``json`` parse arrays and tables recursively: a file with arrays nested a few
thousand deep ends in ``RecursionError`` (a traceback, not a message). The scenario schema
nests four deep at most (``obstacles`` -> an obstacle -> ``vertices`` -> a point), so the text
is scanned first, without recursion (:mod:`mawdo.util.nesting`, the guard of every structured
input), and a file nested deeper than :data:`MAX_NESTING` is refused with its depth and the
line where it happens.
"""

from __future__ import annotations

import json
import tomllib
from typing import Any

from mawdo.util.nesting import MAX_NESTING, NestingError, loads, nesting_depth

__all__ = ["MAX_NESTING", "ScenarioTextError", "nesting_depth", "parse_scenario_text"]


class ScenarioTextError(ValueError):
    """The file's text cannot be read as a scenario (syntax, encoding or nesting)."""


_NEEDS = "a scenario needs 4 levels at most (obstacles -> obstacle -> vertices -> point)"


def parse_scenario_text(text: str, fmt: str) -> Any:
    """Parse a scenario file's text (``fmt`` "toml" or "json") into plain data.

    Raises
    ------
    ScenarioTextError
        For a syntax error, or nesting deeper than :data:`MAX_NESTING` (checked before parsing;
        a ``RecursionError`` of the parser is reported the same way).
    """
    try:
        return loads(text, fmt, MAX_NESTING, needs=_NEEDS)
    except NestingError as exc:
        raise ScenarioTextError(str(exc)) from None
    except (tomllib.TOMLDecodeError, json.JSONDecodeError) as exc:
        raise ScenarioTextError(f"cannot parse {fmt.upper()}: {exc}") from None
