"""The ``mawdo`` command: a thin layer over the library.

``mawdo list``, ``optimize``, ``demo`` and ``reproduce`` live here; ``mawdo study``
(:mod:`mawdo.cli.study`), ``mawdo bench`` (:mod:`mawdo.cli.bench`) and ``mawdo plan``
(:mod:`mawdo.cli.plan`) are sub-apps mounted below.
The command layer is the top floor: it calls the library and nothing imports it.
"""

from __future__ import annotations

import json
import sys
from pathlib import Path

import numpy as np
import typer
from rich.console import Console
from rich.table import Table

from mawdo.cli.args import pairs
from mawdo.cli.errors import (
    IMAGE_SUFFIXES,
    RETRY_HELP,
    SCHEDULER_FILE_HELP,
    STUDY_CTRL_C,
    GuardedGroup,
    check_output_dir,
    check_output_file,
    fail,
    on_ctrl_c,
)

app = typer.Typer(
    cls=GuardedGroup,
    help="Wind driven optimization (WDO, AWDO, MAWDO) and real-time path planning.",
    no_args_is_help=True,
    add_completion=False,
    pretty_exceptions_show_locals=False,
)
console = Console(width=None if sys.stdout.isatty() else 140)


def _parse_options(items: list[str]) -> dict:
    """``key=value`` strings -> dict, values parsed as JSON when possible (numbers, bools);
    lists become tuples (option values are hashable)."""
    try:
        out = pairs(items, "--option", "--option groups=4")
    except ValueError as exc:
        fail(exc)
    return {k: tuple(v) if isinstance(v, list) else v for k, v in out.items()}


@app.command("list")
def list_cmd(
    what: str = typer.Argument("all", help="algorithms, functions, scenarios, families or all"),
):
    """Show the registered algorithms, benchmark functions, scenarios and scene families."""
    from mawdo.functions import FUNCTIONS, PAPER_SUITE
    from mawdo.optimizers import OPTIMIZERS

    if what not in ("all", "algorithms", "functions", "scenarios", "families"):
        fail(f"unknown listing {what!r}; use algorithms, functions, scenarios, families or all")
    if what in ("all", "algorithms"):
        t = Table(title="algorithms")
        for col in ("name", "label", "description", "reference"):
            t.add_column(col, overflow="fold")
        for name, spec in OPTIMIZERS.items():
            t.add_row(name, spec.display, spec.description, spec.reference)
        console.print(t)
    if what in ("all", "functions"):
        t = Table(title="benchmark functions")
        for col in ("name", "paper", "D", "bounds", "f*"):
            t.add_column(col)
        seen = set()
        for name in FUNCTIONS:
            f = FUNCTIONS[name]
            if id(f) in seen:
                continue  # aliases such as F1 -> sphere
            seen.add(id(f))
            suite = "" if f.name in PAPER_SUITE else " (alt)"
            t.add_row(
                f.name,
                (f.paper_id or "-") + suite,
                str(f.dim),
                f"[{f.lb.min():g}, {f.ub.max():g}]",
                f"{f.f_star:.10g}",
            )
        console.print(t)
    if what in ("all", "scenarios"):
        from mawdo.planning import SCENARIOS

        console.print("scenarios: " + ", ".join(SCENARIOS))
    if what in ("all", "families"):
        _list_families()


def _list_families() -> None:
    from mawdo.planning.scenes import FAMILIES

    t = Table(title="scene families (mawdo plan bench --suite NAME,...)")
    for col in ("name", "description", "parameters (--param NAME.KEY=VALUE)"):
        t.add_column(col, overflow="fold")
    for name, fam in FAMILIES.items():
        t.add_row(name, fam.description, ", ".join(p.name for p in fam.params))
    console.print(t)


def _algorithms(text: str, options: dict) -> list[str]:
    """The ``--algorithm`` list, each name once, with every algorithm's options checked before
    the first one computes (an option one of them refuses would else end the command late)."""
    from mawdo.optimizers import OPTIMIZERS, make_optimizer

    names = [a.strip() for a in text.split(",") if a.strip()]
    if not names:
        fail(f"--algorithm {text!r} names no algorithm; give e.g. -a mawdo or -a wdo,gwo")
    seen: dict[str, str] = {}
    for name in names:
        try:
            key = OPTIMIZERS[name].name
        except KeyError as exc:
            fail(f"--algorithm: {exc}")
        if key in seen:
            fail(
                f"--algorithm lists {key!r} twice ({seen[key]!r} and {name!r}); each algorithm "
                "is one row of the table: list it once"
            )
        seen[key] = name
    for name in names:
        try:
            make_optimizer(name, **options)
        except (ValueError, TypeError) as exc:
            fail(f"{name} (--pop, --option): {exc}")
    return names


