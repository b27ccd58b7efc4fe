"""MkDocs hooks: the reference pages generated from the code at build time.

A page asks for a generated part with a marker comment on a line of its own:

* ``<!-- generated: cli -->`` - every ``mawdo`` command, from the Typer app;
* ``<!-- generated: scenario-schema -->`` - the scenario file's fields, from its pydantic model;
* ``<!-- generated: presets -->`` - every study kind's presets, from the study registry;
* ``<!-- generated: api mawdo -->`` (or ``api mawdo.planning``) - one mkdocstrings entry per
  name of the package's ``__all__``.

The functions are plain (no MkDocs import), so ``tests/test_docs_site.py`` calls them too.
"""

from __future__ import annotations

import importlib
import json
import re
import sys
from pathlib import Path

MARKER = re.compile(r"^<!-- generated: ([\w-]+)(?: ([\w.]+))? -->$", re.M)
SRC = Path(__file__).resolve().parents[1] / "src"


def _importable() -> None:
    """Build from a checkout: the package's own sources, whatever is installed."""
    if str(SRC) not in sys.path:
        sys.path.insert(0, str(SRC))


def cli_markdown() -> str:
    """Every command of the ``mawdo`` program, its arguments and options, from the Typer app."""
    _importable()
    import typer.main
    from typer.cli import get_docs_for_click

    from mawdo.cli.main import app

    command = typer.main.get_command(app)
    ctx = command.context_class(command)  # Typer's own click
    docs = get_docs_for_click(obj=command, ctx=ctx, name="mawdo")
    # Typer writes each command as a level-1 heading: one level down under the page's title
    docs = re.sub(r"^(#+) ", r"#\1 ", docs, flags=re.M)
    return docs.strip() + "\n"


def _type_of(field: dict) -> str:
    if "$ref" in field:
        name = field["$ref"].rsplit("/", 1)[1]
        return f"[{name}](#{name.lower()})"
    for key in ("oneOf", "anyOf"):
        if key in field:
            kinds = [_type_of(f) for f in field[key]]
            return " or ".join(k for k in kinds if k != "null") or "null"
    if "const" in field:
        return f'`"{field["const"]}"`'
    if "enum" in field:
        return " or ".join(f'`"{v}"`' for v in field["enum"])
    kind = field.get("type", "any")
    if kind == "array":
        if "prefixItems" in field:
            return "[" + ", ".join(_type_of(f) for f in field["prefixItems"]) + "]"
        return f"list of {_type_of(field.get('items', {}))}"
    return kind


_BOUNDS = {
    "minimum": ">=",
    "exclusiveMinimum": ">",
    "maximum": "<=",
    "exclusiveMaximum": "<",
    "minItems": "items >=",
    "maxItems": "items <=",
}


def _limits(field: dict) -> str:
    said = [f"{word} {field[key]:g}" for key, word in _BOUNDS.items() if key in field]
    if "prefixItems" in field and "minimum" in field["prefixItems"][0]:
        said.append(f"each in [{field['prefixItems'][0]['minimum']:g}, "
                    f"{field['prefixItems'][0]['maximum']:g}]")  # fmt: skip
    return ", ".join(s for s in said if not s.startswith("items")) or ""


def _model_table(name: str, model: dict) -> list[str]:
    lines = [f"### {name}", ""]
    if model.get("description"):
        lines += [" ".join(model["description"].split()), ""]
    required = set(model.get("required", ()))
    lines += ["| field | type | required | default | limits |", "|---|---|---|---|---|"]
    for key, field in model.get("properties", {}).items():
        default = "" if "default" not in field else f"`{json.dumps(field['default'])}`"
        lines.append(
            f"| `{key}` | {_type_of(field)} | {'yes' if key in required else 'no'} | "
            f"{default} | {_limits(field)} |"
        )
    return lines + [""]


