"""The package's import graph: one-way floors and no cycles (docs/architecture.md, issue 11).

Every ``import`` statement in ``src/mawdo/**.py`` is read with ``ast``, lazy imports inside
functions included (a lazy import is still a dependency, and the circles this test guards
against were lazy ones). A module may import its own floor or lower floors, never a higher one.
"""

from __future__ import annotations

import ast
import re
from pathlib import Path

import pytest

import mawdo

SRC = Path(mawdo.__file__).parent

# (prefix, floor): the longest matching prefix decides. Documented in docs/architecture.md.
FLOORS = (
    ("mawdo.registry", 0),
    ("mawdo.streams", 0),
    ("mawdo.problem", 0),
    ("mawdo.result", 0),
    ("mawdo.viz", 0),
    ("mawdo.util", 0),  # internal helpers' package (each module placed below)
    ("mawdo.util.validate", 0),  # argument checks: used by the core itself
    ("mawdo.util.nesting", 0),  # TOML/JSON text refused when nested too deep (plans, scenarios)
    ("mawdo.budget", 0),
    ("mawdo.jit", 0),  # the Numba compile machinery: stale caches, the table's warm-up, inlining
    ("mawdo.util.stablesort", 0),  # a stable argsort for kernels, cheap to compile
    ("mawdo.util.shuffle", 0),  # O(d) permutations: drawn by streams, inlined by kernels
    ("mawdo.util.interrupts", 0),  # Ctrl-C told apart from errors (runner and commands)
    ("mawdo.util.libm", 0),  # tan, exp, pow... by the C library: the same bits on every CPU
    ("mawdo.optimizers", 1),
    ("mawdo.functions", 1),
    ("mawdo.suites", 2),  # BBOB/CEC problems (ioh/opfunu); run_problem drives minimize
    # the driver resolves algorithm and function names in their registries, so it sits on them
    ("mawdo.minimize", 2),
    ("mawdo.util.blocks", 2),  # the driver's blocks of runs
    ("mawdo", 2),  # the package facade only (EXACT): re-exports minimize, OPTIMIZERS, FUNCTIONS
    ("mawdo.planning", 3),
    ("mawdo.experiments", 4),  # the harness: protocol, plans, rows, store, runner, stats, tables
    ("mawdo.experiments.kinds", 5),  # the kinds' package: a docstring
    ("mawdo.experiments.kinds.benchmark", 5),  # study kinds: each imports the harness only
    ("mawdo.experiments.kinds.planning", 5),
    ("mawdo.experiments.kinds.suite", 5),
    ("mawdo.experiments.kinds.arena", 5),
    ("mawdo.experiments.__init__", 6),  # registers the built-in kinds
    ("mawdo.reproduce", 7),  # runs every kind's study: above the kinds, below the commands
    ("mawdo.gym", 7),  # Gymnasium environments on the crowd kind's scenes: above the kinds too
    ("mawdo.cli", 8),
)
# prefixes that name one module, not the modules under it: a new top-level module must be
# given its floor explicitly (the facade's name is a prefix of every module's)
EXACT = {"mawdo"}
# the modules at the package root: public API only (internal helpers live in mawdo.util)
PUBLIC_ROOT = {
    "__init__", "__main__", "budget", "minimize", "problem", "registry", "reproduce", "result",
    "streams", "viz",
}  # fmt: skip
NAMES = {
    0: "core",
    1: "optimizers/functions",
    2: "driver",
    3: "planning",
    4: "experiments harness",
    5: "study kinds",
    6: "experiments facade",
    7: "reproduce",
    8: "commands",
}
KIND_PACKAGES = (
    "mawdo.experiments.kinds.benchmark",
    "mawdo.experiments.kinds.planning",
    "mawdo.experiments.kinds.suite",
    "mawdo.experiments.kinds.arena",
)


def module_name(path: Path) -> str:
    rel = path.relative_to(SRC.parent).with_suffix("")
    parts = list(rel.parts)
    if parts[-1] == "__init__" and len(parts) > 2 and parts[-2] != "experiments":
        parts = parts[:-1]
    elif parts == ["mawdo", "__init__"]:
        parts = ["mawdo"]
    return ".".join(parts)


def floor_of(module: str) -> int:
    best, floor = -1, None
    for prefix, f in FLOORS:
        covers = module == prefix or (prefix not in EXACT and module.startswith(prefix + "."))
        if covers and len(prefix) > best:
            best, floor = len(prefix), f
    if floor is None:
        raise AssertionError(f"{module} has no floor: add it to FLOORS and docs/architecture.md")
    return floor


def all_modules() -> dict[str, Path]:
    return {module_name(p): p for p in sorted(SRC.rglob("*.py"))}


def resolve(target: str, modules: dict[str, Path]) -> str | None:
    """The module an imported name lives in (``mawdo.x.y`` may be a module or a name in x)."""
    while target and target not in modules:
        if target == "mawdo.experiments":
            return "mawdo.experiments.__init__"
        target = target.rpartition(".")[0]
    return target or None


def imports_of(name: str, path: Path, modules: dict[str, Path]) -> set[str]:
    tree = ast.parse(path.read_text(encoding="utf-8"))
    package = name.rpartition(".")[0] if not path.name == "__init__.py" else name
    package = package.removesuffix(".__init__")
    out = set()
    for node in ast.walk(tree):
        targets = []
        if isinstance(node, ast.Import):
            targets = [a.name for a in node.names]
        elif isinstance(node, ast.ImportFrom):
            base = node.module or ""
            if node.level:
                up = package.split(".")
                up = up[: len(up) - (node.level - 1)]
                base = ".".join(up + ([base] if base else []))
            targets = [f"{base}.{a.name}" for a in node.names]
        for t in targets:
            if t == "mawdo" or t.startswith("mawdo."):
                mod = resolve(t, modules)
                if mod is not None and mod != name:
                    out.add(mod)
    return out