@app.command()
def optimize(
    function: str = typer.Argument(..., help="benchmark name or paper id, e.g. rastrigin or F7"),
    algorithm: str = typer.Option(
        "mawdo", "--algorithm", "-a", help="one or more registered names, comma separated"
    ),
    runs: int = typer.Option(30, help="independent runs (one vectorised batch)"),
    seed: int = typer.Option(0, min=0, help="master seed (an integer >= 0)"),
    iters: int = typer.Option(500, help="iterations per run (initial population = 1)"),
    evals: int = typer.Option(None, help="exact evaluation budget per run instead of --iters"),
    pop: int = typer.Option(50, help="population size"),
    dim: int = typer.Option(None, help="dimension for scalable functions"),
    shifted: bool = typer.Option(False, help="move the optimum off the box centre (seeded)"),
    preset: str = typer.Option("paper", help="bounds preset: paper or standard"),
    option: list[str] = typer.Option([], "--option", "-o", help="algorithm option key=value"),
    plot: Path = typer.Option(None, help="save a convergence plot (PNG/SVG)"),
    json_out: Path = typer.Option(None, "--json", help="save per-run results as JSON"),
    progress: bool = typer.Option(True, help="show a progress bar"),
):
    """Run one or more algorithms on a benchmark function and print Best/Ave/Std/nfev/time."""
    from mawdo import minimize

    on_ctrl_c("no result was printed or saved (a rerun computes every run again)")

    opts = _parse_options(option)
    algos = _algorithms(algorithm, {"pop_size": pop, **opts})
    # outputs are checked before minutes of computing, not after
    if plot:
        check_output_file(plot, IMAGE_SUFFIXES, what="--plot")
    if json_out:
        check_output_file(json_out, what="--json")
    results = {}
    for algo in algos:
        try:
            res = minimize(
                function,
                algorithm=algo,
                runs=runs,
                seed=seed,
                max_iter=None if evals else iters,
                max_evals=evals,
                pop_size=pop,
                dim=dim,
                shifted=shifted,
                preset=preset,
                progress=progress,
                **opts,
            )
        except (KeyError, ValueError, TypeError) as exc:
            fail(str(exc.args[0]) if isinstance(exc, KeyError) else str(exc))
        results[res.metadata.get("label", algo)] = res
    _print_table(function, results)
    if plot:
        from mawdo.viz import plot_convergence

        console.print(f"convergence plot: {plot_convergence(results, plot)}")
    if json_out:
        _write_json(json_out, results, seed)
        console.print(f"results: {json_out}")


def _write_json(path: Path, results: dict, seed: int) -> None:
    """Per-run results of each algorithm (label -> fun, nfev, x, params, seed, time) as JSON."""
    payload = {
        label: {
            "fun": r.fun.tolist(),
            "nfev": r.nfev.tolist(),
            "x": r.x.tolist(),
            "params": r.params,
            "seed": seed,
            "time": r.time,
        }
        for label, r in results.items()
    }
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(json.dumps(payload, indent=1, default=str))


def _print_table(function: str, results: dict) -> None:
    first = next(iter(results.values()))
    has_star = first.f_star is not None
    t = Table(
        title=f"{first.problem} ({function}): {first.runs} runs"
        + (f", f* = {first.f_star:.10g}" if has_star else "")
    )
    cols = ["algorithm", "Best", "Ave", "Std"] + (["Ave error"] if has_star else [])
    for col in cols + ["nfev", "time (s)"]:
        t.add_column(col, justify="right")
    for label, r in results.items():
        s = r.summary()
        row = [label, f"{s['best']:.4e}", f"{s['mean']:.4e}", f"{s['std']:.4e}"]
        if has_star:
            row.append(f"{np.mean(r.fun - r.f_star):.4e}")
        row += [f"{s['nfev']:.0f}", f"{r.time:.3f}"]
        t.add_row(*row)
    console.print(t)


