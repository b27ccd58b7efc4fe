"""``mawdo plan``: plan through a scenario and write metrics (and figures).

``mawdo plan SCENARIO ...`` runs one planning run (``run`` is the default command);
``mawdo plan study ...`` and ``mawdo plan report`` are aliases of ``mawdo study run/report``
(:mod:`mawdo.cli.study`) for one release.
"""

from __future__ import annotations

import json
import sys
from contextlib import contextmanager
from pathlib import Path

import typer
from rich.console import Console

from mawdo.cli import quick_exit, record_output, rosmap_input, study
from mawdo.cli.errors import DefaultRunGroup
from mawdo.cli.progress import ERR, notice_compiles, step

console = Console(width=None if sys.stdout.isatty() else 140)


plan_app = typer.Typer(
    cls=DefaultRunGroup,
    no_args_is_help=True,
    add_completion=False,
    help="Path planning among moving obstacles.",
)


def _scenario(name_or_path: str):
    from mawdo.planning import get_scenario, load_scenario

    p = Path(name_or_path)
    if p.suffix.lower() in (".toml", ".json") or p.exists():
        return load_scenario(p)
    return get_scenario(name_or_path)  # raises with close-name suggestions


THREADS_HELP = "threads for the population cost (same result); at most the CPUs it may use"


def usable_cpus() -> int:
    """The CPUs this process may run on (its affinity mask; all of the machine's elsewhere)."""
    import os

    try:
        return len(os.sched_getaffinity(0))
    except AttributeError:  # not on Linux
        return os.cpu_count() or 1


def check_threads(threads: int) -> None:
    """Refuse more ``--threads`` than CPUs: the extra threads would wait for a CPU, the result
    would be the same, and the run's time estimate (measured with that many threads) would
    count their waiting (``--threads 64`` on 2 CPUs: "about 2649 min" for a 76 s run)."""
    from mawdo.cli.errors import fail

    cpus = usable_cpus()
    if threads > cpus:
        fail(
            f"--threads {threads}: this command may use {cpus} CPU(s); give --threads {cpus} "
            "or fewer (more threads than CPUs only wait for each other; the result is the same)"
        )


#: From this many moving obstacles a run under the default preset suggests ``large``.
LARGE_MOVERS = 100


def _prepare(sc, algorithm, seed, preset, static, threads, max_steps, sense=None):
    """The run, set up and checked; a run that may take minutes says so (stderr) first.
    ``sense``: ``(knowledge, sensor)`` for a stepped run (a scenario with people, or
    ``--knowledge observed``)."""
    from mawdo.planning.run.planner import prepare

    extra = {} if max_steps is None else {"max_steps": max_steps}
    run = prepare(sc, algorithm, seed, preset, not static, threads=threads, **extra)
    if sense is not None:
        from mawdo.planning.run.stepped_cli import stepped_run

        run = stepped_run(sc, algorithm, seed, preset, run.step_limit()[0], *sense,
                          threads=threads)  # fmt: skip
    steps, rule = run.step_limit()
    capped = rule > steps and max_steps is None
    seconds = run.estimate_seconds(steps)
    if capped or seconds > 60:
        note = f"step limit: {steps:,} steps"
        if capped:
            note += f" (the automatic {rule:,} capped; --max-steps allows more)"
        if seconds > 60:
            note += f"; this run may take up to about {seconds / 60:.0f} min"
        typer.echo(note, err=True)
    if preset == "realtime" and not static and len(sc.moving_indices) >= LARGE_MOVERS:
        from mawdo.planning.run.config import PRESETS

        ahead = PRESETS["large"].lookahead
        typer.echo(
            f"{len(sc.moving_indices)} moving obstacles: --preset large plans a world this size "
            f"several times faster (it trusts their predicted motion {ahead:g} steps "
            "ahead; every step is still checked against the whole prediction)",
            err=True,
        )
    return run


def _sense(sc, knowledge, static, sensor_range, sensor_noise, miss_rate, predictor):
    """``(knowledge, sensor, predictor)`` of a stepped run, or None for the planner's own run
    loop."""
    from mawdo.planning.run.stepped_cli import sense_of

    return sense_of(sc, knowledge, static, sensor_range, sensor_noise, miss_rate, predictor)


