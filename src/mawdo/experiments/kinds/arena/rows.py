"""The arena store's rows as the summaries and the swarm-share table read them: one place, so
that both judge a run by the same gap and count the same runs."""

from __future__ import annotations

from mawdo.experiments.kinds.arena.execute import NO_TRACE, is_timed
from mawdo.experiments.store import Store

__all__ = ["judged_gap", "ok_rows", "timed_families"]


def ok_rows(store: Store, planner: str, family: str | None = None) -> list:
    """The runs of ``planner`` (in ``family``, or all) that finished without an error."""
    rows = store.rows(planner, family, skip=NO_TRACE)
    return [r for _, _, r in rows if r.status == "ok" and r.error_text is None]


def judged_gap(row) -> float:
    """The gap a run is judged by: T/T* on a scene with an earliest arrival (a timed family,
    where the fastest route may be longer than L*, e.g. through a waiting bay), else L/L*."""
    return row.time_gap if row.t_star is not None else row.gap


def timed_families(store: Store) -> list[str]:
    """Families whose planned scenes carry an earliest arrival ``t_star``."""
    rows = {f: [r for _, _, r in store.rows(None, f, skip=NO_TRACE)] for f in store.plan.families}
    return [f for f, fam_rows in rows.items() if is_timed(fam_rows)]
