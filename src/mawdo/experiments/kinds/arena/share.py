"""The swarm's share, measured: each optimizer-driven planner against the same planner with its
optimizer switched off (``guide_only``), paired scene by scene, with a test.

Per planner and family, on the scenes both solve: the paired gaps (:func:`judged_gap`: T/T* on
a timed family, L/L* otherwise) go through a two-sided Wilcoxon signed-rank test
(:func:`signed_rank`), Holm-corrected over the families of that planner; a row's verdict is
``helps`` (significantly smaller gaps), ``hurts`` (larger) or ``no measurable difference`` at
``alpha = 0.05`` after Holm. The crowd report uses the same test and verdicts on its episodes.

Two gaps within a billionth of each other count as equal: the same route, summed in another
order, differs in the last bits (1e-16), and such noise must not vote in a rank test.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from mawdo.experiments.kinds.arena.figures import label
from mawdo.experiments.kinds.arena.rows import judged_gap, ok_rows, timed_families
from mawdo.experiments.stats import ALPHA, holm
from mawdo.experiments.store import Store
from mawdo.experiments.tables import Table

HELPS, HURTS, SAME = "helps", "hurts", "no measurable difference"
#: Relative difference under which two paired values count as equal (rounding, not a change).
RTOL = 1e-9


@dataclass(frozen=True)
class Paired:
    """A two-sided Wilcoxon signed-rank test of ``ours`` against ``base``, paired.

    Attributes
    ----------
    n : int
        Pairs.
    differ : int
        Pairs whose values differ (relative difference above :data:`RTOL`); the others are
        dropped from the ranks (Wilcoxon's zero method).
    pvalue : float
        ``scipy.stats.wilcoxon`` on the differing pairs, in [0, 1]; 1 when no pair differs
        ("no difference"), NaN when there is no pair.
    lower : bool
        Whether ``ours`` tends lower: the ranks of the negative differences ``ours - base`` sum
        higher than those of the positive ones.
    """

    n: int
    differ: int
    pvalue: float
    lower: bool


def differences(ours, base) -> np.ndarray:
    """``ours - base`` pair by pair, 0 where the two agree to a relative :data:`RTOL`."""
    x = np.asarray(ours, dtype=float).ravel()
    y = np.asarray(base, dtype=float).ravel()
    if x.shape != y.shape:
        raise ValueError(f"paired samples differ in length: {x.size} and {y.size}")
    return np.where(np.isclose(x, y, rtol=RTOL, atol=0.0), 0.0, x - y)


def signed_rank(ours, base) -> Paired:
    """Paired two-sided Wilcoxon signed-rank test of ``ours`` against ``base``.

    Parameters
    ----------
    ours, base : array_like
        Paired values (the same scene or episode at the same index), finite, lower is better.

    Returns
    -------
    Paired
        Differences within :data:`RTOL` (relative) count as zero and are dropped
        (``zero_method="wilcox"``); ``p = 1`` when every difference is zero.
    """
    d = differences(ours, base)
    n = int(d.size)
    if not n:
        return Paired(0, 0, float("nan"), False)
    d = d[d != 0.0]
    if not d.size:
        return Paired(n, 0, 1.0, False)
    from scipy import stats as sps  # lazy: importing scipy.stats costs ~1.5 s per command

    ranks = sps.rankdata(np.abs(d))
    lower = bool(ranks[d < 0].sum() > ranks[d > 0].sum())
    p = float(sps.wilcoxon(d, alternative="two-sided").pvalue)
    return Paired(n, int(d.size), min(p, 1.0) if np.isfinite(p) else 1.0, lower)


def holm_verdicts(tests: list[Paired], alpha: float = ALPHA) -> list[tuple[float, str]]:
    """``(Holm-adjusted p, verdict)`` per test, Holm over the tests that have pairs.

    A test without pairs gets ``(NaN, "no pairs")``; the others ``helps`` (``ours``
    significantly lower after Holm), ``hurts`` (higher) or ``no measurable difference``.
    """
    have = [i for i, t in enumerate(tests) if t.n]
    adj = dict(zip(have, holm([tests[i].pvalue for i in have]), strict=True))
    out = []
    for i, t in enumerate(tests):
        if i not in adj:
            out.append((float("nan"), "no pairs"))
        elif adj[i] < alpha:
            out.append((float(adj[i]), HELPS if t.lower else HURTS))
        else:
            out.append((float(adj[i]), SAME))
    return out


def _median(xs) -> float:
    xs = [x for x in xs if x is not None]
    return float(np.median(xs)) if xs else float("nan")


def _family(ours: list, base: list) -> dict:
    """The paired numbers of one planner against the base on one family's planned scenes."""
    won = {r.scene_name: r for r in ours if r.success}
    theirs = {r.scene_name: r for r in base if r.success}
    both = sorted(set(won) & set(theirs))
    a = np.array([judged_gap(won[n]) for n in both], dtype=float)
    b = np.array([judged_gap(theirs[n]) for n in both], dtype=float)
    ran = {r.scene_name for r in ours} & {r.scene_name for r in base}
    return {
        "pairs": len(both),
        "success": sum(bool(r.success) for r in ours) / len(ours) if ours else float("nan"),
        "base success": sum(bool(r.success) for r in base) / len(base) if base else float("nan"),
        "only planner": len((set(won) - set(theirs)) & ran),
        "only base": len((set(theirs) - set(won)) & ran),
        "median": float(np.median(a)) if both else float("nan"),
        "base median": float(np.median(b)) if both else float("nan"),
        "median ratio": float(np.median(a / b)) if both else float("nan"),
        "differ": int(np.count_nonzero(differences(a, b))),
        "mean difference": float(np.mean(differences(a, b))) if both else float("nan"),
        "latency": _median(won[n].latency_p95_ms for n in both),
        "base latency": _median(theirs[n].latency_p95_ms for n in both),
        "test": signed_rank(a, b),
        "searched": _searched(ours),
    }


def _searched(rows: list) -> int | None:
    """How many of the runs searched at least once (a (re)plan not taken by the guide gate);
    None for a store made before the counts were stored."""
    counts = [(r.replans, r.gated) for r in rows]
    if not counts or any(n is None or g is None for n, g in counts):
        return None
    return sum(n > g for n, g in counts)


def share_rows(store: Store, base: str = "guide_only", alpha: float = ALPHA) -> list[dict]:
    """One dict per (optimizer-driven planner, family), in plan order; empty without ``base``.

    Keys: ``planner``, ``family``, ``gap`` (``"T/T*"`` or ``"L/L*"``), ``pairs`` (scenes both
    solve), ``success`` and ``base success`` (over each one's planned scenes), ``only planner``
    and ``only base`` (scenes one solves and the other does not), ``median`` and ``base
    median`` (gaps over the pairs), ``median ratio`` (of the paired gaps, the planner's over
    the base's), ``differ`` (pairs whose gaps differ, :func:`differences`), ``mean
    difference`` (the planner's gap minus the base's, over the pairs), ``latency`` and
    ``base latency`` (median over the pairs of each run's replan p95, ms), ``test``
    (:class:`Paired`), ``p holm`` and ``verdict`` (Holm over the planner's families),
    ``searched`` (the planner's runs in which its optimizer searched at least once, that is
    made a (re)plan the guide gate did not take; None for stores without the counts).
    """
    plan = store.plan
    if base not in plan.planners:
        return []
    timed = set(timed_families(store))
    base_rows = {f: ok_rows(store, base, f) for f in plan.families}
    out = []
    for a in plan.algorithms:
        mine = []
        for f in plan.families:
            ours = ok_rows(store, a, f)
            if ours or base_rows[f]:
                gap = "T/T*" if f in timed else "L/L*"
                mine.append({"planner": a, "family": f, "gap": gap} | _family(ours, base_rows[f]))
        judged = holm_verdicts([m["test"] for m in mine], alpha)
        out += [m | {"p holm": p, "verdict": v} for m, (p, v) in zip(mine, judged, strict=True)]
    return out


def share_columns(base: str) -> list[str]:
    """The share table's header, the base planner named where a column is its."""
    return ["planner", "family", "gap", "pairs", "success", f"{base} success", "only planner",
            f"only {base}", "gap median", f"{base} gap median", "median ratio", "differ",
            "mean difference", "p", "p Holm",
            "verdict", "latency p95 (ms)", f"{base} latency p95 (ms)", "runs searched"]  # fmt: skip


_KEYS = ["pairs", "success", "base success", "only planner", "only base", "median",
         "base median", "median ratio", "differ", "mean difference"]  # fmt: skip


def share_table(store: Store, base: str = "guide_only", alpha: float = ALPHA) -> Table | None:
    """The swarm's share as a table (``swarm_share.md/.tex/.csv``); None without ``base``."""
    rows = share_rows(store, base, alpha)
    if not rows:
        return None
    cols = share_columns(base)
    t = Table(
        name="swarm_share",
        title=f"The swarm's share: each optimizer-driven planner against {base}, paired",
        columns=cols,
        formats={c: ".3f" for c in cols[8:11]}
        | {"success": ".0%", f"{base} success": ".0%", "mean difference": "+.2g"}
        | {"p": ".2g", "p Holm": ".2g"}
        | {c: ".1f" for c in cols[16:18]},
    )
    for r in rows:
        t.rows.append([label(r["planner"]), r["family"], r["gap"], *(r[k] for k in _KEYS),
                       r["test"].pvalue, r["p holm"], r["verdict"], r["latency"],
                       r["base latency"], r["searched"]])  # fmt: skip
    t.notes.append(
        f"{base} is the same planner with its optimizer switched off. Pairs: the scenes both "
        "solve; success over each one's planned scenes; only planner / only "
        f"{base}: scenes one solves and the other does not. Gap (T/T* on timed families, L/L* "
        "otherwise), the median of the paired ratios, the pairs whose gaps differ, the mean "
        f"paired difference (planner minus {base}) and the latency (median of each run's "
        "replan p95) are over the pairs."
    )
    t.notes.append(
        "p: two-sided Wilcoxon signed-rank test of the paired gaps (scipy.stats.wilcoxon; "
        f"pairs within a relative {RTOL:g} count as equal and drop out; p = 1 when no pair "
        f"differs); p Holm: Holm over the planner's families. Verdict at {alpha:g} after Holm: "
        f"helps = significantly smaller gaps than {base}, hurts = larger."
    )
    t.notes.append(
        "Runs searched: the planner's runs of the family in which its optimizer searched at "
        "least once; the guide gate takes the others' every plan from the guides, unsearched "
        "(blank: a store made before the counts were stored)."
    )
    return t


def _named(rows: list[dict]) -> str:
    if not rows:
        return "no family"
    return ", ".join(
        f"{r['family']} ({r['gap']} differs on {r['differ']} of {r['pairs']} scenes, mean "
        f"difference {r['mean difference']:+.2g}, Holm p = {r['p holm']:.2g})"
        for r in rows
    )


def swarm_share(store: Store, base: str = "guide_only", alpha: float = ALPHA) -> list[str]:
    """One summary sentence (Markdown bullet) per optimizer-driven planner: the families where
    its swarm helps and hurts, and how many show no measurable difference (see the table)."""
    rows = share_rows(store, base, alpha)
    lines = []
    for a in store.plan.algorithms:
        mine = [r for r in rows if r["planner"] == a]
        if not mine:
            continue
        by = {v: [r for r in mine if r["verdict"] == v] for v in (HELPS, HURTS, SAME)}
        none = [r["family"] for r in mine if r["verdict"] not in by]
        tested = len(mine) - len(none)
        line = (
            f"- {a} against {base} (the same planner without its optimizer; Wilcoxon "
            f"signed-rank test of the paired gaps on the scenes both solve, Holm over "
            f"{tested} families, {alpha:g}): helps on {_named(by[HELPS])}; hurts on "
            f"{_named(by[HURTS])}; no measurable difference on the other "
            + ("family" if len(by[SAME]) == 1 else f"{len(by[SAME])} families")
        )
        if none:
            line += f"; no scene both solve in {', '.join(none)}"
        lines.append(line + ".")
    return lines
