"""Reports from a results store: tables (Markdown, LaTeX, CSV) and figures.

Reads only the store (its plan and its runs) and never recomputes a run, so a report can be
regenerated at any time, also from a partial sweep. Every table is a deterministic function of
the stored numbers; wall-clock times go to ``timing.csv`` alone.
The tables beside the paper's are :mod:`.paper_compare`; the store is read by :mod:`.data`.

Files written to the output directory:

``report.md``                 every table below, the figures, the plan.
``results_raw.*``             paper Table 3 layout on raw final values ``f``: per function Best,
                              Ave, Std and the Wilcoxon row ``P`` (reference vs each rival).
``results_error.*``           the same on the error ``f - f*``.
``ablation_raw.*`` / ``ablation_error.*``  paper Table 5 layout (only when the plan has
                              MAWDO-1..4).
``wilcoxon.*``                U, p, Holm-adjusted p and signs per (function, rival), and
``wilcoxon_totals.*``         the ``+/=/-`` counts per rival.
``friedman.*``                average ranks over functions and the Friedman test.
``paper_comparison.*``        our Best/Ave/Std/P beside the paper's (unshifted plans only);
                              F12-F16 marked "not comparable".
``summary.csv``               tidy: one row per (algorithm, function).
``timing.csv``                mean wall time per run (not deterministic).
``convergence.png``, ``boxplots.png`` (and ``.svg`` on request).
"""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path

import numpy as np

from mawdo.experiments import stats
from mawdo.experiments.kinds.benchmark.data import (
    REFERENCE,
    SweepData,
    comparisons,
    load,
    summaries,
)
from mawdo.experiments.kinds.benchmark.labels import function_label, label
from mawdo.experiments.kinds.benchmark.paper_compare import (
    paper_table,
    paper_totals_notes,
)
from mawdo.experiments.store import Store
from mawdo.experiments.tables import Table, to_csv, to_latex, to_markdown
from mawdo.optimizers import ABLATION_ALGORITHMS


# ---------------------------------------------------------------------- tables
def results_table(
    data: SweepData, kind: str, algorithms: Sequence[str], name: str, title: str, wilcoxon: bool
) -> Table:
    """Paper Table 3 / 5 layout: per function Best, Ave, Std (and P) rows, algorithms across."""
    summ = summaries(data, kind)
    signs = {(c.function, c.rival): c.sign for c in comparisons(data)} if wilcoxon else {}
    idx = [("Best", "best"), ("Ave", "mean"), ("Std", "std")]
    t = Table(
        name,
        title,
        ["Function", "Index", *(label(a) for a in algorithms)],
        block=len(idx) + bool(wilcoxon),
    )
    for fn in data.functions:
        for text, attr in idx:
            t.rows.append(
                [
                    function_label(fn),
                    text,
                    *(getattr(summ[a, fn], attr) if (a, fn) in summ else None for a in algorithms),
                ]
            )
        if wilcoxon:
            t.rows.append([function_label(fn), "P", *(signs.get((fn, a), "") for a in algorithms)])
    what = "final value f" if kind == "fun" else "error f - f*"
    t.notes.append(f"Best / Ave / Std (ddof=1) of the {what} over {data.plan.runs} runs.")
    if wilcoxon:
        t.notes.append(
            f"P: Wilcoxon rank-sum (two-sided, 5%) of {label(data.reference)} against each "
            f"algorithm on f: + {label(data.reference)} significantly better, - worse, "
            f"= no significant difference."
        )
    _note_failures(t, data, algorithms)
    _note_partial(t, data)
    return t


def _note_failures(t: Table, data: SweepData, algorithms: Sequence[str]) -> None:
    failed = [
        (a, f, v["failed"]) for (a, f), v in data.finals.items() if v["failed"] and a in algorithms
    ]
    for a, f, n in failed:
        t.notes.append(f"{label(a)} on {function_label(f)}: {n} failed runs excluded.")


def _note_partial(t: Table, data: SweepData) -> None:
    if data.stored < data.total:
        t.notes.append(f"Incomplete sweep: {data.stored} of {data.total} runs stored.")