def _demo_run(ready, out: Path, drawing=None):
    """The demo's run (set up by ``prepare_demo``), its table and caption printed, its metrics
    saved; the figures' process ``drawing`` (if any) gets its steps as they are made and the
    run before the printing."""
    from mawdo.cli.plan import fed
    from mawdo.cli.progress import notice_compiles
    from mawdo.planning import demo as job

    with notice_compiles():  # a first run after installing compiles the kernels
        run = job.finish_demo(ready.execute(fed(ready, drawing)))
    if drawing is not None:
        drawing.send((run.result, run.metrics, job.figure_text_chunks(run)))
    t = Table(title="MAWDO on the paper scenario (one run)")
    t.add_column("metric")
    t.add_column("value", justify="right")
    for k, v in run.rows():
        t.add_row(k, v)
    console.print(t)
    console.print(run.caption + ".")
    (out / "metrics.json").write_text(json.dumps(run.metrics, indent=1))
    (out / "metrics.md").write_text(
        "| metric | value |\n|---|---|\n" + "".join(f"| {k} | {v} |\n" for k, v in run.rows())
    )
    return run


@app.command()
def demo(
    out: Path = typer.Option(Path("out/demo"), help="output folder"),
    seed: int = typer.Option(0, min=0, help="seed of the run (an integer >= 0)"),
):
    """The main job: MAWDO plans through the moving obstacles of the `paper` scenario."""
    import time

    on_ctrl_c("the run was not finished: no metrics or figures were written")

    from mawdo.cli import quick_exit
    from mawdo.cli.plan import begin_figures, draw_figures, early_figures
    from mawdo.cli.progress import notice_compiles
    from mawdo.planning import demo as job
    from mawdo.planning.world.scenario import get_scenario

    t0 = time.perf_counter()
    check_output_dir(out, "--out folder")
    sc = get_scenario(job.SCENARIO)
    grid, gif = out / job.FIGURE, out / "mawdo_paper.gif"
    console.print(
        f"[bold]mawdo demo[/]: MAWDO on the '{sc.name}' scenario ({sc.width:g} x "
        f"{sc.height:g} px, {len(sc.static_indices)} static and "
        f"{len(sc.moving_indices)} moving obstacles), real-time receding-horizon replanning"
    )
    # the figures' process starts now: matplotlib imported while the run is set up, the
    # figures laid out while it is planned
    with early_figures(True, sc, job.ALGORITHM, seed, grid, gif, label=job.LABEL) as drawing:
        with notice_compiles():  # a first run after installing compiles the kernels
            ready = job.prepare_demo(seed)
        begin_figures(drawing, sc)
        run = _demo_run(ready, out, drawing)
        from mawdo.planning.render.animation import animation_times

        frames = len(animation_times(run.result))
        grid, gif = draw_figures(drawing, frames, True)
    console.print(f"snapshot grid : {grid}")
    console.print(f"animation     : {gif}")
    console.print(f"metrics       : {out / 'metrics.md'}, {out / 'metrics.json'}")
    console.print(f"done in {time.perf_counter() - t0:.1f} s")
    quick_exit.allow()  # files written, the figures' processes joined


@app.command()
def reproduce(
    out: Path = typer.Option(Path("report"), help="output folder (report.md, results/)"),
    quick: bool = typer.Option(False, help="reduced budget: minutes instead of about an hour"),
    workers: int = typer.Option(None, help="local worker processes (default 2; 1 with Dask)"),
    dask: str = typer.Option(None, help="Dask scheduler address"),
    scheduler_file: Path = typer.Option(None, help=SCHEDULER_FILE_HELP),
    retry_failed: bool = typer.Option(False, help=RETRY_HELP),
    progress: bool = typer.Option(True, help="show progress bars"),
):
    """Reproduce the paper: benchmark, shifted suite, ablation and planning study, one report."""
    from functools import partial

    from mawdo.cli.progress import notice_compiles, step
    from mawdo.reproduce import reproduce as run

    on_ctrl_c(STUDY_CTRL_C)
    check_output_dir(out, "--out folder")
    backend = dict(workers=workers, dask=dask, scheduler_file=scheduler_file)
    try:
        with notice_compiles(progress):  # runs with --workers 1 and the reports compile here
            path = run(
                out, quick=quick, **backend, retry_failed=retry_failed, progress=progress,
                say=console.print, step=partial(step, enabled=progress),
            )  # fmt: skip
    except KeyboardInterrupt:
        typer.echo(f"interrupted: stopped by Ctrl-C; {STUDY_CTRL_C}", err=True)
        raise typer.Exit(130) from None
    console.print(f"report: {path}")


def _mount_subapps() -> None:
    from mawdo.cli.bench import bench_app
    from mawdo.cli.plan import plan_app
    from mawdo.cli.study import study_app

    app.add_typer(study_app, name="study")
    app.add_typer(bench_app, name="bench", help="Benchmark study: run plans, make reports.")
    app.add_typer(plan_app, name="plan", help="Path planning among moving obstacles.")


_mount_subapps()

if __name__ == "__main__":  # pragma: no cover
    app()
