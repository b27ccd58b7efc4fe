"""``mawdo bench``: run benchmark plans into a results store and report from it.

A thin Typer layer over :mod:`mawdo.experiments`; every decision lives in the library.
Mounted by the main CLI as ``mawdo bench``. ``run``, ``report`` and ``presets`` are aliases of
``mawdo study run/report/presets`` (:mod:`mawdo.cli.study`) for one release: each says so in
one line on stderr, turns its flags into plan fields and runs through :func:`run_study`.
"""

from __future__ import annotations

from pathlib import Path

import typer

from mawdo.cli import study
from mawdo.cli.args import names
from mawdo.cli.bbob import export_cmd
from mawdo.cli.errors import GuardedGroup, exit_code_of, fail
from mawdo.cli.study import moved, run_study

bench_app = typer.Typer(
    cls=GuardedGroup,  # its errors are plain lines also when it runs on its own (tests)
    name="bench",
    help="Benchmark sweeps (paper Tables 3 and 5): run a plan into a SQLite store, then report.",
    no_args_is_help=True,
    add_completion=False,
)


@bench_app.command("run")
def run_cmd(
    preset: str = typer.Option(None, "--preset", help="Named plan (see `presets`)."),
    plan_file: Path = typer.Option(
        None, "--plan", help="Plan file (TOML; a suite plan also JSON).", exists=False
    ),
    out: Path = typer.Option(Path("results.db"), "--out", "-o", help="Results store (SQLite)."),
    workers: int = study.WORKERS,
    dask: str = study.DASK,
    scheduler_file: Path = study.SCHEDULER_FILE,
    force: bool = study.FORCE,
    retry_failed: bool = study.RETRY_FAILED,
    runs: int = typer.Option(None, "--runs", help="Override: runs per (algorithm, function)."),
    iters: int = typer.Option(None, "--iters", help="Override: iterations (max_iter)."),
    pop_size: int = typer.Option(None, "--pop-size", help="Override: population size."),
    seed: int = typer.Option(None, "--seed", help="Override: master seed."),
    algorithms: str = typer.Option(None, "--algorithms", help="Override: a,b,c"),
    functions: str = typer.Option(None, "--functions", help="Override: f,g (names or F1..F16)"),
    batch_size: int = typer.Option(None, "--batch-size", help="Override: runs per task."),
    budget: str = typer.Option(
        None,
        "--budget",
        help="Override: iterations | evals; with --suite: evaluations per dimension (1e4).",
    ),
    suite: str = typer.Option(
        None, "--suite", help="Standard suite: bbob, cec2017, cec2022 (or cec2017-opfunu, ...)."
    ),
    instances: str = typer.Option(None, "--instances", help="With --suite: instances (1-5)."),
    dims: str = typer.Option(None, "--dims", help="With --suite: dimensions (5,20)."),
    variant: list[str] = typer.Option(
        None,
        "--variant",
        help="With --suite, repeatable: a named variant LABEL=ALGORITHM[:OPTION=VALUE,...] "
        "(e.g. mawdo-r10=mawdo:restart_every=10), stored and reported under LABEL.",
    ),
    option: list[str] = typer.Option(
        None,
        "--option",
        help="With --suite, repeatable: NAME.OPTION=VALUE for an algorithm or a variant "
        "(e.g. mawdo.groups=4).",
    ),
    progress: bool = study.PROGRESS,
) -> None:
    """Run (or resume) a sweep. Stored runs are skipped; Ctrl-C keeps what finished.

    Long by design: a Typer command; its option declarations are most of its length.

    The plan comes from --preset, --plan, or from --algorithms and --functions alone (paper
    defaults: 30 runs, pop 50, 500 iterations); the other flags override its fields.
    """
    from mawdo.cli import bbob
    from mawdo.experiments import ExperimentPlan, PlanError, preset_plan

    moved("mawdo bench run", "mawdo study run")
    backend = dict(
        workers=workers, dask=dask, scheduler_file=scheduler_file, progress=progress,
        force=force, retry_failed=retry_failed,
    )  # fmt: skip
    if suite is not None or bbob.is_suite_preset(preset) or bbob.is_suite_plan_file(plan_file):
        if iters is not None:
            fail("--iters does not apply to --suite studies (budget: --budget 1e4)")
        if preset is not None and plan_file is not None:
            fail("give one of --preset NAME or --plan FILE, not both")
        try:
            splan = bbob.suite_plan(
                preset, suite, names(algorithms), functions, instances, dims, budget,
                plan_file=plan_file, variants=variant or [], options=option or [],
                runs=runs, seed=seed, pop_size=pop_size, batch_size=batch_size,
            )  # fmt: skip
        except PlanError as exc:
            fail(f"invalid plan:\n{exc}")
        except ValueError as exc:  # a malformed flag (--variant, --budget ...)
            fail(str(exc))
        return run_study(splan, out, **backend)
    if instances is not None or dims is not None or variant or option:
        fail("--instances, --dims, --variant and --option need --suite bbob|cec2017|cec2022")
    if preset is not None and plan_file is not None:
        fail("give one of --preset NAME or --plan FILE.toml, not both")
    if preset is None and plan_file is None and (algorithms is None or functions is None):
        fail("give --preset NAME, --plan FILE.toml, or at least --algorithms and --functions")
    try:
        if preset is not None:
            plan = preset_plan(preset)
        elif plan_file is not None:
            plan = ExperimentPlan.from_toml(plan_file)
        else:
            # A plan from flags alone: the paper protocol's defaults for everything not given.
            plan = ExperimentPlan.from_dict(
                {"name": "cli", "algorithms": names(algorithms), "functions": names(functions)}
            )
        plan = plan.with_overrides(
            runs=runs,
            max_iter=iters,
            pop_size=pop_size,
            seed=seed,
            algorithms=names(algorithms),
            functions=names(functions),
            batch_size=batch_size,
            budget=budget,
        )
    except PlanError as exc:
        fail(f"invalid plan:\n{exc}")
    run_study(plan, out, **backend)


