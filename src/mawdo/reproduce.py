"""``mawdo reproduce``: every table and figure of the paper's study in one Markdown report.

Runs (or resumes) four stores under ``OUT/results/``: the benchmark table (paper Table 3), the
same on the shifted suite, the ablation (Table 5) and the planning study (Table 6); then writes
each one's report and a top-level ``OUT/report.md`` that gathers them. Re-running skips what is
stored, so an interrupted reproduction picks up where it stopped.
"""

from __future__ import annotations

from pathlib import Path

from mawdo.experiments import run_plan
from mawdo.experiments.benchmark import preset_plan, write_report
from mawdo.experiments.planning import study_preset, write_study_report

# --quick: the same protocol on a reduced budget (minutes, not an hour).
QUICK_BENCH = {"runs": 5, "max_iter": 100}
QUICK_STUDY = "study-quick"


def reproduce(
    out: str | Path,
    quick: bool = False,
    workers: int = 2,
    dask=None,
    progress: bool = True,
    say=print,
    bench_overrides: dict | None = None,
    study: str | None = None,
) -> Path:
    """Run the benchmark, ablation and planning studies and write ``OUT/report.md``.

    Parameters
    ----------
    out : str or Path
        Output folder; stores go to ``out/results``, reports to ``out/<part>``.
    quick : bool
        Reduced budget (5 runs x 100 iterations; 5 planning runs per algorithm, real-time
        planner) instead of the paper's (30 x 500; 50 planning runs).
    workers, dask
        Execution backend (see :func:`~mawdo.experiments.runner.run_plan`).
    bench_overrides : dict, optional
        Plan fields to change in the three benchmark plans (beyond ``quick``'s).
    study : str, optional
        Study preset to run instead of the default one.
    """
    out = Path(out)
    stores = out / "results"
    parts = []
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
        summary = run_plan(plan, db, workers=workers, dask=dask, progress=progress)
        say(f"  {summary}")
        if summary.interrupted:
            raise KeyboardInterrupt
        write_report(db, out / preset)
        parts.append((title, out / preset / "report.md"))
    study = study_preset(study or (QUICK_STUDY if quick else "paper-table6"))
    db = stores / f"{study.name}-study.db"
    say(f"[Path planning (paper Table 6)] {study.describe()}")
    summary = run_plan(study, db, workers=workers, dask=dask, progress=progress)
    say(f"  {summary}")
    if summary.interrupted:
        raise KeyboardInterrupt
    parts.append(("Path planning (paper Table 6)", write_study_report(db, out / "paper-table6")))
    return _gather(out, parts, quick)


def _gather(out: Path, parts, quick: bool) -> Path:
    lines = [
        "# mawdo: reproduction of Liu, Mohd Zain & Mao (arXiv 2511.20394)",
        "",
        "Budget: "
        + (
            "**quick** (reduced; not the paper's protocol)"
            if quick
            else "the paper's protocol (30 runs x 500 iterations, pop 50; 50 planning runs)"
        ),
        "",
        "Readings of the paper and every departure from it: `docs/deviations.md`. "
        "F12-F16 paper values are not comparable (docs/functions.md#f-f12-f16); the planning map "
        "is a "
        "reconstruction (compare ratios and ranks).",
        "",
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
