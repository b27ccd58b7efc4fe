"""The report of a suite study: aRT tables, fixed-budget tables, Friedman ranks (Markdown,
LaTeX, CSV) and figures (runtime ECDFs, convergence), from the store only.
"""

from __future__ import annotations

import os
from pathlib import Path

from mawdo.experiments.kinds.suite.competition import competition_tables, score_table
from mawdo.experiments.kinds.suite.data import StudyRuns, load_runs
from mawdo.experiments.kinds.suite.effects import effect_tables
from mawdo.experiments.kinds.suite.measures import (
    ART_TARGETS,
    RANK_FLOOR,
    art,
    budget_grid,
    friedman_final,
    groups,
    median_precision,
    success_counts,
)
from mawdo.experiments.kinds.suite.summary import function_list, headline
from mawdo.experiments.tables import Table, to_csv, to_latex, to_markdown


def art_table(study: StudyRuns, dim: int) -> Table:
    """aRT (evaluations) per function and target, one column per algorithm."""
    values, succ = art(study, dim), success_counts(study, dim)
    rows = []
    for fid in study.functions:
        for j, t in enumerate(ART_TARGETS):
            rows.append([f"f{fid}", f"{t:.0e}", *values[fid][:, j].tolist()])
        rows.append([f"f{fid}", "solved", *(f"{s}/{n}" for s, n in succ[fid])])
    return Table(
        name=f"art_d{dim}",
        title=f"{study.suite} D={dim}: aRT in evaluations to reach f - f_opt <= target",
        columns=["function", "target", *study.algorithms],
        rows=rows,
        block=len(ART_TARGETS) + 1,
        notes=[
            "aRT = (evaluations of all runs until success or budget) / successes, instances "
            "pooled (COCO); inf: no run reached the target. 'solved': runs reaching 1e-8.",
        ],
        formats=dict.fromkeys(study.algorithms, ".4g"),
    )


def fixed_budget_table(study: StudyRuns, dim: int) -> Table:
    """Median precision over instances and runs after each budget ``D * 10^k`` and the last."""
    budgets = budget_grid(study, dim)
    med = median_precision(study, dim, budgets)
    rows = [
        [f"f{fid}", int(b), *med[fid][:, j].tolist()]
        for fid in study.functions
        for j, b in enumerate(budgets)
    ]
    return Table(
        name=f"fixed_budget_d{dim}",
        title=f"{study.suite} D={dim}: median f - f_opt after a budget (evaluations)",
        columns=["function", "evaluations", *study.algorithms],
        rows=rows,
        block=len(budgets),
        notes=["Runs stop at f - f_opt <= 1e-8 (COCO's final target) and keep that value."],
        formats=dict.fromkeys(study.algorithms, ".3g"),
    )


def friedman_table(study: StudyRuns) -> Table:
    """Friedman mean ranks per dimension and over all dimensions."""
    rows = []
    for label, dims in [*((f"D={d}", (d,)) for d in study.dims), ("all", study.dims)]:
        fr = friedman_final(study, dims)
        rows.append([label, fr.n_functions, *fr.mean_ranks.tolist(), fr.statistic, fr.pvalue])
    return Table(
        name="friedman",
        title=f"{study.suite}: Friedman mean ranks of the median final f - f_opt (1 = best)",
        columns=["dimensions", "blocks", *study.algorithms, "chi2", "p"],
        rows=rows,
        notes=[
            "Blocks: (function, instance, dimension); value: median over runs of the final "
            f"precision, floored at {RANK_FLOOR:g} so solved problems tie.",
        ],
        formats={**dict.fromkeys(study.algorithms, ".2f"), "chi2": ".1f", "p": ".2g"},
    )


def friedman_groups_table(study: StudyRuns) -> Table | None:
    """Friedman mean ranks within each of the suite's function groups, per dimension: where
    each algorithm stands on unimodal, multimodal, hybrid and composition functions (None for
    a suite without groups)."""
    grp = {k: v for k, v in groups(study).items() if k != "all functions"}
    if not grp:
        return None
    rows = []
    for dim in study.dims:
        for name, fids in grp.items():
            fr = friedman_final(study, (dim,), fids)
            if not fr.n_functions:  # a study still running: no finished block in the group
                continue
            rows.append([f"D={dim}", f"{name} ({function_list(fids)})", fr.n_functions,
                         *fr.mean_ranks.tolist(), fr.statistic, fr.pvalue])  # fmt: skip
    return Table(
        name="friedman_groups",
        title=f"{study.suite}: Friedman mean ranks per function group (1 = best)",
        columns=["dimensions", "group", "blocks", *study.algorithms, "chi2", "p"],
        rows=rows,
        notes=[
            "Each group's blocks ranked as in the table of all functions (the ranks of a "
            "block do not depend on the other blocks); chi2 and p: Friedman's test within "
            "the group.",
        ],
        formats={**dict.fromkeys(study.algorithms, ".2f"), "chi2": ".1f", "p": ".2g"},
    )


