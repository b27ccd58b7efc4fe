"""Our benchmark results beside the paper's (its Tables 3 and 5): the comparison table, the
paper's own ``+/=/-`` counts and what the paper's numbers are worth for each function."""

from __future__ import annotations

import re
from collections.abc import Sequence

from mawdo.experiments.kinds.benchmark.data import REFERENCE, SweepData, comparisons, summaries
from mawdo.experiments.kinds.benchmark.labels import function_label, label
from mawdo.experiments.kinds.benchmark.paper_values import (
    NOT_COMPARABLE,
    OTHER_FORMULA,
    paper_entry,
)
from mawdo.experiments.tables import Table

PAPER_PROTOCOL = {
    "pop_size": 50,
    "max_iter": 500,
    "runs": 30,
    "budget": "iterations",
    "bounds_preset": "paper",
}


def paper_totals_notes(data: SweepData) -> list[str]:
    """The paper's own ``+/=/-`` counts of MAWDO on the same functions, beside ours.

    Only for unshifted sweeps against MAWDO (the paper has no shifted suite); counted on the
    paper ids of this sweep, F12-F16 included (the signs are the paper's own test on its rows).
    """
    if data.plan.shifted or data.reference != REFERENCE:
        return []
    ids = [function_label(f) for f in data.functions]
    out = []
    for rival in (a for a in data.algorithms if a != data.reference):
        signs = [e[1].sign for e in (paper_entry(rival, p) for p in ids) if e and e[1].sign]
        if signs:
            counts = ", ".join(f"{signs.count(s)} {s}" for s in "+=-")
            # the paper's own algorithm names (its MEWDO is not our reconstruction)
            out.append(
                f"The paper's Table 3 marks MAWDO against {rival.upper()}: {counts} over "
                f"{len(signs)} of these {len(ids)} functions."
            )
    return out


def paper_table(data: SweepData) -> Table | None:
    """Ours beside the paper's Table 3 / 5 values, for algorithms and functions the paper has."""
    if data.plan.shifted:
        return None
    algos = [
        a for a in data.algorithms if any(paper_entry(a, function_label(f)) for f in data.functions)
    ]
    if not algos:
        return None
    summ = summaries(data, "fun")
    signs = {(c.function, c.rival): c.sign for c in comparisons(data)}
    cols = ["Function", "Index"]
    for a in algos:
        cols += [f"{label(a)} ours", f"{label(a)} paper"]
    t = Table(
        "paper_comparison", "Our results beside the paper's (raw final values f)", cols, block=4
    )
    for fn in data.functions:
        pid = function_label(fn)
        for text, attr, field in (
            ("Best", "best", "best"),
            ("Ave", "mean", "ave"),
            ("Std", "std", "std"),
            ("P", None, "sign"),
        ):
            row: list = [pid, text]
            for a in algos:
                ours = (
                    signs.get((fn, a), "")
                    if attr is None
                    else (getattr(summ[a, fn], attr) if (a, fn) in summ else None)
                )
                pe = paper_entry(a, pid)
                if pe is None:
                    theirs = ""
                elif pid in NOT_COMPARABLE:
                    theirs = "n.c."
                else:
                    v = getattr(pe[1], field)
                    theirs = "" if v is None else v
                row += [ours, theirs]
            t.rows.append(row)
    t.notes.append(
        "Paper values from Tables 3 and 5 of arXiv 2511.20394 "
        "(src/mawdo/experiments/kinds/benchmark/paper_values.py)."
    )
    t.notes += comparability_notes([function_label(f) for f in data.functions])
    diffs = [
        f"{k}={getattr(data.plan, k)} (paper {v})"
        for k, v in PAPER_PROTOCOL.items()
        if getattr(data.plan, k) != v
    ]
    if diffs:
        t.notes.append("This plan differs from the paper's protocol: " + ", ".join(diffs) + ".")
    if data.reference != REFERENCE:
        t.notes.append(f"Our P row is against {label(data.reference)}, the paper's against MAWDO.")
    return t


def comparability_notes(paper_ids: Sequence[str]) -> list[str]:
    """What the paper's numbers beside ours are worth, for the paper ids in the table."""
    other = [p for p in paper_ids if p in OTHER_FORMULA]
    nc = [p for p in paper_ids if p in NOT_COMPARABLE]
    same = [
        p for p in paper_ids if re.fullmatch(r"F\d+", p) and p not in OTHER_FORMULA and p not in nc
    ]
    out = []
    if same:
        out.append(
            f"{', '.join(same)}: we run the formula the paper prints (F6 with our reading of its "
            "noise, docs/functions.md#f-noise), so the paper's numbers are for the same function."
        )
    if other:
        anchors = ", ".join(f"{p} {OTHER_FORMULA[p]}" for p in other)
        out.append(
            f"{', '.join(other)}: we run a standard function in place of the printed formula "
            f"({anchors}); the paper's numbers may come from either, so they are not verified "
            "to be comparable."
        )
    if nc:
        out.append(
            f"{', '.join(nc)}: not comparable (n.c. in the tables): the paper's rows for them do "
            "not fit its own function table (docs/functions.md#f-f12-f16)."
        )
    return out