def wilcoxon_tables(data: SweepData) -> tuple[Table, Table]:
    """Per-cell test results and the per-rival ``+/=/-`` totals (plain and Holm-corrected)."""
    comps = comparisons(data)
    ref = label(data.reference)
    detail = Table(
        "wilcoxon",
        f"Wilcoxon rank-sum of {ref} against each rival",
        ["Function", "Rival", "U", "p", "p (Holm)", "sign", "sign (Holm)"],
        formats={"U": "g", "p": ".3g", "p (Holm)": ".3g"},
    )
    for c in comps:
        detail.rows.append(
            [
                function_label(c.function),
                label(c.rival),
                c.statistic,
                c.pvalue,
                c.p_holm,
                c.sign,
                c.sign_holm,
            ]
        )
    detail.notes.append(
        f"U of {ref}; two-sided asymptotic test with continuity and tie correction; Holm "
        f"correction over all {len(comps)} (rival, function) pairs."
    )
    totals = Table(
        "wilcoxon_totals",
        f"Wins, ties and losses of {ref}",
        ["Rival", "+", "=", "-", "+ (Holm)", "= (Holm)", "- (Holm)"],
    )
    for rival in (a for a in data.algorithms if a != data.reference):
        mine = [c for c in comps if c.rival == rival]
        totals.rows.append(
            [
                label(rival),
                *(sum(c.sign == s for c in mine) for s in "+=-"),
                *(sum(c.sign_holm == s for c in mine) for s in "+=-"),
            ]
        )
    totals.notes += paper_totals_notes(data)
    return detail, totals


def friedman_table(data: SweepData) -> Table:
    """Average Friedman ranks of the mean error, best first."""
    errs = summaries(data, "error")
    m = np.array(
        [
            [errs[a, f].mean if (a, f) in errs else np.nan for a in data.algorithms]
            for f in data.functions
        ],
        dtype=float,
    ).reshape(len(data.functions), len(data.algorithms))
    fr = stats.friedman(m, data.algorithms)
    t = Table(
        "friedman",
        "Friedman average ranks (mean error per function, 1 = best)",
        ["Position", "Algorithm", "Average rank"],
        formats={"Average rank": ".3f"},
    )
    order = np.argsort(fr.mean_ranks, kind="stable")
    for pos, j in enumerate(order, start=1):
        t.rows.append([pos, label(data.algorithms[j]), float(fr.mean_ranks[j])])
    if np.isfinite(fr.statistic):
        t.notes.append(
            f"Friedman chi-square = {fr.statistic:.4g}, p = {fr.pvalue:.3g} over "
            f"{fr.n_functions} functions and {len(data.algorithms)} algorithms."
        )
    else:
        t.notes.append(
            f"Friedman test not computed (needs >= 3 algorithms and >= 2 functions; "
            f"have {len(data.algorithms)} and {fr.n_functions})."
        )
    return t


def summary_table(data: SweepData) -> Table:
    """Tidy per (algorithm, function) statistics of f and f - f*, and mean nfev."""
    cols = ["algorithm", "label", "function", "paper_id", "runs", "failed"]
    for kind in ("fun", "error"):
        cols += [f"{kind}_{s}" for s in ("best", "mean", "std", "median", "worst")]
    cols += ["nfev_mean"]
    t = Table("summary", "Summary per algorithm and function", cols)
    for a in data.algorithms:
        for f in data.functions:
            v = data.finals.get((a, f))
            if v is None:
                continue
            row = [a, label(a), f, function_label(f), int(v["fun"].size), int(v["failed"])]
            for kind in ("fun", "error"):
                s = stats.summarize(v[kind])
                row += [s.best, s.mean, s.std, s.median, s.worst]
            row.append(float(v["nfev"].mean()) if v["nfev"].size else float("nan"))
            t.rows.append(row)
    return t


def timing_table(data: SweepData) -> Table:
    t = Table("timing", "Mean wall time per run (s)", ["algorithm", "function", "wall_mean"])
    for a in data.algorithms:
        for f in data.functions:
            v = data.finals.get((a, f))
            if v is not None and v["wall"].size:
                t.rows.append([a, f, float(np.mean(v["wall"]))])
    return t


