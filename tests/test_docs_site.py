"""The documentation site: it builds with warnings as errors, every example on it runs, and its
reference pages cover the code.

* Each hand-written page's ``python`` blocks and ``console`` commands run, in the page's order,
  as one script in an empty folder (a ``console`` line ``$ mawdo ...`` runs the real CLI). Pages
  whose examples plan routes or run a cluster are ``slow``.
* Every ``mawdo ...`` line of a ``bash`` or ``console`` block (README included) names a real
  command, and each of its options is one of that command's.
* The API pages list every name of ``mawdo.__all__`` and ``mawdo.planning.__all__``, the CLI page
  every command, the presets page every preset, the schema page every field.
* ``mkdocs build --strict`` succeeds, and the built API pages hold each public name's entry.
"""

from __future__ import annotations

import importlib
import importlib.util
import os
import re
import shlex
import subprocess
import sys
import textwrap
import tomllib
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
DOCS = ROOT / "docs"
FENCE = re.compile(r"^```(\w+)\n(.*?)^```", re.M | re.S)

#: The reference pages written at build time, and the reports of committed studies (their
#: examples are the code's own output, not instructions).
GENERATED = {"results"}
#: Pages whose examples take more than a few seconds: planning runs (the planner's kernels
#: compile on a cold cache), studies of planning runs, a local Dask cluster.
SLOW = {
    "planning.md",
    "observed.md",
    "tutorials/first-planning-run.md",
    "tutorials/among-people.md",
    "bbob.md",
    "tutorials/first-study.md",
    "how-to/add-a-planner.md",
    "how-to/add-a-scene-family.md",
    "how-to/dask.md",
    "how-to/load-maps.md",
}


