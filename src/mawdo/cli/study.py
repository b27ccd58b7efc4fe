"""``mawdo study``: run any registered study kind's plan into a store, report from a store,
list every kind's presets.

One path for every kind, read from :data:`mawdo.experiments.STUDY_KINDS`: a preset name finds
its kind (preset names are unique across kinds), a plan file names its kind, a store's meta row
names the kind whose report reads it. A kind registered by a plug-in (or a test) is served
without a change here. The older per-kind commands (``mawdo bench run``, ``mawdo plan study``,
``mawdo plan bench`` ...) build their plan from their own flags and end in :func:`run_study`.
"""

from __future__ import annotations

import inspect
import typing
from pathlib import Path
from typing import Any

import typer

from mawdo.cli.args import pairs, value
from mawdo.cli.errors import (
    REPORT_CTRL_C,
    RETRY_HELP,
    SCHEDULER_FILE_HELP,
    STUDY_CTRL_C,
    GuardedGroup,
    check_output_dir,
    exit_code_of,
    fail,
    on_ctrl_c,
    writing_into,
)

study_app = typer.Typer(
    cls=GuardedGroup,  # its errors are plain lines also when it runs on its own (tests)
    name="study",
    help="Studies of every kind: run a preset or a plan file into a resumable store, report it.",
    no_args_is_help=True,
    add_completion=False,
)

# the flags every study-running command shares (one declaration, reused by the aliases)
WORKERS = typer.Option(1, "--workers", "-w", min=1, help="local worker processes")
DASK = typer.Option(None, "--dask", help="Dask scheduler address, e.g. tcp://host:8786")
SCHEDULER_FILE = typer.Option(None, "--scheduler-file", help=SCHEDULER_FILE_HELP)
FORCE = typer.Option(False, "--force", help="discard a store made by another plan or version")
RETRY_FAILED = typer.Option(False, "--retry-failed", help=RETRY_HELP)
PROGRESS = typer.Option(True, "--progress/--no-progress", help="show a progress bar (stderr)")
REUSE_HELP = "another store whose identical runs are copied, not computed (repeatable)"
REUSE = typer.Option(None, "--reuse", help=REUSE_HELP)

ALIAS_RELEASE = "1.0"  # was 0.9; kept one more minor release (0.9.0 still has them)
"""The release that drops the older per-kind study commands."""


def moved(old: str, new: str) -> None:
    """The one line an older command prints (stderr) before it does what it always did."""
    typer.echo(f"note: '{old}' is now '{new}'; this alias goes in {ALIAS_RELEASE}", err=True)


def set_values(plan: Any, items: list[str] | None) -> dict[str, Any]:
    """``--set key=value`` items as plan overrides.

    A value is read as JSON when it parses (``runs=3``, ``options={"mawdo": {"groups": 4}}``,
    ``final_target=null``), else as text; for a field that holds a list, ``a,b`` is the list
    ``["a", "b"]`` (each item read as JSON when it parses: ``dims=5,20`` is ``[5, 20]``).
    ``null`` is kept (None where the field allows it, else refused with the field's type), and
    ``true``/``false`` stay bools (refused for a field of numbers or names).
    """
    out = pairs(items, "--set", "runs=3")
    for key, val in out.items():
        listed = isinstance(getattr(plan, key, None), tuple | list)
        if listed and isinstance(val, str | int) and not isinstance(val, bool):
            text = str(val)
            out[key] = [value(t.strip(), f"--set {key}") for t in text.split(",") if t.strip()]
    return out


def load_plan(spec: str, sets: list[str] | None = None) -> Any:
    """The plan of a preset name or a plan file (TOML, or JSON by its suffix), with ``--set``
    overrides applied through the plan's ``with_overrides``; a bad name, file or field ends the
    command with exit code 2."""
    from mawdo.experiments import PlanError
    from mawdo.experiments.protocol import find_preset, load_plan_file

    path = Path(spec)
    try:
        if path.exists() or _names_a_file(spec):
            plan = load_plan_file(_plan_file(path))
        else:
            plan = find_preset(spec)
        return plan.with_fields(**set_values(plan, sets))
    except (PlanError, ValueError) as exc:
        fail(exc)


