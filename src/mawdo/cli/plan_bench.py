"""``mawdo plan bench``: the planning arena (generated scene families x planners).

``mawdo plan bench --suite forest,maze --n 100 ...`` runs (``run`` is the default command);
``mawdo plan bench report STORE --out DIR`` writes the report from the store.
"""

from __future__ import annotations

import json
import sys
from pathlib import Path

import typer
from rich.console import Console

from mawdo.cli.errors import RETRY_HELP, SCHEDULER_FILE_HELP, DefaultRunGroup

console = Console(width=None if sys.stdout.isatty() else 140)


bench_app = typer.Typer(
    cls=DefaultRunGroup,
    no_args_is_help=True,
    add_completion=False,
    help="Planning arena: seeded scene families x planners, success / gap / latency.",
)


def _names(text: str | None) -> list[str] | None:
    return None if text is None else [t.strip() for t in text.split(",") if t.strip()]


def _params(pairs: list[str]) -> dict[str, dict]:
    """``family.key=value`` -> ``{family: {key: value}}`` (values parsed as JSON numbers)."""
    out: dict[str, dict] = {}
    for pair in pairs:
        head, sep, value = pair.partition("=")
        fam, dot, key = head.partition(".")
        if not sep or not dot or not fam or not key:
            raise ValueError(f"--param {pair!r} must look like family.name=value, e.g. forest.n=12")
        try:
            v = json.loads(value)
        except json.JSONDecodeError:
            v = value
        out.setdefault(fam.strip().lower(), {})[key.strip()] = v
    return out


def _options(pairs: list[str]) -> dict:
    """``key=value`` planner overrides (values parsed as JSON when possible)."""
    out = {}
    for pair in pairs:
        key, sep, value = pair.partition("=")
        if not sep or not key.strip():
            raise ValueError(f"--option {pair!r} must look like key=value, e.g. max_steps=200")
        try:
            out[key.strip()] = json.loads(value)
        except json.JSONDecodeError:
            out[key.strip()] = value
    return out


def _plan(suite, n, algorithms, baselines, seed, planner, params, batch_size, options=()):
    from mawdo.experiments.arena import ARENA_PRESETS, arena_preset

    names = _names(suite) or ["arena-default"]
    if len(names) == 1 and names[0] in ARENA_PRESETS:
        plan, fams = arena_preset(names[0]), None
    else:
        plan, fams = arena_preset("arena-default"), names
    return plan.with_overrides(
        name=None if fams is None else "arena",
        families=fams,
        n=n,
        algorithms=_names(algorithms),
        baselines=_names(baselines),
        seed=seed,
        planner=planner,
        params=_params(params) or None,
        batch_size=batch_size,
        overrides=_options(options) or None,
    )


@bench_app.command("run")
def run_cmd(
    suite: str = typer.Option(
        "arena-default",
        help="comma-separated scene families, or a preset (arena-default, arena-quick)",
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
    workers: int = typer.Option(1, help="local worker processes"),
    dask: str = typer.Option(None, help="Dask scheduler address, e.g. tcp://host:8786"),
    scheduler_file: Path = typer.Option(None, help=SCHEDULER_FILE_HELP),
    out: Path = typer.Option(Path("results/arena.db"), help="SQLite results store"),
    force: bool = typer.Option(False, help="discard a store made by another plan or version"),
    retry_failed: bool = typer.Option(False, help=RETRY_HELP),
    report: Path = typer.Option(None, help="also write the report to this folder"),
    progress: bool = typer.Option(True, help="show a progress bar"),
):
    """Run the arena into a resumable store (the same command resumes it)."""
    from mawdo.cli.errors import check_output_dir
    from mawdo.experiments import PlanError, StoreError, run_plan

    if report is not None:
        check_output_dir(report, "--report folder")
    try:
        plan = _plan(suite, n, algorithms, baselines, seed, planner, param, batch_size, option)
    except (PlanError, ValueError) as exc:
        console.print(f"[bold red]error:[/] {exc}")
        raise typer.Exit(2) from None
    console.print(plan.describe())
    try:
        summary = run_plan(
            plan, out, workers=workers, dask=dask, scheduler_file=scheduler_file,
            progress=progress, force=force, retry_failed=retry_failed,
        )  # fmt: skip
    except (StoreError, ValueError) as exc:
        console.print(f"[bold red]error:[/] {exc}")
        raise typer.Exit(1) from None
    console.print(str(summary))
    if summary.interrupted:
        raise typer.Exit(130)
    if report is not None:
        report_cmd(out, report, gallery=200, figures=True)


@bench_app.command("report")
def report_cmd(
    store: Path = typer.Argument(..., help="results store of an arena"),
    out: Path = typer.Option(Path("report/arena"), help="output folder"),
    gallery: int = typer.Option(200, help="at most this many failure images"),
    figures: bool = typer.Option(True, help="write the ECDFs and the failure gallery"),
):
    """Tables, ECDFs and the failure gallery of an arena, read from its store."""
    from mawdo.cli.errors import check_output_dir
    from mawdo.experiments import StoreError
    from mawdo.experiments.arena import write_arena_report

    check_output_dir(out, "--out folder")
    try:
        path = write_arena_report(store, out, figures=figures, gallery_limit=gallery)
    except (StoreError, ValueError) as exc:
        console.print(f"[bold red]error:[/] {exc}")
        raise typer.Exit(1) from None
    console.print(f"report: {path}")
