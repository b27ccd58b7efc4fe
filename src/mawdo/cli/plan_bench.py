"""``mawdo plan bench``: the planning arena (generated scene families x planners).

``mawdo plan bench --suite forest,maze --n 100 ...`` runs (``run`` is the default command);
``mawdo plan bench report STORE --out DIR`` writes the report from the store. Both are aliases
of ``mawdo study run/report`` (:mod:`mawdo.cli.study`) for one release.
"""

from __future__ import annotations

import sys
from pathlib import Path

import typer
from rich.console import Console

from mawdo.cli import study
from mawdo.cli.args import dotted_pairs, names, pairs
from mawdo.cli.errors import DefaultRunGroup, fail
from mawdo.cli.study import moved, run_study

console = Console(width=None if sys.stdout.isatty() else 140)


bench_app = typer.Typer(
    cls=DefaultRunGroup,
    no_args_is_help=True,
    add_completion=False,
    help="Planning arena: seeded scene families x planners, success / gap / latency.",
)


def _plan(suite, n, algorithms, baselines, seed, planner, params, batch_size, options=()):
    from mawdo.experiments.kinds.arena import ARENA_PRESETS, arena_preset

    given = names(suite) or ["arena-default"]
    if len(given) == 1 and given[0] in ARENA_PRESETS:
        plan, fams = arena_preset(given[0]), None
    else:
        plan, fams = arena_preset("arena-default"), given
    return plan.with_overrides(
        name=None if fams is None else "arena",
        families=fams,
        n=n,
        algorithms=names(algorithms),
        baselines=names(baselines),
        seed=seed,
        planner=planner,
        params=dotted_pairs(params, "--param", "forest.n=12", group="family") or None,
        batch_size=batch_size,
        overrides=pairs(options, "--option", "max_steps=200") or None,
    )


@bench_app.command("run")
def run_cmd(
    suite: str = typer.Option(
        "arena-default",
        help="comma-separated scene families, or a preset (arena-default, arena-quick, "
        "arena-large: 1000 px worlds with 200 movers, minutes a scene)",
    ),
    n: int = typer.Option(None, "--n", help="scenes per family (override)"),
    algorithms: str = typer.Option(None, help="comma-separated optimizers, e.g. mawdo,woa,gwo"),
    baselines: str = typer.Option(
        None, help="comma-separated baselines: oracle, straight, rrtstar, bitstar, prmstar"
    ),
    seed: int = typer.Option(None, help="master seed of scenes and planners"),
    planner: str = typer.Option(None, help="planner preset: realtime, study, paper, quick"),
    param: list[str] = typer.Option([], help="family parameter, e.g. --param forest.n=12"),
    option: list[str] = typer.Option([], help="planner setting, e.g. --option max_steps=200"),
    batch_size: int = typer.Option(None, help="scenes per task"),
    workers: int = study.WORKERS,
    dask: str = study.DASK,
    scheduler_file: Path = study.SCHEDULER_FILE,
    out: Path = typer.Option(Path("results/arena.db"), help="SQLite results store"),
    force: bool = study.FORCE,
    retry_failed: bool = study.RETRY_FAILED,
    report: Path = typer.Option(None, help="also write the report to this folder"),
    progress: bool = study.PROGRESS,
):
    """Run the arena into a resumable store (the same command resumes it)."""
    from mawdo.cli.errors import check_output_dir
    from mawdo.experiments import PlanError

    moved("mawdo plan bench", "mawdo study run")
    if report is not None:
        check_output_dir(report, "--report folder")
    try:
        plan = _plan(suite, n, algorithms, baselines, seed, planner, param, batch_size, option)
    except (PlanError, ValueError) as exc:
        fail(exc)
    run_study(
        plan, out, workers=workers, dask=dask, scheduler_file=scheduler_file,
        progress=progress, force=force, retry_failed=retry_failed,
    )  # fmt: skip
    if report is not None:
        _write_report(out, report, gallery=200, figures=True)


@bench_app.command("report")
def report_cmd(
    store: Path = typer.Argument(..., help="results store of an arena"),
    out: Path = typer.Option(Path("report/arena"), help="output folder"),
    gallery: int = typer.Option(200, help="at most this many failure images"),
    figures: bool = typer.Option(True, help="write the ECDFs and the failure gallery"),
):
    """Tables, ECDFs and the failure gallery of an arena, read from its store."""
    moved("mawdo plan bench report", "mawdo study report")
    _write_report(store, out, gallery, figures)


def _write_report(store: Path, out: Path, gallery: int, figures: bool) -> None:
    from mawdo.cli.errors import REPORT_CTRL_C, check_output_dir, exit_code_of, on_ctrl_c
    from mawdo.experiments import StoreError
    from mawdo.experiments.kinds.arena import write_arena_report

    on_ctrl_c(REPORT_CTRL_C)
    check_output_dir(out, "--out folder")
    try:
        path = write_arena_report(store, out, figures=figures, gallery_limit=gallery)
    except (StoreError, ValueError) as exc:
        fail(exc, exit_code_of(exc) or 1)
    console.print(f"report: {path}")