def scenario_schema_markdown() -> str:
    """The scenario file's fields, one table per model, and the JSON schema itself, from
    ``ScenarioSpec.model_json_schema()`` (the pydantic model that validates every file)."""
    _importable()
    from mawdo.planning import ScenarioError

    schema_module = sys.modules[ScenarioError.__module__]
    schema = schema_module.ScenarioSpec.model_json_schema()
    lines = [
        f"Schema version {schema_module.SCHEMA_VERSION}. Unknown keys are errors; units are "
        'pixels, time steps and pixels per time step, or with `units = "m"` metres, seconds '
        "and metres per second.",
        "",
    ]
    lines += _model_table("ScenarioSpec", schema)
    for name, model in sorted(schema.get("$defs", {}).items()):
        lines += _model_table(name, model)
    lines += ["### The JSON schema", "", "```json", json.dumps(schema, indent=2), "```", ""]
    return "\n".join(lines)


def presets_markdown() -> str:
    """Every study kind's presets: name, what it runs, its number of runs (as
    ``mawdo study presets`` lists them)."""
    _importable()
    from mawdo.experiments import STUDY_KINDS

    lines = []
    for kind in STUDY_KINDS.values():
        if not kind.presets:
            continue
        lines += [f"## `{kind.name}`", "", " ".join(kind.description.split()), ""]
        lines += ["| preset | what it runs | runs |", "|---|---|---|"]
        for name in kind.presets:
            line = kind.preset_line(name).replace("|", "\\|")
            lines.append(f"| `{name}` | {line} | {kind.preset_plan(name).total_runs} |")
        lines.append("")
    return "\n".join(lines)


def public_paths(package: str) -> dict[str, str]:
    """Each name of ``package.__all__`` -> the dotted path where it is defined (the module its
    lazy import loads, or the package itself)."""
    _importable()
    module = importlib.import_module(package)
    lazy = getattr(module, "_LAZY", {})
    out = {}
    for name in module.__all__:
        home = lazy.get(name)
        if home is None:
            obj = getattr(module, name)
            home = getattr(obj, "__module__", package) if callable(obj) else package
        elif not home.startswith("mawdo"):
            home = f"{package}.{home}"
        out[name] = f"{home}.{name}"
    return out


#: Public names whose numpydoc docstring has prose inside its Parameters section, which the
#: parser reads as a parameter (a warning, so an error in the strict build): their docstring
#: warnings are off until the prose moves to a Notes section. Remove a name once it parses.
PROSE_IN_PARAMETERS: set[str] = set()


def api_markdown(package: str) -> str:
    """One mkdocstrings entry per public name of ``package``, in ``__all__``'s order."""
    quiet = "    options:\n      docstring_options:\n        warnings: false\n"
    return "\n".join(
        f"::: {path}\n" + (quiet if name in PROSE_IN_PARAMETERS else "")
        for name, path in public_paths(package).items()
    )


GENERATORS = {
    "cli": lambda _: cli_markdown(),
    "scenario-schema": lambda _: scenario_schema_markdown(),
    "presets": lambda _: presets_markdown(),
    "api": api_markdown,
}


def expand(markdown: str) -> str:
    """``markdown`` with every generated-part marker replaced by its part."""
    return MARKER.sub(lambda m: GENERATORS[m.group(1)](m.group(2)), markdown)


FOLDER_LINK = re.compile(r"\]\(((?![a-z]+:)[^)#\s]+/)\)")


def folder_links(markdown: str, page_dir: Path) -> str:
    """Links to a folder that holds a README.md point at that README, as GitHub shows it."""

    def to_readme(m: re.Match) -> str:
        readme = page_dir / m.group(1) / "README.md"
        return f"]({m.group(1)}README.md)" if readme.is_file() else m.group(0)

    return FOLDER_LINK.sub(to_readme, markdown)


def on_page_markdown(markdown, page, config, files):  # noqa: ARG001 (MkDocs' hook signature)
    page_dir = (Path(config["docs_dir"]) / page.file.src_path).parent
    return folder_links(expand(markdown), page_dir)
