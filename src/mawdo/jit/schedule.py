"""Which kernel a free compiling process takes next (:class:`Schedule`), and what each process
would compile were every compile to take its recorded seconds (:func:`plan_order`).

:func:`mawdo.jit.warm.warm` hands the table's entries to its processes one at a time, each to
the first process that is free, so the real compile times (which differ from the recorded
ones: Numba's own helpers compile in whichever process first needs them) decide who does
what, and all processes end within about one entry of each other. The rule: the entry with
the longest chain of recorded seconds up to an entry nobody calls comes first (so the cost
kernel's long chain starts at once), and an entry only once every entry it calls is done
(cached), so no process compiles a callee that another one is compiling.
"""

from __future__ import annotations

from typing import Protocol


class Row(Protocol):  # mawdo.jit.warm.Entry
    key: str
    caller: str
    seconds: float


class Schedule:
    """The entries still to hand out, in order of their longest chain, and those done.

    Parameters
    ----------
    entries : list
        Entries with ``key``, ``caller`` (the key of the entry whose compile compiled it, or
        anything else for none) and ``seconds`` (recorded CPU time of its compile, >= 0).
    """

    def __init__(self, entries: list[Row]) -> None:
        by_key = {e.key: e for e in entries}
        self.callees: dict[str, set[str]] = {e.key: set() for e in entries}
        for e in entries:
            if e.caller in by_key and e.caller != e.key:
                self.callees[e.caller].add(e.key)
        chain: dict[str, float] = {}
        for e in entries:  # own seconds plus the callers' up to an entry nobody calls
            total, key, seen = 0.0, e.key, set()
            while key in by_key and key not in seen:  # (a cycle in the table stops here)
                seen.add(key)
                total += by_key[key].seconds
                key = by_key[key].caller
            chain[e.key] = total
        order = sorted(range(len(entries)), key=lambda i: (-chain[entries[i].key], i))
        self.pending = [entries[i] for i in order]
        self.done: set[str] = set()

    @property
    def empty(self) -> bool:
        """Whether every entry has been handed out."""
        return not self.pending

    def next(self, busy: bool = True):
        """The next entry to compile, taken out; None if none is ready (an entry it calls is
        not done yet). With ``busy`` False (no process compiles anything now, so nothing will
        become ready) the first pending entry, ready or not."""
        for i, e in enumerate(self.pending):
            if self.callees[e.key] <= self.done:
                return self.pending.pop(i)
        return self.pending.pop(0) if self.pending and not busy else None

    def finish(self, entry: Row) -> None:
        """Mark ``entry`` done (its callers may be handed out now)."""
        self.done.add(entry.key)


def plan_order(entries: list[Row], jobs: int) -> list[list[Row]]:
    """What each of ``jobs`` processes compiles under :class:`Schedule`'s rule, were every
    compile to take exactly its recorded seconds (no empty lists)."""
    sched = Schedule(entries)
    parts: list[list[Row]] = [[] for _ in range(max(1, jobs))]
    running: dict[int, tuple[float, Row]] = {}  # process -> (end, entry)
    now = 0.0
    while not sched.empty or running:
        for k in range(len(parts)):
            if k not in running:
                e = sched.next(busy=bool(running))
                if e is None:
                    break
                running[k] = (now + e.seconds, e)
                parts[k].append(e)
        k = min(running, key=lambda k: (running[k][0], k))
        now, e = running.pop(k)
        sched.finish(e)
    return [p for p in parts if p]