def _hooks():
    spec = importlib.util.spec_from_file_location("docs_hooks", DOCS / "hooks.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def hand_written() -> list[Path]:
    """The site's pages that people wrote (not the committed study reports)."""
    pages = sorted(DOCS.rglob("*.md"))
    return [p for p in pages if p.relative_to(DOCS).parts[0] not in GENERATED]


def blocks(text: str) -> list[tuple[str, str]]:
    """The fenced code blocks of a Markdown text: (language, code), in order."""
    return FENCE.findall(text)


def console_commands(code: str) -> list[str]:
    """The commands of a ``console`` block: lines starting with ``$ ``."""
    return [line[2:] for line in code.splitlines() if line.startswith("$ ")]


def page_script(text: str) -> str:
    """The page's examples as one Python script: its ``python`` blocks as written, each
    ``console`` command as a call of the real CLI, in the page's order."""
    parts = [
        textwrap.dedent(
            """\
            import shlex as _shlex, subprocess as _subprocess, sys as _sys
            def _console(line):
                argv = _shlex.split(line)
                assert argv[0] == "mawdo", f"only mawdo commands run here: {line}"
                done = _subprocess.run([_sys.executable, "-m", "mawdo.cli", *argv[1:]])
                assert done.returncode == 0, f"exit {done.returncode}: {line}"
            """
        )
    ]
    for language, code in blocks(text):
        if language == "python":
            parts.append(code)
        elif language == "console":
            parts += [f"_console({c!r})" for c in console_commands(code)]
    return "\n".join(parts)


def runnable_pages() -> list:
    out = []
    for page in hand_written():
        langs = {lang for lang, code in blocks(page.read_text("utf-8"))}
        if langs & {"python", "console"}:
            rel = str(page.relative_to(DOCS))
            marks = [pytest.mark.slow] if rel in SLOW else []
            out.append(pytest.param(page, id=rel, marks=marks))
    return out


def run_script(script: str, folder: Path) -> subprocess.CompletedProcess:
    (folder / "example.py").write_text(script, encoding="utf-8")
    env = {**os.environ, "MPLBACKEND": "Agg", "COLUMNS": "200"}
    env["PYTHONPATH"] = os.pathsep.join([str(ROOT / "src"), env.get("PYTHONPATH", "")])
    return subprocess.run(
        [sys.executable, "example.py"], cwd=folder, env=env, capture_output=True, text=True
    )


@pytest.mark.parametrize("page", runnable_pages())
def test_the_page_examples_run_as_written(page, tmp_path):
    done = run_script(page_script(page.read_text("utf-8")), tmp_path)
    assert done.returncode == 0, f"{page.name}\n{done.stdout[-3000:]}\n{done.stderr[-3000:]}"


def readme_python() -> list:
    text = (ROOT / "README.md").read_text("utf-8")
    codes = [code for lang, code in blocks(text) if lang == "python"]
    return [
        pytest.param(code, id=f"block{i}", marks=[pytest.mark.slow] if "planning" in code else [])
        for i, code in enumerate(codes)
    ]


def test_the_readme_has_one_example_per_audience():
    codes = [p.values[0] for p in readme_python()]
    assert len(codes) == 2
    assert "from mawdo import minimize" in codes[0] and "from mawdo.planning" in codes[1]


@pytest.mark.parametrize("code", readme_python())
def test_each_readme_example_runs_as_pasted(code, tmp_path):
    """Each block alone, in a fresh interpreter: as a reader pastes it."""
    done = run_script(code, tmp_path)
    assert done.returncode == 0, f"{done.stdout[-2000:]}\n{done.stderr[-2000:]}"


# ------------------------------------------------------------------ command lines on the pages
def cli_lines() -> list[tuple[str, str]]:
    """Every ``mawdo ...`` command of a ``bash``/``console`` block: (file, command)."""
    out = []
    for path in [ROOT / "README.md", *hand_written()]:
        for lang, code in blocks(path.read_text("utf-8")):
            if lang not in ("bash", "console"):
                continue
            joined = re.sub(r"\\\n\s*", "", code)
            for line in joined.splitlines():
                line = re.sub(r"\s+#.*$", "", line.removeprefix("$ ")).strip()
                if line.startswith("mawdo "):
                    out.append((str(path.relative_to(ROOT)), line))
    return out


def resolve(command: str):
    """The click command a ``mawdo ...`` line runs, and the options it gives, or an error."""
    import typer.main

    from mawdo.cli.main import app

    cmd = typer.main.get_command(app)  # Typer's own copy of click: groups have ``commands``
    words = shlex.split(command.replace("[", "").replace("]", ""))[1:]
    while hasattr(cmd, "commands") and words and words[0] in cmd.commands:
        cmd = cmd.commands[words.pop(0)]
    if (
        hasattr(cmd, "commands")
        and "run" in cmd.commands
        and type(cmd).__name__.startswith("DefaultRun")
    ):  # `mawdo plan paper` is `mawdo plan run paper`
        cmd = cmd.commands["run"]
    assert not hasattr(cmd, "commands"), f"{command!r}: no such command"
    known = {o for p in cmd.params for o in (*p.opts, *p.secondary_opts)}
    given = {w.split("=")[0] for w in words if w.startswith("-")}
    return cmd, given - known


def test_every_command_on_the_pages_is_a_real_command_with_real_options():
    lines = cli_lines()
    assert len(lines) >= 25  # README, tutorials and how-to pages: the scan must see them
    wrong = [(f, c, sorted(bad)) for f, c in lines if (bad := resolve(c)[1])]
    assert not wrong, f"options that the command does not have: {wrong}"


def test_the_option_check_catches_a_misspelt_option():
    assert resolve("mawdo study run smoke --out x.db")[1] == set()
    assert resolve("mawdo study run smoke --outt x.db")[1] == {"--outt"}
    with pytest.raises(AssertionError, match="no such command"):
        resolve("mawdo study")


# ------------------------------------------------------------------ generated reference pages
@pytest.mark.parametrize("package", ["mawdo", "mawdo.planning"])
def test_the_api_page_documents_every_public_name(package):
    hooks = _hooks()
    module = importlib.import_module(package)
    paths = hooks.public_paths(package)
    assert list(paths) == list(module.__all__)
    page = hooks.api_markdown(package)
    for name, path in paths.items():
        assert f"::: {path}\n" in page, name
        home, _, attr = path.rpartition(".")
        obj = getattr(importlib.import_module(home), attr)  # the path names the real object
        if name != "__version__":
            assert obj is getattr(module, name), name
    page_file = {"mawdo": "api.md", "mawdo.planning": "api-planning.md"}[package]
    assert f"<!-- generated: api {package} -->" in (DOCS / "reference" / page_file).read_text()


def test_each_docstring_left_unchecked_still_needs_it(caplog):
    """The API page turns docstring warnings off only for the names whose docstring has prose
    in its Parameters section; once one parses cleanly, it must leave the list."""
    import griffe

    hooks = _hooks()
    paths = {**hooks.public_paths("mawdo"), **hooks.public_paths("mawdo.planning")}
    loader = griffe.GriffeLoader(search_paths=[str(ROOT / "src")])
    assert hooks.PROSE_IN_PARAMETERS <= set(paths)
    for name in sorted(hooks.PROSE_IN_PARAMETERS):
        module, _, attr = paths[name].rpartition(".")
        caplog.clear()
        with caplog.at_level("WARNING", logger="griffe"):
            loader.load(module)[attr].docstring.parse("numpy")
        assert caplog.records, f"{name}'s docstring parses now: remove it from PROSE_IN_PARAMETERS"


def test_the_cli_page_has_every_command():
    import typer.main

    from mawdo.cli.main import app

    page = _hooks().cli_markdown()

    def walk(cmd, path):
        yield path
        if hasattr(cmd, "commands"):
            for name, sub in cmd.commands.items():
                yield from walk(sub, f"{path} {name}")

    names = list(walk(typer.main.get_command(app), "mawdo"))
    assert len(names) > 15
    missing = [n for n in names if f"`{n}`" not in page]
    assert not missing, missing
    assert "--workers" in page and "--set" in page


def test_the_presets_page_has_every_preset():
    from mawdo.experiments import STUDY_KINDS

    page = _hooks().presets_markdown()
    for kind in STUDY_KINDS.values():
        for name in kind.presets:
            runs = kind.preset_plan(name).total_runs
            assert re.search(rf"^\| `{re.escape(name)}` \| .* \| {runs} \|$", page, re.M), name


def test_the_schema_page_has_every_field_and_its_example_loads():
    from mawdo.planning import ScenarioError, scenario_from_dict

    schema = sys.modules[ScenarioError.__module__].ScenarioSpec.model_json_schema()
    page = _hooks().scenario_schema_markdown()
    models = {"ScenarioSpec": schema, **schema["$defs"]}
    for name, model in models.items():
        assert f"### {name}" in page
        for field in model["properties"]:
            assert f"| `{field}` |" in page, (name, field)
    text = (DOCS / "reference" / "scenario-schema.md").read_text("utf-8")
    examples = [code for lang, code in blocks(text) if lang == "toml"]
    assert examples
    for code in examples:
        scenario = scenario_from_dict(tomllib.loads(code))
        assert scenario.name == "example" and len(scenario.obstacles) == 2


# ------------------------------------------------------------------ words and links on the pages
HISTORY = re.compile(r"\bissues? \d+|\bsessions?\b|\bitem \d+ of issue", re.I)


def test_user_docs_name_no_issue_numbers_or_sessions():
    """History belongs in CHANGELOG.md, not in the pages a user reads. A line quoted verbatim
    from a committed report is the report generator's text and is left to it."""
    quoted = {
        line.strip().removeprefix("- ")
        for report in (DOCS / "results").rglob("*.md")
        for line in report.read_text("utf-8").splitlines()
    }
    found = [
        (str(p.relative_to(ROOT)), m.group(0))
        for p in [ROOT / "README.md", *hand_written()]
        for line in p.read_text("utf-8").splitlines()
        if line.strip().removeprefix("- ") not in quoted
        for m in HISTORY.finditer(line)
    ]
    assert not found, found


# ------------------------------------------------------------------ the build itself
@pytest.mark.slow
def test_the_site_builds_strict_with_every_public_name(tmp_path):
    site = tmp_path / "site"
    env = {**os.environ, "PYTHONPATH": str(ROOT / "src"), "NO_MKDOCS_2_WARNING": "1"}
    done = subprocess.run(
        [sys.executable, "-m", "mkdocs", "build", "--strict", "-f", str(ROOT / "mkdocs.yml"),
         "-d", str(site)],
        cwd=ROOT, env=env, capture_output=True, text=True,
    )  # fmt: skip
    assert done.returncode == 0, done.stderr[-5000:]
    hooks = _hooks()
    for package, page in [("mawdo", "api"), ("mawdo.planning", "api-planning")]:
        html = (site / "reference" / page / "index.html").read_text("utf-8")
        for name, path in hooks.public_paths(package).items():
            assert f'id="{path}"' in html, f"{package}.{name} has no entry in the built page"
    cli = (site / "reference" / "cli" / "index.html").read_text("utf-8")
    assert "mawdo study run" in cli