def _write(table: Table, out: Path) -> list[Path]:
    files = []
    for ext, text in (
        ("md", to_markdown(table)),
        ("tex", to_latex(table, label=f"tab:{table.name}", source="mawdo suite study")),
        ("csv", to_csv(table)),
    ):
        p = out / f"{table.name}.{ext}"
        p.write_text(text, encoding="utf-8")
        files.append(p)
    return files


def _names(store_path) -> str:
    """The store file name(s), without folders (reports are moved and committed)."""
    paths = [store_path] if isinstance(store_path, (str, os.PathLike)) else store_path
    return " + ".join(Path(p).name for p in paths)


def _setup_lines(study: StudyRuns) -> list[str]:
    """One line per algorithm whose name is a variant's label or that has options."""
    shown = [(a, study.setups[a]) for a in study.algorithms if study.setups.get(a, a) != a]
    if not shown:
        return []
    return ["Algorithms run with options:", "", *(f"- {a}: {s}" for a, s in shown), ""]


def write_suite_report(
    store_path, out_dir, plots: bool = True, svg: bool = False, reference: str = "mawdo", **_
) -> Path:
    """Write ``report.md``, the tables (``.md/.tex/.csv``) and the figures into ``out_dir``.

    Parameters
    ----------
    store_path : str, Path or sequence of them
        A store of a suite study (``mawdo bench run --suite ...``), or several stores of one
        study (e.g. one per dimension), merged by
        :func:`~mawdo.experiments.kinds.suite.data.load_runs`.
    out_dir : str or Path
        Output folder (created).
    plots, svg : bool
        Draw the figures (PNG), also as SVG.
    reference : str
        The algorithm the headline sentences (``summary.md``) are about.

    Returns
    -------
    Path
        ``out_dir / "report.md"``.
    """
    study = load_runs(store_path)
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    if not study.runs:
        raise ValueError(f"{_names(store_path)} holds no finished run yet; run the study first")
    summary = headline(study, reference or "mawdo")
    if summary:
        (out / "summary.md").write_text("\n".join(summary) + "\n", encoding="utf-8")
    tables = [friedman_table(study)]
    by_group = friedman_groups_table(study)
    tables += [by_group] if by_group is not None else []
    for dim in study.dims:
        tables += [art_table(study, dim), fixed_budget_table(study, dim)]
    for dim in study.dims:  # component studies: each switch against its base
        tables += effect_tables(study, dim)
    for dim in study.dims:  # the competition's own tables (CEC)
        tables += competition_tables(study, dim)
    score = score_table(study)
    tables += [score] if score is not None else []
    lines = [
        f"# {study.suite} study: {', '.join(study.algorithms)}",
        "",
        f"Functions {', '.join(f'f{f}' for f in study.functions)}; D {study.dims}; budget "
        f"{study.budget:g} x D evaluations; {len(study.runs)} runs stored"
        f"{f', {study.failed} failed' if study.failed else ''} (from {_names(store_path)}, "
        f"made by mawdo {' and '.join(study.versions)}). Precision is the error f - f_opt "
        "(lower is better).",
        "",
        *([study.numbering, ""] if study.numbering else []),
        *_setup_lines(study),
        *summary,
        "",
    ]
    for t in tables:
        _write(t, out)
        lines += [to_markdown(t), ""]
    if plots:
        from mawdo.experiments.kinds.suite.plots import plot_convergence, plot_ecdfs

        for dim in study.dims:
            for p in plot_ecdfs(study, dim, out, svg) + plot_convergence(study, dim, out, svg):
                if p.suffix == ".png":
                    lines += [f"![{p.stem}]({p.name})", ""]
    report = out / "report.md"
    report.write_text("\n".join(lines), encoding="utf-8")
    return report
