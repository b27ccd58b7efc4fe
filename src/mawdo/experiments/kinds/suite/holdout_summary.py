"""Where WDO+ stands on the hold-out suites, in sentences and tables made from the stores only.

``summary.md`` is one paragraph that the README quotes verbatim (a test checks the quote and
that the committed stores give exactly these lines); ``ranks.md`` holds the tables behind it:
the mean Friedman rank of all ten algorithms per suite, and per rival the functions on which
WDO+ is better, worse or tied. Run as a module to rewrite both::

    python -m mawdo.experiments.kinds.suite.holdout_summary STORE... --out docs/results/holdout

The statistic everywhere: per function, the median over runs of the final error ``f - f_opt``,
floored at 1e-8 (COCO's final target) so that solved functions tie; Friedman ranks of that over
the functions every algorithm has finished (1 = best); "better" is a lower median.
"""

from __future__ import annotations

import argparse
import sys
from collections.abc import Sequence
from pathlib import Path

import numpy as np

from mawdo.experiments import stats
from mawdo.experiments.kinds.suite.holdout import HOLDOUT_PRESETS
from mawdo.experiments.kinds.suite.holdout_data import CEC_NAMES, HoldoutSuite, load_holdout
from mawdo.experiments.sqlitefile import StoreError
from mawdo.experiments.tables import Table, to_markdown
from mawdo.optimizers import OPTIMIZERS
from mawdo.suites import evaluation_budget

VARIANT = "wdo_plus"
RIVALS = ("cmaes", "scipy_de", "gwo", "mawdo")
"""The algorithms named for WDO+'s wins and losses (item 5)."""


def name(algorithm: str) -> str:
    """Short display name (``WDO+``, ``CMA-ES``, ``DE (scipy)``)."""
    spec = OPTIMIZERS.get(algorithm)
    return (spec.label or algorithm) if spec is not None else algorithm


def mean_ranks(suite: HoldoutSuite) -> tuple[dict[str, float], int]:
    """Mean Friedman rank per algorithm (1 = best) and the number of functions ranked."""
    fr = stats.friedman(suite.median_errors(), suite.algorithms)
    return dict(zip(suite.algorithms, fr.mean_ranks.tolist(), strict=True)), fr.n_functions


def place(ranks: dict[str, float], algorithm: str) -> int:
    """1 + the number of algorithms with a strictly lower mean rank."""
    return 1 + sum(1 for r in ranks.values() if r < ranks[algorithm])


def versus(suite: HoldoutSuite, ref: str, other: str) -> tuple[list[str], list[str], list[str]]:
    """Functions where ``ref``'s median final error is below (better), above (worse) or equal
    to (tied) ``other``'s; functions either has no run on are left out."""
    med = suite.median_errors()
    i, j = suite.algorithms.index(ref), suite.algorithms.index(other)
    better, worse, tied = [], [], []
    for f, row in zip(suite.functions, med, strict=True):
        a, b = row[i], row[j]
        if np.isnan(a) or np.isnan(b):
            continue
        (better if a < b else worse if a > b else tied).append(f)
    return better, worse, tied


def _goal(suite: HoldoutSuite, ranks: dict[str, float]) -> str:
    """WDO+'s design goal for this suite, and whether the stored runs meet it."""
    if suite.key.startswith("cec"):
        met = place(ranks, VARIANT) == 2 and place(ranks, "cmaes") == 1
        return f"WDO+'s design goal, second only to CMA-ES, is {'met' if met else 'not met'}"
    met = place(ranks, VARIANT) <= 2
    return f"WDO+'s design goal, top two, is {'met' if met else 'not met'}"


def suite_sentence(suite: HoldoutSuite) -> str:
    """One line: WDO+'s rank and place, who is ahead, the rivals' ranks, and its wins and
    losses against each rival by count of functions."""
    ranks, n = mean_ranks(suite)
    at = place(ranks, VARIANT)
    ahead = sorted((a for a in ranks if ranks[a] < ranks[VARIANT]), key=ranks.get)
    where = f"behind {', '.join(f'{name(a)} {ranks[a]:.2f}' for a in ahead)}" if ahead else "first"
    rest = [a for a in RIVALS if a in ranks and a not in ahead]
    others = f"; {', '.join(f'{name(a)} {ranks[a]:.2f}' for a in rest)}" if rest else ""
    counts = []
    for rival in (a for a in RIVALS if a in ranks):
        better, worse, tied = versus(suite, VARIANT, rival)
        counts.append(f"{len(better)} / {len(worse)} / {len(tied)} against {name(rival)}")
    return (
        f"{suite.title}, {suite.protocol}, {n} functions: {name(VARIANT)} {ranks[VARIANT]:.2f}, "
        f"place {at} of {len(ranks)}, {where} ({_goal(suite, ranks)}){others}; better / worse "
        f"/ tied on {', '.join(counts)}."
    )