@contextmanager
def early_figures(enabled: bool, sc, algorithm: str, seed: int, grid: Path, gif: Path, **kw):
    """A run's snapshot grid and GIF begun now in a forked process (:mod:`mawdo.planning.render
    .early`), ended if the ``with`` body stops early; yields None without figures (disabled, or
    no matplotlib). Begun once the scenario is read and Numba imported (the render modules
    import it), before the run is set up: the process imports matplotlib meanwhile
    (:func:`~mawdo.planning.render.early.warm_up`) and waits for :func:`begin_figures`, which
    hands it the static optimum, so it loads no kernel itself (forked before Numba's import,
    it imported Numba and the planner a second time, 1.3 s more CPU, as measured at load 5).
    What exists so far is frozen for the garbage collector first (:func:`settled`).
    On a cold kernel cache as well: the process imports matplotlib while the kernels compile
    and sets the figures up while the run is planned, as on a warm one (it compiles nothing:
    :func:`begin_figures` comes after the compile), instead of drawing everything after the
    run (cold ``plan paper``: 1.6 -> 0.4 s after the run)."""
    import importlib.util

    if not enabled or importlib.util.find_spec("matplotlib") is None:
        settled()
        yield None
        return
    from mawdo.planning.render.early import EarlyFigures, run_figures

    prepare = run_figures(sc, algorithm, seed, grid, gif, **kw)
    settled()
    with EarlyFigures(prepare) as job:
        yield job


def settled() -> None:
    """Move every object made so far (the imported modules, the scenario) out of the garbage
    collector's sight (``gc.freeze``), as Python's documentation advises before a ``fork``:
    ``plan paper``'s set-up and run made one full collection of 131 000 objects (0.05-0.07 s
    of CPU, 3 runs), none now; the figures' process forked next does not scan them either, so
    it leaves the pages it shares with this one unwritten (copy-on-write faults of this
    process while it sets its run up: 13 700 -> 11 100). These objects live until the command
    ends anyway; nothing is computed differently."""
    import gc

    gc.freeze()


def begin_figures(job, sc) -> None:
    """Give the figures' process ``job`` (None: no figures) the scenario's static optimum
    path, computed here with the oracle's kernels this process has loaded for its run (the
    figures' process, forked before, would load them again)."""
    if job is not None:
        from mawdo.planning.render.style import optimum_path

        job.begin(optimum_path(sc, {}))


def fed(run, job, then=None):
    """The progress callback of ``run.execute``: ``then`` (a progress bar), and with a figures'
    process ``job`` the run's steps sent to it as they are made (it draws the GIF's frames
    meanwhile: :mod:`mawdo.planning.render.live`)."""
    if job is None:
        return then
    from mawdo.planning.render.live import RunStream

    return RunStream(run, job, then)


def draw_figures(job, frames: int, progress: bool) -> tuple[Path, Path]:
    """Wait for the figures of a run sent to the figures' process (:meth:`EarlyFigures.send
    <mawdo.planning.render.early.EarlyFigures.send>`), saying so (stderr)."""
    note = ", set up while planning" if job.early else ""
    with step(f"drawing the snapshot grid and writing the GIF ({frames} frames{note})", progress):
        return job.result()


class _StepBar:
    """A rich progress bar over the planner's steps (stderr), with the replan count."""

    def __init__(self, enabled: bool, label: str) -> None:
        self.progress = self.task = None
        if not enabled:
            return
        from rich.progress import TimeElapsedColumn

        from mawdo.experiments.progress import start_bar

        columns = ["steps, {task.fields[replans]} replans", TimeElapsedColumn()]
        self.progress, self.task = start_bar(label, columns, console=ERR, transient=True, replans=0)

    def __call__(self, step: int, max_steps: int, replans: int) -> None:
        if self.progress is not None:
            self.progress.update(self.task, completed=step, total=max_steps, replans=replans)

    def close(self) -> None:
        if self.progress is not None:
            self.progress.stop()


