"""``mawdo bench`` for standard suites: the plan of ``run --suite bbob|cec2017|cec2022``,
``export``, and the report of a suite-study store.

Mounted by :mod:`mawdo.cli.bench`: ``run`` hands over here when ``--suite`` or a ``bbob-*``
preset is given, ``report`` when the store holds a suite study. Every decision lives in
:mod:`mawdo.experiments.kinds.suite`.
"""

from __future__ import annotations

from pathlib import Path

import typer

from mawdo.cli.errors import exit_code_of, fail


def is_suite_preset(name: str | None) -> bool:
    """Whether ``name`` is a preset of the suite study (``bbob-quick``, ``bbob-full``)."""
    from mawdo.experiments.kinds.suite import PRESETS

    return name is not None and (name in PRESETS or name.startswith("bbob"))


def is_suite_plan_file(path: Path | None) -> bool:
    """Whether the plan file at ``path`` holds a suite plan (``kind = "suite"``, or its former
    name ``"bbob"``, a ``suite`` field or a ``bbob-*`` preset); False for anything else, which
    the benchmark's reader then reads (and reports, if it cannot)."""
    from mawdo.experiments import PlanError
    from mawdo.experiments.plans import read_plan_file

    if path is None:
        return False
    try:
        data = read_plan_file(path)
    except PlanError:
        return False
    from mawdo.experiments.kinds.suite import KIND, OLD_KIND_NAMES

    kind = data.get("kind")
    return kind in (KIND, *OLD_KIND_NAMES) or "suite" in data or is_suite_preset(data.get("preset"))


def is_suite_store(path: Path) -> bool:
    """Whether the store at ``path`` holds a suite study (False if it is not a store at all:
    the caller's own reading then reports what is wrong)."""
    from mawdo.experiments import Store, StoreError
    from mawdo.experiments.kinds.suite import KIND

    try:
        with Store.read(path) as store:
            return store.plan.kind == KIND
    except StoreError:
        return False


def _ids(text: str | None, what: str) -> list | None:
    from mawdo.experiments.kinds.suite import parse_ids

    return None if text is None else parse_ids(text, what)


def _budget(text: str | None) -> float | None:
    if text is None:
        return None
    try:
        return float(text)
    except ValueError:
        raise ValueError(
            f"--budget {text!r}: with --suite it is evaluations per dimension, a number > 0 "
            f"(e.g. 1e4 for 10^4 x D evaluations per run)"
        ) from None


def suite_plan(
    preset, suite, algorithms, functions, instances, dims, budget, *, plan_file=None,
    variants=(), options=(), **overrides,
):  # fmt: skip
    """The plan of ``mawdo bench run`` for a suite study, from a preset, a plan file or flags;
    ``--variant``/``--option`` texts add named variants and options (checked with the plan,
    before anything runs).

    Raises
    ------
    PlanError
        An invalid field (unknown suite, function id, dimension, budget <= 0, option ...).
    ValueError
        A malformed ``--variant``/``--option`` or missing flags.
    """
    from mawdo.experiments.kinds.suite import SuitePlan, preset_plan
    from mawdo.experiments.kinds.suite.variants import cli_fields

    fields = {
        "suite": suite,
        "algorithms": algorithms,
        "functions": _ids(functions, "--functions"),
        "instances": _ids(instances, "--instances"),
        "dims": _ids(dims, "--dims"),
        "budget": _budget(budget),
        **overrides,
    }
    base = None
    if preset is not None:
        base = preset_plan(preset)
    elif plan_file is not None:
        base = SuitePlan.from_file(plan_file)
    elif algorithms is None or functions is None:
        raise ValueError("with --suite give --algorithms a,b and --functions (e.g. 1-24)")
    if variants or options:
        start = base.model_dump() if base is not None else {}
        fields |= cli_fields(algorithms or list(start["algorithms"]), variants, options, start)
    if base is not None:
        return base.with_overrides(**fields)
    given = {k: v for k, v in fields.items() if v is not None}
    return SuitePlan.from_dict({"name": "cli", **given})


def report_suite(
    stores: list[Path], out: Path, plots: bool, svg: bool, reference: str | None = None
) -> None:
    """Write the suite study's report from ``stores`` (one study, merged) into ``out``."""
    from mawdo.experiments import StoreError
    from mawdo.experiments.kinds.suite import write_suite_report

    try:
        report = write_suite_report(stores, out, plots=plots, svg=svg, reference=reference)
    except (StoreError, ValueError) as exc:
        fail(exc, exit_code_of(exc) or 1)
    typer.echo(f"wrote the suite report to {out}/ (start with {report})")


def export_cmd(
    store: Path = typer.Argument(..., help="Results store of a suite study (`run --suite`)."),
    folder: Path = typer.Argument(..., help="Output folder (one sub-folder per algorithm)."),
    fmt: str = typer.Option(
        "ioh", "--format", help="ioh (IOHanalyzer logs) or cec (the CEC competitions' files)."
    ),
) -> None:
    """Export a suite study's runs: IOHanalyzer logs (zip a folder and upload it), or for a CEC
    study the competition's result files (``<algorithm>_<F>_<D>.txt``)."""
    from mawdo.cli.errors import check_output_dir, on_ctrl_c
    from mawdo.experiments.kinds.suite import EXPORT_FORMATS

    on_ctrl_c("the export was not finished (its folder may hold some of the files)")
    if fmt.lower() not in EXPORT_FORMATS:
        names = ", ".join(f"'{k}' ({what})" for k, (_, what) in EXPORT_FORMATS.items())
        raise ValueError(f"--format {fmt!r} is not an export format; choose {names}")
    export, what = EXPORT_FORMATS[fmt.lower()]
    check_output_dir(folder, "export folder")
    files = export(store, folder)
    typer.echo(f"wrote {what}: {len(files)} files to {folder}/")