def headline(suites: Sequence[HoldoutSuite]) -> list[str]:
    """The paragraph the README quotes, one sentence per line (Markdown).

    Parameters
    ----------
    suites : sequence of HoldoutSuite
        The hold-out stores, read by :func:`load_holdout`, in the order to report.

    Returns
    -------
    list of str
        An opening line, one line per suite, the line on what was reduced and why, and one per
        suite with functions still missing (none when every store is complete).
    """
    lines = [
        f"{name(VARIANT)} (`{VARIANT}`) was designed on BBOB alone and is judged here on suites "
        "it never saw, against the hold-out's ten algorithms: the mean Friedman rank of the median "
        "final error f - f_opt per function (1 = best; errors floored at 1e-8, so solved "
        f"functions tie), {name(VARIANT)}'s place, and on how many functions its median final "
        "error is better / worse / tied against each rival."
    ]
    lines += [suite_sentence(s) for s in suites]
    lines.append(_reduced(suites))
    for s in suites:
        gap = _gap(s)
        if gap:
            lines.append(f"Not computed (runs missing) in {s.title}: {gap}.")
    return lines


def _number(label: str) -> int | None:
    """``"F12"`` -> 12; None for a label that is not ``F`` and a number."""
    return int(label[1:]) if label[:1] == "F" and label[1:].isdigit() else None


def _gap(suite: HoldoutSuite) -> str:
    """``"F5 (gwo, woa); no run on F6-F29"``: the functions some algorithms have not finished,
    naming them, then the functions nobody has started, as ranges; ``""`` when complete."""
    partial, empty = [], []
    for f in suite.functions:
        short = [a for a in suite.algorithms if len(suite.finals.get((a, f), ())) < suite.runs]
        if len(short) == len(suite.algorithms) and not any(
            (a, f) in suite.finals for a in suite.algorithms
        ):
            empty.append(f)
        elif short:
            partial.append(f"{f} ({', '.join(short)})")
    spans: list[list[str]] = []
    for f in empty:  # consecutive labels F6, F7, ... -> one span
        n, last = _number(f), _number(spans[-1][-1]) if spans else None
        if n is not None and last is not None and n == last + 1:
            spans[-1].append(f)
        else:
            spans.append([f])
    ranges = ", ".join(s[0] if len(s) == 1 else f"{s[0]}-{s[-1]}" for s in spans)
    return "; ".join([*partial, *([f"no run on {ranges}"] if ranges else [])])


def _reduced(suites: Sequence[HoldoutSuite]) -> str:
    """What the study cut from the full protocol: the stores' plans against the full presets
    (``holdout-cec2017``, ``holdout-cec2022-d10``/``-d20``; F1-F16: the benchmark kind's
    ``holdout-paper*``, 50 x 500 evaluations and 30 runs, which tests/test_holdout_results.py
    checks)."""
    cec = [s for s in suites if s.key.startswith("cec")]
    paper = [s for s in suites if not s.key.startswith("cec")]
    here = [f"{CEC_NAMES[s.key]} at {_dims(s)}: {s.protocol}" for s in cec]
    here += [f"{p} on F1-F16" for p in sorted({s.protocol for s in paper})]
    p17 = HOLDOUT_PRESETS["holdout-cec2017"]
    p22 = [HOLDOUT_PRESETS[f"holdout-cec2022-d{d}"] for d in (10, 20)]
    full = (
        f"CEC 2017 at D = {' and '.join(map(str, p17['dims']))} with {p17['budget']:g} x D "
        f"evaluations, CEC 2022 at D = {' and '.join(str(p['dims'][0]) for p in p22)} with "
        f"{' and '.join(str(evaluation_budget(p['budget'], p['dims'][0])) for p in p22)} "
        f"evaluations, {p17['runs']} runs, and F1-F16 with 50 x 500 evaluations and 30 runs"
    )
    timed = [s for s in cec if s.random_us is not None]
    cost = ", ".join(f"{CEC_NAMES[s.key]} at {_dims(s)} {s.random_us:.0f} us" for s in timed)
    # one figure per suite (the mean of its stores'): its full presets cover all its dimensions
    per_eval: dict[str, list[float]] = {}
    for s in timed:
        per_eval.setdefault(s.key, []).append(s.random_us)
    days = sum(full_evaluations(k) * float(np.mean(v)) * 1e-6 for k, v in per_eval.items()) / 86400
    return (
        f"The study is reduced ({'; '.join(here) or 'no suite'}; the full presets ask {full}) "
        "because opfunu evaluates CEC functions one point per call: at random search's wall "
        f"time per evaluation in these stores ({cost or 'not stored'}; its own cost is "
        f"negligible), the full presets of these CEC suites take {days:.1f} days of one core "
        "for the evaluations alone, and the machine that made this study had 2 shared cores."
    )