@plan_app.command("run")
def run_cmd(
    scenario: str = typer.Argument(
        ..., help="built-in name (paper), a .toml/.json file or a ROS map .yaml"
    ),
    algorithm: str = typer.Option("mawdo", "--algorithm", "-a", help="registered optimizer"),
    seed: int = typer.Option(0, min=0, help="seed of the run (an integer >= 0)"),
    preset: str = typer.Option(
        "realtime",
        help="planner preset: realtime, large (worlds far larger than the paper's), paper or quick",
    ),
    static: bool = typer.Option(False, "--static", help="plan once on the map frozen at t=0"),
    out: Path = typer.Option(Path("out/plan"), help="output folder (metrics.json, figures)"),
    figures: bool = typer.Option(True, help="write the snapshot grid and the GIF"),
    progress: bool = typer.Option(True, help="show a progress bar (stderr)"),
    threads: int = typer.Option(1, min=1, help=THREADS_HELP),
    max_steps: int = typer.Option(
        None,
        min=1,
        max=1_000_000,  # mawdo.planning.world.scenario.MAX_RUN_STEPS (not imported: startup time)
        help="step limit (default: 4 straight lines or 2 detours around the static obstacles, "
        "at most 20000)",
    ),
    knowledge: str = typer.Option(
        None,
        help="what the planner knows of the moving agents: oracle (their future) or observed "
        "(sensor, tracker, predictor each step); default observed with people, else oracle",
    ),
    sensor_range: float = typer.Option(None, min=0, help="sensor range (scenario units)"),
    sensor_noise: float = typer.Option(
        0.0, min=0, help="s.d. of sensed positions (scenario units)"
    ),
    miss_rate: float = typer.Option(0.0, min=0, max=0.999, help="chance to miss an agent"),
    predictor: str = typer.Option(
        "constant_velocity", help="how observed agents are predicted: constant_velocity, stop"
    ),
    start: str = rosmap_input.START,
    goal: str = rosmap_input.GOAL,
    robot_radius: float = rosmap_input.ROBOT_RADIUS,
    robot_speed: float = rosmap_input.ROBOT_SPEED,
    record: Path = record_output.RECORD,
):
    """Plan and execute one run; print and save its metrics."""
    from mawdo.cli.errors import bad_input, check_output_dir, on_ctrl_c

    on_ctrl_c("the run was not finished: no metrics or figures were written")
    check_threads(threads)
    # every input is checked before --out is created (exit 2, as for the other commands)
    try:
        sc = rosmap_input.ros_map_scenario(scenario, start, goal, robot_radius, robot_speed)
        sc = sc or _scenario(scenario)
        sense = _sense(sc, knowledge, static, sensor_range, sensor_noise, miss_rate, predictor)
        record_output.check_record(record)
    except (KeyError, ValueError, FileNotFoundError, ImportError) as exc:
        raise bad_input(exc) from None
    # the figures' process starts now: it imports matplotlib while this one sets its run up,
    # then lays the figures out while this one plans (ended unwritten if the input is bad)
    with early_figures(figures, sc, algorithm, seed, out / "snapshots.png", out / "run.gif") as job:
        try:
            with notice_compiles(progress):  # setting up the run compiles the kernels
                run = _prepare(sc, algorithm, seed, preset, static, threads, max_steps, sense)
        except (KeyError, ValueError, FileNotFoundError) as exc:
            raise bad_input(exc) from None
        check_output_dir(out, "--out folder")
        begin_figures(job, sc)
        res = _execute(run, sc, algorithm, seed, preset, static, threads, out, progress, job)
        record_output.write_record(res, record, console)
        if job is not None:
            from mawdo.planning.render.animation import animation_times

            frames = len(animation_times(res))
            grid, gif = draw_figures(job, frames, progress)  # (_execute sent the run)
            console.print(f"snapshot grid: {grid}")
            console.print(f"animation: {gif}")
    quick_exit.allow()  # files written, the figures' processes joined


