"""An attribute held by weak reference, for objects cached per scenario.

The planner caches what it builds for a scenario (guides, roadmaps) in a
:class:`weakref.WeakKeyDictionary` keyed by the scenario, so that the cache entry goes when the
scenario goes. That holds only if the cached object does not itself keep the scenario alive: a
value that refers to its key strongly pins the key, and every scenario ever cached stays in
memory (an observing planner makes a prediction scenario every step, some megabytes a step
over an episode). Such objects keep their scenario in a :class:`WeakAttribute`.
"""

from __future__ import annotations

import weakref

__all__ = ["WeakAttribute"]


class WeakAttribute:
    """A data descriptor whose value is stored as a weak reference.

    Reading it after its object was collected raises :class:`ReferenceError` naming the
    attribute, rather than handing back ``None``.
    """

    def __set_name__(self, owner, name: str) -> None:
        self.name, self.slot = name, f"_weak_{name}"

    def __get__(self, obj, objtype=None):
        if obj is None:
            return self
        target = obj.__dict__[self.slot]()
        if target is None:
            raise ReferenceError(
                f"{type(obj).__name__}.{self.name} no longer exists: keep the object it was "
                "built from alive while this one is used"
            )
        return target

    def __set__(self, obj, value) -> None:
        obj.__dict__[self.slot] = weakref.ref(value)