def _dims(suite: HoldoutSuite) -> str:
    return "D = " + " and ".join(map(str, suite.dims))


def full_evaluations(suite: str) -> int:
    """Objective evaluations of the full hold-out presets of one CEC suite (all dimensions,
    functions, algorithms and runs)."""
    total = 0
    for p in HOLDOUT_PRESETS.values():
        if p["suite"] == suite and not p["name"].startswith("holdout-quick"):
            per_run = sum(evaluation_budget(p["budget"], d) for d in p["dims"])
            total += per_run * len(p["functions"]) * len(p["algorithms"]) * p["runs"]
    return total


def rank_table(suites: Sequence[HoldoutSuite]) -> Table:
    """Mean Friedman rank of every algorithm per suite, and WDO+'s place."""
    algos = list(dict.fromkeys(a for s in suites for a in s.algorithms))
    rows = []
    for s in suites:
        ranks, n = mean_ranks(s)
        rows.append(
            [s.title, n, *(ranks.get(a, float("nan")) for a in algos), place(ranks, VARIANT)]
        )
    return Table(
        name="ranks",
        title="Mean Friedman rank per hold-out suite (1 = best)",
        columns=["suite", "functions", *map(name, algos), f"{name(VARIANT)} place"],
        rows=rows,
        notes=[
            "Per function: median over runs of the final f - f_opt, floored at 1e-8; ranked "
            "among the algorithms; averaged over the functions every algorithm finished."
        ],
        formats=dict.fromkeys(map(name, algos), ".2f"),
    )


def versus_table(suites: Sequence[HoldoutSuite]) -> Table:
    """Per suite and rival, the functions on which WDO+ is better, worse and tied."""
    rows = []
    for s in suites:
        for rival in (a for a in RIVALS if a in s.algorithms):
            better, worse, tied = versus(s, VARIANT, rival)
            rows.append(
                [
                    s.title,
                    name(rival),
                    *(f"{len(x)}: {' '.join(x) or '-'}" for x in (better, worse, tied)),
                ]
            )
    return Table(
        name="versus",
        title=f"{name(VARIANT)} against each rival, function by function (median final error)",
        columns=["suite", "rival", "better", "worse", "tied"],
        rows=rows,
    )


def write_holdout_summary(stores: Sequence[str | Path], out_dir: str | Path) -> list[Path]:
    """Write ``summary.md`` (the README's paragraph) and ``ranks.md`` into ``out_dir``.

    Parameters
    ----------
    stores : sequence of str or Path
        The hold-out stores, in report order (CEC 2017, CEC 2022, F1-F16, F1-F16 shifted).
    out_dir : str or Path
        Output folder (created).

    Returns
    -------
    list of Path
        The files written.
    """
    suites = [load_holdout(p) for p in stores]
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    summary, ranks = out / "summary.md", out / "ranks.md"
    summary.write_text("\n".join(headline(suites)) + "\n", encoding="utf-8")
    stores_line = "Stores: " + ", ".join(f"{s.store} ({s.title})" for s in suites) + "."
    body = [to_markdown(rank_table(suites)), to_markdown(versus_table(suites))]
    ranks.write_text("\n\n".join([stores_line, *body]) + "\n", encoding="utf-8")
    return [summary, ranks]


def main(argv: Sequence[str] | None = None) -> int:
    """``python -m mawdo.experiments.kinds.suite.holdout_summary STORE... --out DIR``."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("stores", nargs="+", type=Path, help="hold-out stores, in report order")
    parser.add_argument("--out", type=Path, required=True, help="output folder")
    args = parser.parse_args(argv)
    try:
        for p in write_holdout_summary(args.stores, args.out):
            print(p)
    except (ValueError, OSError, StoreError) as exc:  # a missing or foreign store: say which
        print(f"error: {exc}", file=sys.stderr)
        return 2
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
