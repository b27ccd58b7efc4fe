"""Parse the text of a scenario file (TOML or JSON) without letting its nesting crash the reader.

``tomllib`` and ``json`` parse arrays and tables recursively: a file with arrays nested a few
thousand deep ends in ``RecursionError`` (a traceback, not a message). The scenario schema
nests four deep at most (``obstacles`` -> an obstacle -> ``vertices`` -> a point), so the text
is scanned first, without recursion, and a file nested deeper than :data:`MAX_NESTING` is
refused with its depth and the line where it happens.
"""

from __future__ import annotations

import json
import tomllib
from typing import Any

__all__ = ["MAX_NESTING", "ScenarioTextError", "nesting_depth", "parse_scenario_text"]

#: Most nested arrays and tables a scenario file may have (the schema needs 4).
MAX_NESTING = 32


class ScenarioTextError(ValueError):
    """The file's text cannot be read as a scenario (syntax, encoding or nesting)."""


def _skip_string(text: str, i: int, toml: bool) -> int:
    """Index just after the string that starts at ``text[i]`` (a quote character)."""
    q = text[i]
    if toml and text.startswith(q * 3, i):
        end = text.find(q * 3, i + 3)
        while q == '"' and end > 0 and _escaped(text, end):
            end = text.find(q * 3, end + 1)
        return len(text) if end < 0 else end + 3
    j = i + 1
    while j < len(text):
        c = text[j]
        if c == "\\" and q == '"':
            j += 2
            continue
        if c == q or (toml and c == "\n"):
            return j + 1
        j += 1
    return j


def _escaped(text: str, k: int) -> bool:
    n = 0
    while k - 1 - n >= 0 and text[k - 1 - n] == "\\":
        n += 1
    return n % 2 == 1


def nesting_depth(text: str, toml: bool, limit: int | None = None) -> tuple[int, int]:
    """Deepest nesting of ``[ ]`` and ``{ }`` outside strings (and TOML comments), and the
    line (1-based) where it is first reached; stops early once ``limit`` is passed.

    TOML table headers (``[a]``, ``[[obstacles]]``) count as the brackets they are written
    with, which never exceeds their depth in the parsed data by more than one.
    """
    depth = deepest = 0
    line = where = 1
    i, n = 0, len(text)
    while i < n:
        c = text[i]
        if c == "\n":
            line += 1
        elif c == '"' or (toml and c == "'"):
            j = _skip_string(text, i, toml)
            line += text.count("\n", i, j)
            i = j
            continue
        elif toml and c == "#":
            j = text.find("\n", i)
            i = n if j < 0 else j
            continue
        elif c in "[{":
            depth += 1
            if depth > deepest:
                deepest, where = depth, line
                if limit is not None and deepest > limit:
                    break
        elif c in "]}":
            depth = max(depth - 1, 0)
        i += 1
    return deepest, where


def parse_scenario_text(text: str, fmt: str) -> Any:
    """Parse a scenario file's text (``fmt`` "toml" or "json") into plain data.

    Raises
    ------
    ScenarioTextError
        For a syntax error, or nesting deeper than :data:`MAX_NESTING` (checked before parsing;
        a ``RecursionError`` of the parser is reported the same way).
    """
    toml = fmt == "toml"
    depth, line = nesting_depth(text, toml, limit=MAX_NESTING)
    too_deep = (
        f"arrays/tables are nested more than {MAX_NESTING} deep (line {line}); a scenario "
        "needs 4 levels at most (obstacles -> obstacle -> vertices -> point)"
    )
    if depth > MAX_NESTING:
        raise ScenarioTextError(too_deep)
    try:
        return tomllib.loads(text) if toml else json.loads(text)
    except (tomllib.TOMLDecodeError, json.JSONDecodeError) as exc:
        raise ScenarioTextError(f"cannot parse {fmt.upper()}: {exc}") from None
    except RecursionError:  # a form of nesting the scan did not count
        raise ScenarioTextError(too_deep) from None
