"""A small name -> entry registry that suggests the closest names on a miss.

Registries drive the CLI (``mawdo list``), the contract test suites and the experiment plans,
so every lookup error must tell the user what exists.
"""

from __future__ import annotations

import difflib
from collections.abc import Iterator, Mapping
from typing import Generic, TypeVar

T = TypeVar("T")


class Registry(Mapping[str, T], Generic[T]):
    """An ordered, case-insensitive mapping from names to entries.

    Parameters
    ----------
    kind : str
        What the entries are ("algorithm", "function", "scenario"); used in error messages.
    """

    def __init__(self, kind: str) -> None:
        self.kind = kind
        self._items: dict[str, T] = {}
        self._aliases: dict[str, str] = {}

    def register(self, name: str, entry: T) -> T:
        """Add ``entry`` under ``name`` (lower-cased); a duplicate name is an error."""
        key = name.lower()
        if key in self._items:
            raise ValueError(f"{self.kind} {name!r} is already registered")
        if key in self._aliases:
            raise ValueError(f"{self.kind} {name!r} is already an alias")
        self._items[key] = entry
        return entry

    def add_alias(self, alias: str, name: str) -> None:
        """Make ``alias`` (a paper id, a former name) look up the registered ``name``; aliases
        are not listed (iteration and ``len`` see registered names only)."""
        key, target = alias.lower(), name.lower()
        if key in self._aliases or key in self._items:
            raise ValueError(f"{self.kind} alias {alias!r} is already taken")
        if target not in self._items:
            raise UnknownNameError(unknown_name_message(self.kind, name, self._items))
        self._aliases[key] = target

    @property
    def aliases(self) -> dict[str, str]:
        """A copy of the alias table (lower-case alias -> registered name)."""
        return dict(self._aliases)

    def resolve(self, name: str) -> str:
        """The lower-case registered name ``name`` stands for (itself, or its alias's target);
        whether it is registered is not checked."""
        key = name.lower()
        return self._aliases.get(key, key)

    def unregister(self, name: str) -> T:
        """Remove and return the entry under ``name`` (for throw-away entries in tests)."""
        entry = self[name]
        del self._items[self.resolve(name)]
        return entry

    def __getitem__(self, name: str) -> T:
        if not isinstance(name, str):
            raise TypeError(f"{self.kind} name must be a string, got {type(name).__name__}")
        key = self.resolve(name)
        try:
            return self._items[key]
        except KeyError:
            raise UnknownNameError(unknown_name_message(self.kind, name, self._items)) from None

    def __iter__(self) -> Iterator[str]:
        return iter(self._items)

    def __len__(self) -> int:
        return len(self._items)

    def __repr__(self) -> str:
        return f"Registry({self.kind!r}, {list(self._items)})"


def unknown_name_message(kind: str, name: str, known) -> str:
    """Message for an unknown name: the closest known names, then the full list."""
    known = list(known)
    close = difflib.get_close_matches(name.lower(), known, n=3, cutoff=0.5)
    hint = f" Did you mean {', '.join(repr(c) for c in close)}?" if close else ""
    plural = kind[:-1] + "ies" if kind.endswith("y") else kind + "s"
    return f"unknown {kind} {name!r}.{hint} Known {plural}: {', '.join(known)}."


class UnknownNameError(KeyError, ValueError):
    """Raised for an unknown registry name; is both a KeyError and a ValueError."""

    def __str__(self) -> str:  # KeyError would quote the message
        return str(self.args[0]) if self.args else ""