def _names_a_file(spec: str) -> bool:
    """Whether ``spec`` is written as a file (a suffix or a folder), not a preset name (preset
    names have neither)."""
    return bool(Path(spec).suffix) or "/" in spec or "\\" in spec


def _plan_file(path: Path) -> Path:
    """``path`` if it is a plan file that exists, with a ``.toml`` or ``.json`` suffix (the
    formats read); else a ``ValueError`` saying which of those is wrong."""
    if not path.exists():
        raise ValueError(
            f"plan file {path} does not exist (a plan is a preset name, see `mawdo study "
            "presets`, or a .toml or .json file)"
        )
    if path.is_dir():
        raise ValueError(f"plan {path} is a folder; give a .toml or .json plan file")
    if path.suffix.lower() not in (".toml", ".json"):
        raise ValueError(
            f"plan file {path}: plan files are TOML (.toml) or JSON (.json), not "
            f"{path.suffix or 'a file without a suffix'}"
        )
    return path


def run_study(plan: Any, out: Path, **backend: Any) -> None:
    """Run (or resume) ``plan`` into the store ``out``: one line on stderr saying what runs,
    the summary on stdout; exit 130 after Ctrl-C, 1 when a task was lost.

    ``backend``: ``workers``, ``dask``, ``scheduler_file``, ``progress``, ``force`` and
    ``retry_failed`` (and ``reuse``) of :func:`mawdo.experiments.run_plan`.
    """
    from mawdo.experiments import StoreError, run_plan

    on_ctrl_c(STUDY_CTRL_C)
    check = getattr(plan, "check_libraries", None)  # optional: a kind's missing extra
    try:
        if check is not None:
            check()
    except ImportError as exc:
        fail(exc, code=1)
    except ValueError as exc:  # a data file the plan needs is missing or damaged: input
        fail(exc, code=2)
    # what it will do, before any work: the plan and its size (at most MAX_PLAN_RUNS runs)
    total = getattr(plan, "total_runs", None)
    size = f"; {total:,} runs in all" if isinstance(total, int) else ""
    typer.echo(f"{plan.describe()}{size}; plan {plan.plan_hash[:12]} -> {out}", err=True)
    try:
        summary = run_plan(plan, out, **backend)
    except (StoreError, ValueError, RuntimeError) as exc:
        fail(exc, code=exit_code_of(exc) or 1)  # a store or plan given: 2; the work failed: 1
    typer.echo(str(summary))
    if summary.interrupted:
        raise typer.Exit(130)
    if summary.lost:
        raise typer.Exit(1)


@study_app.command("run")
def run_cmd(
    plan: str = typer.Argument(..., help="a preset (`mawdo study presets`) or a plan file"),
    sets: list[str] = typer.Option(
        None, "--set", help="plan field override, repeatable: --set runs=3 --set algorithms=a,b"
    ),
    out: Path = typer.Option(..., "--out", "-o", help="results store (SQLite)"),
    workers: int = WORKERS,
    dask: str = DASK,
    scheduler_file: Path = SCHEDULER_FILE,
    force: bool = FORCE,
    retry_failed: bool = RETRY_FAILED,
    progress: bool = PROGRESS,
    reuse: list[Path] = REUSE,
) -> None:
    """Run (or resume) a study: stored runs are skipped, Ctrl-C keeps what finished."""
    study = load_plan(plan, sets)
    run_study(
        study, out, workers=workers, dask=dask, scheduler_file=scheduler_file,
        progress=progress, force=force, retry_failed=retry_failed, reuse=reuse or (),
    )  # fmt: skip


def store_kind(store: Path) -> Any:
    """The registered kind of the study in ``store`` (its meta row names it)."""
    from mawdo.experiments import Store
    from mawdo.experiments.protocol import kind_of

    with Store.read(store) as s:
        return kind_of(s.plan)