@bench_app.command("report")
def report_cmd(
    stores: list[Path] = typer.Argument(
        ...,
        help="Results store written by `run`; for a suite study, several stores of one study "
        "(e.g. one per dimension) are reported together.",
    ),
    out: Path = typer.Option(Path("report"), "--out", "-o", help="Output directory."),
    plots: bool = typer.Option(True, "--plots/--no-plots", help="Draw figures."),
    svg: bool = typer.Option(False, "--svg", help="Also write SVG figures."),
    reference: str = typer.Option(
        None, "--reference", help="Algorithm tested against the others (default mawdo)."
    ),
) -> None:
    """Write tables (Markdown, LaTeX, CSV) and figures from a store, without recomputing."""
    from mawdo.cli.errors import REPORT_CTRL_C, check_output_dir, on_ctrl_c, writing_into
    from mawdo.experiments import StoreError, write_report

    on_ctrl_c(REPORT_CTRL_C)
    moved("mawdo bench report", "mawdo study report")
    check_output_dir(out, "--out folder")
    from mawdo.cli.bbob import is_suite_store, report_suite

    suite = [is_suite_store(s) for s in stores]
    if all(suite):
        with writing_into(out):
            return report_suite(stores, out, plots, svg, reference)
    if len(stores) > 1:
        missing = [str(s) for s in stores if not s.exists()]
        if missing:
            fail(f"no such results store: {', '.join(missing)}")
        others = ", ".join(str(s) for s, ok in zip(stores, suite, strict=True) if not ok)
        fail(
            f"several stores are reported together only for suite studies (`run --suite`); "
            f"{others} is not one: report each store on its own"
        )
    try:
        with writing_into(out):
            files = write_report(stores[0], out, plots=plots, svg=svg, reference=reference)
    except (StoreError, ValueError) as exc:
        fail(exc, exit_code_of(exc) or 1)
    typer.echo(f"wrote {len(files)} files to {out}/ (start with {out / 'report.md'})")


@bench_app.command("presets")
def presets_cmd() -> None:
    """List the named plans of the function benchmark and the suite study."""
    from mawdo.experiments import STUDY_KINDS

    moved("mawdo bench presets", "mawdo study presets")
    for kind in (STUDY_KINDS["benchmark"], STUDY_KINDS["bbob"]):
        for name in kind.presets:
            p = kind.preset_plan(name)
            typer.echo(
                f"{name:22s} {kind.preset_line(name)}\n"
                f"{'':22s} {p.total_runs} runs, plan {p.plan_hash[:12]}"
            )


bench_app.command("export")(export_cmd)
