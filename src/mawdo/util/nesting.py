"""Parse TOML or JSON text without letting its nesting crash the reader.

``tomllib`` and ``json`` parse arrays and tables recursively: text with arrays nested a few
thousand deep ends in ``RecursionError`` (a traceback, not a message), and ``tomllib`` takes
about a minute to get there. Every file format of the project nests a few levels at most, so
the text is scanned first, without recursion, in time linear in its length, and text nested
deeper than a limit is refused with its depth and the line where it happens. Used for plan
files, values of ``--set`` and ``--option`` and plans stored in a results store; scenario files
have the same guard.
"""

from __future__ import annotations

import json
import tomllib
from typing import Any

__all__ = ["MAX_NESTING", "NestingError", "check_nesting", "loads", "nesting_depth"]

#: Most nested arrays and tables accepted (the deepest format of the project needs 4).
MAX_NESTING = 32


class NestingError(ValueError):
    """Text nested deeper than its limit; the message gives the limit and the line."""


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


def _too_deep(limit: int, line: int | None, what: str, needs: str) -> str:
    hint = f"; {needs}" if needs else ""
    where = "" if line is None else f" (line {line})"
    head = f"{what}: " if what else ""
    return f"{head}arrays/tables are nested more than {limit} deep{where}{hint}"


def check_nesting(
    text: str, fmt: str, limit: int = MAX_NESTING, what: str = "", needs: str = ""
) -> None:
    """Raise :class:`NestingError` if ``text`` (``fmt`` "toml" or "json") nests arrays and
    tables deeper than ``limit``.

    ``what`` names the text at the message's start (a file, a flag; none if empty); ``needs``
    says how deep the format really goes (e.g. "a plan needs 3 levels at most").
    """
    depth, line = nesting_depth(text, fmt == "toml", limit=limit)
    if depth > limit:
        raise NestingError(_too_deep(limit, line, what, needs))


def loads(text: str, fmt: str, limit: int = MAX_NESTING, what: str = "", needs: str = "") -> Any:
    """``tomllib.loads`` or ``json.loads`` of ``text`` (``fmt`` "toml" or "json"), refusing
    nesting deeper than ``limit`` before parsing.

    Raises
    ------
    NestingError
        Nesting deeper than ``limit`` (also a ``RecursionError`` of the parser, for a form of
        nesting the scan did not count).
    tomllib.TOMLDecodeError, json.JSONDecodeError
        A syntax error, left to the caller to word.
    """
    check_nesting(text, fmt, limit, what, needs)
    try:
        return tomllib.loads(text) if fmt == "toml" else json.loads(text)
    except RecursionError:
        raise NestingError(_too_deep(limit, None, what, needs)) from None