def report_options(kind: Any, items: list[str] | None) -> dict[str, Any]:
    """``--option key=value`` items checked against the keyword options of ``kind.report``:
    each name, and each value against the option's type (``plots=banana`` is no bool)."""
    try:
        options = pairs(items, "--option", "plots=false")
    except ValueError as exc:
        fail(exc)
    params = list(inspect.signature(kind.report).parameters.values())[2:]
    known = {p.name: p for p in params if p.kind in (p.KEYWORD_ONLY, p.POSITIONAL_OR_KEYWORD)}
    try:
        hints = typing.get_type_hints(kind.report)
    except (NameError, TypeError):  # an annotation that cannot be resolved: the defaults say
        hints = {}
    for key, val in options.items():
        if key not in known:
            fail(f"--option {key}: the {kind.name} report has no such option; its options: "
                 f"{', '.join(known) or 'none'}")  # fmt: skip
        problem = option_problem(val, hints.get(key), known[key].default)
        if problem:
            fail(f"--option {key}={val!r}: {problem}")
    return options


def option_problem(val: Any, hint: Any, default: Any) -> str:
    """Why ``val`` does not fit a report option of type ``hint`` (its default ``default`` when
    the type is unknown); "" when it fits."""
    if hint is None and default is not inspect.Parameter.empty and default is not None:
        hint = type(default)
    if hint is None or hint is Any:
        return ""
    allowed = set(typing.get_args(hint)) or {hint}
    if val is None:
        return "" if type(None) in allowed else "this option cannot be null"
    if isinstance(val, bool):
        return "" if bool in allowed else f"must be {_option_type(allowed)}, not true/false"
    if any(isinstance(val, t) for t in allowed if isinstance(t, type) and t is not bool):
        return ""
    if float in allowed and isinstance(val, int):
        return ""
    return f"must be {_option_type(allowed)}"


def _option_type(allowed: set) -> str:
    words = {bool: "true or false", int: "an integer", float: "a number", str: "a name"}
    said = [words.get(t, getattr(t, "__name__", str(t))) for t in allowed if t is not type(None)]
    return " or ".join(said) + (" or null" if type(None) in allowed else "")


def report_path(result: Any, out: Path) -> Path:
    """The report's main file: what the kind's report returned, or ``report.md`` among the
    files it wrote."""
    if isinstance(result, str | Path):
        return Path(result)
    files = [Path(f) for f in result or ()]
    return next((f for f in files if f.name == "report.md"), files[0] if files else out)


@study_app.command("report")
def report_cmd(
    stores: list[Path] = typer.Argument(
        ..., help="results store; several stores of one study when its kind merges them"
    ),
    out: Path = typer.Option(Path("report"), "--out", "-o", help="output folder"),
    option: list[str] = typer.Option(
        None, "--option", help="report option, repeatable: --option plots=false"
    ),
) -> None:
    """Write the report of the study in STORE (tables, figures), without recomputing."""
    on_ctrl_c(REPORT_CTRL_C)
    check_output_dir(out, "--out folder")
    missing = [str(s) for s in stores if not s.exists()]
    if missing:
        fail(f"no such results store: {', '.join(missing)}")
    kinds = [store_kind(s) for s in stores]
    kind = kinds[0]
    if kind.report is None:
        fail(f"the {kind.name} study kind has no report")
    if len(stores) > 1 and not (
        kind.report_merges_stores and {k.name for k in kinds} == {kind.name}
    ):
        fail(
            f"several stores are reported together only for one study of a kind that merges "
            f"them; these hold {', '.join(sorted({k.name for k in kinds}))}: report each store "
            f"on its own"
        )
    options = report_options(kind, option)
    target = list(stores) if kind.report_merges_stores else stores[0]
    from mawdo.cli.progress import step

    # tens of seconds of tables and figures: a line on stderr says what is going on
    with writing_into(out), step(f"writing the report of the {kind.name} study"):
        result = kind.report(target, out, **options)
    typer.echo(f"report: {report_path(result, out)}")


@study_app.command("presets")
def presets_cmd() -> None:
    """List every study kind's presets (name, what it runs, its number of runs)."""
    from mawdo.experiments import STUDY_KINDS

    for kind in STUDY_KINDS.values():
        if not kind.presets:
            continue
        typer.echo(f"{kind.name}: {kind.description}")
        for name in kind.presets:
            runs = kind.preset_plan(name).total_runs
            typer.echo(f"  {name:22s} {kind.preset_line(name)} ({runs} runs)")