def _execute(run, sc, algorithm, seed, preset, static, threads, out, progress, job=None):
    """Execute the run (its steps fed to the figures' process ``job`` as they are made, then
    the run itself: its figures need no metrics); print its metrics and save them in
    ``out/metrics.json``."""
    from mawdo.planning.judge.metrics import in_units, run_metrics_kept

    bar = _StepBar(progress, f"{algorithm} on {sc.name}")
    try:
        with notice_compiles(progress):
            res = run.execute(fed(run, job, bar))
    finally:
        bar.close()
    if job is not None:
        job.send((res, None, None))  # drawn while the metrics are computed and printed
    m, error = run_metrics_kept(res)
    units, given = sc.units, {}
    if not units.is_pixels:  # lengths, times and speeds in the units of the scenario's file
        given = {"units": "m", "dt_s": units.dt, "resolution_m": units.resolution}
    payload = {
        "scenario": sc.name,
        "algorithm": algorithm,
        "seed": seed,
        "preset": preset,
        "dynamic": not static,
        "threads": threads,
        **given,
        **(in_units(m, units) if m else {"metrics_error": error}),
    }
    (out / "metrics.json").write_text(json.dumps(payload, indent=1))
    for k, v in payload.items():
        console.print(f"{k:>22s}: {v:.4g}" if isinstance(v, float) else f"{k:>22s}: {v}")
    console.print(f"metrics: {out / 'metrics.json'}")
    return res


@plan_app.command("study")
def study_cmd(
    preset: str = typer.Option("paper-table6", help="paper-table6, study-quick or study-smoke"),
    out: Path = typer.Option(Path("results/table6.db"), help="SQLite results store"),
    runs: int = typer.Option(None, help="runs per algorithm (override)"),
    algorithms: str = typer.Option(None, help="comma-separated algorithms (override)"),
    scenario: str = typer.Option(None, help="scenario name or file (override)"),
    workers: int = study.WORKERS,
    dask: str = study.DASK,
    scheduler_file: Path = study.SCHEDULER_FILE,
    force: bool = study.FORCE,
    retry_failed: bool = study.RETRY_FAILED,
    report: Path = typer.Option(None, help="also write the report to this folder"),
    progress: bool = study.PROGRESS,
):
    """Run the planning study (paper Table 6) into a resumable store."""
    from mawdo.cli.args import names
    from mawdo.cli.errors import check_output_dir, fail
    from mawdo.cli.study import moved, run_study
    from mawdo.experiments import STUDY_KINDS, PlanError

    moved("mawdo plan study", "mawdo study run")
    if report is not None:
        check_output_dir(report, "--report folder")
    # errors end at the command edge: a message on stderr (2: bad plan, 1: store ...)
    try:
        plan = (
            STUDY_KINDS["planning"]
            .preset_plan(preset)
            .with_overrides(runs=runs, scenario=scenario, algorithms=names(algorithms))
        )
    except PlanError as exc:
        fail(exc)
    run_study(
        plan, out, workers=workers, dask=dask, scheduler_file=scheduler_file,
        progress=progress, force=force, retry_failed=retry_failed,
    )  # fmt: skip
    if report is not None:
        _write_report(out, report, gif=True)


def _write_report(store: Path, out: Path, gif: bool) -> None:
    from mawdo.cli.errors import REPORT_CTRL_C, check_output_dir, on_ctrl_c, writing_into
    from mawdo.experiments.kinds.planning import write_study_report

    on_ctrl_c(REPORT_CTRL_C)
    check_output_dir(out, "--out folder")
    with writing_into(out):
        path = write_study_report(store, out, gif=gif)
    console.print(f"report: {path}")


@plan_app.command("report")
def report_cmd(
    store: Path = typer.Argument(..., help="results store of a study"),
    out: Path = typer.Option(Path("report/study"), help="output folder"),
    gif: bool = typer.Option(True, help="write the animated GIF"),
):
    """Tables and figures of a planning study, read from its store (nothing is recomputed)."""
    from mawdo.cli.study import moved

    moved("mawdo plan report", "mawdo study report")
    _write_report(store, out, gif)


# ``mawdo plan bench``: the planning arena, in its own module
from mawdo.cli.plan_bench import bench_app  # noqa: E402

plan_app.add_typer(bench_app, name="bench")