def build_tables(data: SweepData) -> list[Table]:
    """Every report table, in report order."""
    plan = data.plan
    suite = " (shifted suite)" if plan.shifted else ""
    out = [
        results_table(
            data,
            "fun",
            data.algorithms,
            "results_raw",
            f"Results on the final value f{suite}",
            wilcoxon=True,
        ),
        results_table(
            data,
            "error",
            data.algorithms,
            "results_error",
            f"Results on the error f - f*{suite}",
            wilcoxon=True,
        ),
    ]
    abl = [a for a in ABLATION_ALGORITHMS if a in data.algorithms]
    if any(a != REFERENCE for a in abl):
        out += [
            results_table(
                data,
                "fun",
                abl,
                "ablation_raw",
                f"Ablation (paper Table 5 layout), final value f{suite}",
                False,
            ),
            results_table(
                data,
                "error",
                abl,
                "ablation_error",
                f"Ablation (paper Table 5 layout), error f - f*{suite}",
                False,
            ),
        ]
    out += [*wilcoxon_tables(data), friedman_table(data)]
    pt = paper_table(data)
    if pt is not None:
        out.append(pt)
    return out


# ---------------------------------------------------------------------- writing
def write_report(
    store_path: str | Path,
    out_dir: str | Path,
    *,
    plots: bool = True,
    svg: bool = False,
    reference: str | None = None,
) -> list[Path]:
    """Write every table (Markdown, LaTeX, CSV) and figure for the store at ``store_path``.

    Parameters
    ----------
    store_path : str or Path
        A results store written by :func:`~mawdo.experiments.runner.run_plan`.
    out_dir : str or Path
        Output directory (created).
    plots : bool
        Also draw the convergence curves and box plots.
    svg : bool
        Save figures as SVG too.
    reference : str, optional
        Algorithm the Wilcoxon tests are against (default MAWDO).

    Returns
    -------
    list of Path
        The files written.
    """
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    written: list[Path] = []

    def put(name: str, text: str) -> None:
        p = out / name
        p.write_text(text, encoding="utf-8")
        written.append(p)

    with Store.read(store_path) as store:
        data = load(store, reference)
        tables = build_tables(data)
        figures: list[Path] = []
        if plots and data.algorithms:
            from mawdo.experiments.kinds.benchmark import plots as plotting

            formats = ("png", "svg") if svg else ("png",)
            figures += plotting.convergence_figure(store, out / "convergence", formats)
            figures += plotting.boxplot_figure(store, out / "boxplots", formats)
    source = f"mawdo {data.library_version}, plan {data.plan_hash[:12]}"
    for t in tables:
        put(f"{t.name}.md", to_markdown(t))
        put(
            f"{t.name}.tex",
            to_latex(t, label=f"tab:mawdo-{t.name.replace('_', '-')}", source=source),
        )
        put(f"{t.name}.csv", to_csv(t))
    put("summary.csv", to_csv(summary_table(data)))
    put("timing.csv", to_csv(timing_table(data)))
    put("report.md", _markdown_report(data, tables, [f for f in figures if f.suffix == ".png"]))
    return written + figures


def _markdown_report(data: SweepData, tables: list[Table], figures: list[Path]) -> str:
    p = data.plan
    lines = [
        f"# Benchmark report: {p.name}",
        "",
        f"- Plan: {p.describe()}",
        f"- Plan hash: `{data.plan_hash}`; mawdo {data.library_version}",
        f"- Runs stored: {data.stored} of {data.total}",
        f"- Algorithms: {', '.join(label(a) for a in p.algorithms)}",
        f"- Functions: {', '.join(function_label(f) for f in p.functions)}",
        f"- Wilcoxon reference: {label(data.reference)}",
        "",
    ]
    for t in tables:
        lines.append(to_markdown(t, heading="##"))
    for f in figures:
        lines += [f"![{f.stem}]({f.name})", ""]
    return "\n".join(lines)
