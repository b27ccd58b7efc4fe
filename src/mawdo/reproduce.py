"""``mawdo reproduce``: every table and figure of the paper's study in one Markdown report.

Runs (or resumes) four stores under ``OUT/results/``: the benchmark table (paper Table 3), the
same on the shifted suite, the ablation (Table 5) and the planning study (Table 6); then writes
each one's report and a top-level ``OUT/report.md`` that gathers them. Re-running skips what is
stored, so an interrupted reproduction picks up where it stopped.
"""

from __future__ import annotations

from contextlib import nullcontext
from pathlib import Path

from mawdo.experiments import run_plan
from mawdo.experiments.kinds.benchmark import preset_plan, write_report
from mawdo.experiments.kinds.benchmark.paper_compare import PAPER_PROTOCOL, comparability_notes
from mawdo.experiments.kinds.planning import study_preset, write_study_report
from mawdo.experiments.kinds.planning.findings import planner_differences

# --quick: the same protocol on a reduced budget (minutes, not an hour).
QUICK_BENCH = {"runs": 5, "max_iter": 100}
QUICK_STUDY = "study-quick"


def reproduce(
    out: str | Path,
    quick: bool = False,
    workers: int | None = None,
    dask=None,
    progress: bool = True,
    say=print,
    bench_overrides: dict | None = None,
    study: str | None = None,
    step=None,
    scheduler_file: str | Path | None = None,
    retry_failed: bool = False,
) -> Path:
    """Run the benchmark, ablation and planning studies and write ``OUT/report.md``.

    Parameters
    ----------
    out : str or Path
        Output folder; stores go to ``out/results``, reports to ``out/<part>``.
    quick : bool
        Reduced budget (5 runs x 100 iterations; 5 planning runs per algorithm, real-time
        planner) instead of the paper's benchmark protocol (30 x 500) and 50 planning runs.
    workers, dask, scheduler_file
        Execution backend (see :func:`~mawdo.experiments.runner.run_plan`); ``workers``
        defaults to 2 local processes, or 1 when a Dask cluster (``dask`` or
        ``scheduler_file``) computes.
    bench_overrides : dict, optional
        Plan fields to change in the three benchmark plans (beyond ``quick``'s).
    study : str, optional
        Study preset to run instead of the default one.
    step : callable, optional
        ``step(message)`` returns a context manager that shows what a step is doing while it
        runs (the command's progress lines); each report (tens of seconds of figures) is one.
    retry_failed : bool
        Compute again the runs stored with an error (see ``run_plan``).
    """
    step = step or (lambda message: nullcontext())
    out = Path(out)
    stores = out / "results"
    if workers is None:  # a cluster computes instead of a local pool
        workers = 1 if dask is not None or scheduler_file is not None else 2
    backend = dict(
        workers=workers, dask=dask, scheduler_file=scheduler_file, retry_failed=retry_failed
    )
    parts, plans = [], []
    for preset, title in (
        ("paper-table3", "Benchmark functions (paper Table 3)"),
        ("paper-table3-shifted", "Shifted suite (optimum off the centre)"),
        ("paper-ablation", "Ablation (paper Table 5)"),
    ):
        plan = preset_plan(preset)
        if quick:
            plan = plan.with_overrides(name=f"{preset}-quick", **QUICK_BENCH)
        if bench_overrides:
            plan = plan.with_overrides(**bench_overrides)
        db = stores / f"{preset}{'-quick' if quick else ''}.db"  # one store per part
        say(f"[{title}] {plan.describe()}")
        summary = run_plan(plan, db, **backend, progress=progress)
        say(f"  {summary}")
        if summary.interrupted:
            raise KeyboardInterrupt
        with step(f"writing the report of {preset} (tables, convergence and box plots)"):
            write_report(db, out / preset)
        parts.append((title, out / preset / "report.md"))
        plans.append(plan)
    study = study_preset(study or (QUICK_STUDY if quick else "paper-table6"))
    db = stores / f"{study.name}-study.db"
    say(f"[Path planning (paper Table 6)] {study.describe()}")
    summary = run_plan(study, db, **backend, progress=progress)
    say(f"  {summary}")
    if summary.interrupted:
        raise KeyboardInterrupt
    with step(f"writing the report of {study.name} (tables and figures of the routes)"):
        report = write_study_report(db, out / "paper-table6")
    parts.append(("Path planning (paper Table 6)", report))
    return _gather(out, parts, _preamble(plans, study, quick))


def _bench_budget(plan) -> str:
    """One benchmark plan's budget, and how it differs from the paper's protocol."""
    diffs = [
        f"{k} {getattr(plan, k)} (paper {v})"
        for k, v in PAPER_PROTOCOL.items()
        if getattr(plan, k) != v
    ]
    what = (
        "the paper's protocol (docs/deviations.md#d-protocol)"
        if not diffs
        else "not the paper's protocol: " + ", ".join(diffs)
    )
    if plan.shifted:
        what += "; shifted suite, ours, not in the paper (docs/functions.md#f-shift)"
    return (
        f"{plan.name}: {plan.runs} runs x {plan.max_iter} iterations, pop {plan.pop_size}; {what}"
    )


def _preamble(bench_plans, study, quick: bool) -> list[str]:
    """What was run and what is, and is not, comparable with the paper: from the plans."""
    from mawdo.functions import FUNCTIONS

    ids = sorted(
        {FUNCTIONS[f].paper_id for p in bench_plans for f in p.functions if f in FUNCTIONS}
        - {None},
        key=lambda p: int(p[1:]),
    )
    lines = ["Budget" + (" (**quick**: reduced)" if quick else "") + ":", ""]
    lines += [f"- {_bench_budget(p)}" for p in bench_plans]
    lines += [
        f"- {study.name}: {study.runs} planning runs per algorithm on '{study.scenario}' "
        f"(the paper: 50); the planner is not the paper's: {planner_differences(study)}",
        "",
        "Readings of the paper and every departure from it: `docs/deviations.md`. What the "
        "paper's numbers beside ours are worth:",
        "",
    ]
    lines += [f"- Benchmark {n}" for n in comparability_notes(ids)]
    lines += [
        "- Path planning: the map is a reconstruction (pixel values are not comparable, "
        "docs/deviations.md#d-paper-scenario) and the planner differs (above), so no number of "
        "Table 6 checks the paper's; the gap L/L* and the rankings are the closest comparison "
        "available, without any claim that they should agree.",
        "",
    ]
    return lines


def _gather(out: Path, parts, preamble: list[str]) -> Path:
    lines = [
        "# mawdo: reproduction of Liu, Mohd Zain & Mao (arXiv 2511.20394)",
        "",
        *preamble,
    ]
    for title, path in parts:
        rel = path.relative_to(out)
        body = path.read_text(encoding="utf-8")
        # re-root the part's image links so they resolve from OUT/report.md
        body = body.replace("](", f"]({rel.parent.as_posix()}/").replace(
            f"]({rel.parent.as_posix()}/http", "](http"
        )
        lines += [
            f"## {title}",
            "",
            f"Full report: [{rel}]({rel.as_posix()})",
            "",
            _demote(body),
            "",
        ]
    path = out / "report.md"
    path.write_text("\n".join(lines), encoding="utf-8")
    return path


def _demote(md: str) -> str:
    """Shift a part's headings down two levels under the gathering report's sections."""
    return "\n".join("##" + ln if ln.startswith("#") else ln for ln in md.splitlines())