@pytest.fixture(scope="module")
def graph() -> dict[str, set[str]]:
    modules = all_modules()
    return {name: imports_of(name, path, modules) for name, path in modules.items()}


def test_the_package_root_holds_only_public_modules_and_packages():
    root = {p.stem for p in SRC.glob("*.py")}
    assert root <= PUBLIC_ROOT, (
        f"internal modules at the package root: {sorted(root - PUBLIC_ROOT)}"
    )
    planning = {p.stem for p in (SRC / "planning").glob("*.py")}
    assert len(planning) <= 8, f"planning's root holds {len(planning)} modules: {sorted(planning)}"


def test_every_module_has_a_floor(graph):
    for name in graph:
        floor_of(name)


def test_no_import_from_a_higher_floor(graph):
    upward = [
        f"{a} ({NAMES[floor_of(a)]}) imports {b} ({NAMES[floor_of(b)]})"
        for a, deps in graph.items()
        for b in deps
        if floor_of(b) > floor_of(a)
    ]
    assert not upward, "upward imports:\n" + "\n".join(sorted(upward))


def test_study_kinds_do_not_import_each_other(graph):
    def kind(m):
        return next((k for k in KIND_PACKAGES if m == k or m.startswith(k + ".")), None)

    crossing = [
        f"{a} imports {b}"
        for a, deps in graph.items()
        for b in deps
        if kind(a) and kind(b) and kind(a) != kind(b)
    ]
    assert not crossing


def test_no_import_cycle(graph):
    cycle = find_cycle(graph)
    assert cycle is None, "import cycle: " + " -> ".join(cycle)


def find_cycle(graph: dict[str, set[str]]) -> list[str] | None:
    """A cycle of ``graph`` as a path ``a -> ... -> a``, or None (iterative DFS)."""
    colour: dict[str, int] = {}
    for root in sorted(graph):
        if colour.get(root):
            continue
        stack = [(root, iter(sorted(graph.get(root, ()))))]
        path = [root]
        colour[root] = 1
        while stack:
            node, it = stack[-1]
            nxt = next(it, None)
            if nxt is None:
                colour[node] = 2
                stack.pop()
                path.pop()
            elif colour.get(nxt) == 1:
                return path[path.index(nxt) :] + [nxt]
            elif not colour.get(nxt):
                colour[nxt] = 1
                path.append(nxt)
                stack.append((nxt, iter(sorted(graph.get(nxt, ())))))
    return None


def test_the_checks_catch_what_they_claim():
    # the cycle finder and the floor map on hand-made graphs, so a green run means something
    assert find_cycle({"a": {"b"}, "b": {"c"}, "c": {"a"}}) == ["a", "b", "c", "a"]
    assert find_cycle({"a": {"b"}, "b": {"c"}, "c": set()}) is None
    assert floor_of("mawdo.cli.bench") > floor_of("mawdo.experiments.store")
    runner = floor_of("mawdo.experiments.runner")
    assert floor_of("mawdo.experiments.kinds.benchmark.report") > runner
    assert floor_of("mawdo.planning.refine.kernel") < floor_of("mawdo.experiments.runner")
    assert floor_of("mawdo.optimizers.wdo") < floor_of("mawdo.planning.run.planner")
    assert floor_of("mawdo.registry") < floor_of("mawdo.optimizers.wdo")
    with pytest.raises(AssertionError, match="has no floor"):
        floor_of("mawdo.newcomer")  # a module nobody placed fails, not the facade's floor
    assert floor_of("mawdo.experiments.__init__") > floor_of("mawdo.experiments.kinds.planning")


def test_the_module_map_names_every_package_and_the_recipes_name_real_files():
    # docs/architecture.md is drawn from the code: every package appears in its tree, and every
    # file or folder a recipe sends a contributor to exists
    doc = (SRC.parents[1] / "docs" / "architecture.md").read_text(encoding="utf-8")
    tree = doc.split("```")[1]
    packages = sorted(p.parent for p in SRC.rglob("__init__.py") if p.parent != SRC)
    missing = [str(p.relative_to(SRC)) for p in packages if f" {p.name}/" not in tree]
    assert not missing, f"packages missing from the module map: {missing}"
    recipes = doc.split("## Recipes")[1].split("\n## ")[0]
    named = set(
        re.findall(r"`((?:optimizers|planning|suites|experiments|tests)/[\w/.*]+)`", recipes)
    )
    assert len(named) >= 8
    root = SRC.parents[1]
    for rel in named:
        base = root / "src" / "mawdo" if not rel.startswith("tests/") else root
        assert list(base.glob(rel.rstrip("/"))), f"architecture.md recipe names {rel}: no such path"


def test_no_private_name_is_imported_from_another_module():
    # issue 26: what crosses a module boundary is public; a leading underscore means "mine"
    leaks = []
    for path in sorted(SRC.rglob("*.py")):
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            if isinstance(node, ast.ImportFrom) and (node.level or node.module.startswith("mawdo")):
                leaks += [
                    f"{path.relative_to(SRC)}:{node.lineno} imports {a.name}"
                    for a in node.names
                    if a.name.startswith("_") and not a.name.startswith("__")
                ]
    assert not leaks, "\n".join(leaks)
