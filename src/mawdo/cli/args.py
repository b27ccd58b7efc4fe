"""The commands' shared argument parsing: comma lists and ``key=value`` pairs.

One copy for every command (``mawdo optimize --option``, ``mawdo study run --set``, the arena's
``--param``/``--option``); a malformed item is a :class:`ValueError` naming the flag, the item
and an example, which the command edge shows as ``error: ...`` (exit 2).
"""

from __future__ import annotations

import json
from typing import Any

from mawdo.util.nesting import loads


def names(text: str | None) -> list[str] | None:
    """``"a, b,,c"`` -> ``["a", "b", "c"]`` (empty items dropped); None stays None."""
    if text is None:
        return None
    return [t.strip() for t in text.split(",") if t.strip()]


def value(text: str, what: str = "the value") -> Any:
    """A flag's value: JSON when it parses (numbers, ``true``, ``null``, lists), else the text
    itself; JSON nested deeper than :data:`mawdo.util.nesting.MAX_NESTING` is a ``ValueError``
    naming ``what`` (never a ``RecursionError``)."""
    try:
        return loads(text, "json", what=what)
    except json.JSONDecodeError:
        return text


def pairs(items: list[str] | None, flag: str, example: str) -> dict[str, Any]:
    """``["key=value", ...]`` -> ``{key: value}``, values read by :func:`value`.

    Parameters
    ----------
    items : list of str or None
        The flag's repeated values.
    flag : str
        The flag's name for messages, e.g. ``"--option"``.
    example : str
        A correct item shown in the message, e.g. ``"groups=4"``.

    Raises
    ------
    ValueError
        An item without ``=`` or with an empty key.
    """
    out: dict[str, Any] = {}
    for item in items or ():
        key, sep, text = item.partition("=")
        if not sep or not key.strip():
            raise ValueError(f"{flag} {item!r} must look like key=value, e.g. {example}")
        out[key.strip()] = value(text, f"{flag} {key.strip()}")
    return out


def dotted_pairs(
    items: list[str] | None, flag: str, example: str, group: str = "group"
) -> dict[str, dict[str, Any]]:
    """``["group.key=value", ...]`` -> ``{group: {key: value}}`` (groups lower-cased).

    ``group`` names the first part in messages (``"family"``: ``family.name=value``).

    Raises
    ------
    ValueError
        An item not of the form ``group.key=value``.
    """
    out: dict[str, dict[str, Any]] = {}
    for item in items or ():
        head, sep, text = item.partition("=")
        first, dot, key = head.partition(".")
        if not sep or not dot or not first.strip() or not key.strip():
            raise ValueError(f"{flag} {item!r} must look like {group}.name=value, e.g. {example}")
        out.setdefault(first.strip().lower(), {})[key.strip()] = value(text, f"{flag} {head}")
    return out
