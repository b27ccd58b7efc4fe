"""What the committed component study shows, in sentences made from its stores.

``findings.md`` (in ``docs/results/wdo-components``) and the component-study section of
``docs/algorithms.md`` are this module's output, and tests/test_component_results.py checks
both against the committed stores and recomputes their numbers from the raw rows. Run as a
module to rewrite ``findings.md`` and the figures and to print the docs section::

    python -m mawdo.experiments.kinds.suite.components_summary \\
        d5pairs.db d5refs.db d20.db d20refs.db --out docs/results/wdo-components

The measure everywhere is the normalised area under a run's runtime ECDF (:mod:`.effects`), in
percent, averaged over a group's functions; a switch's effect is its variant's area minus its
base's, with the bootstrap 95 % interval of :class:`.effects.EffectData`.
"""

from __future__ import annotations

import argparse
import sys
from collections.abc import Sequence
from dataclasses import replace
from pathlib import Path

import numpy as np

from mawdo.experiments.kinds.suite.components import BASE_SWITCHES, PAIR_BASE, parse_label
from mawdo.experiments.kinds.suite.components_text import (
    GROUP_SHORT,
    command,
    docs_section,
    name,
    protocol_line,
)
from mawdo.experiments.kinds.suite.data import StudyRuns, load_runs
from mawdo.experiments.kinds.suite.effects import EffectData, centre_pull
from mawdo.experiments.kinds.suite.measures import groups

BASES = ("wdo", "awdo", "mawdo")
REFERENCES = ("cmaes", "gwo", "random")
ZOOM = 0.4
"""Top of the y axis of the zoomed ECDF figures."""
GRAVITY_FIX = "grav_best"
"""The switch the study singles out: gravity toward the best-so-far instead of the box centre."""


class DimFacts:
    """The measures of one dimension's stores that the sentences quote.

    Parameters
    ----------
    study : StudyRuns
        The dimension's stores merged (variants and references).
    dim : int
        Dimension D.
    """

    def __init__(self, study: StudyRuns, dim: int):
        self.study, self.dim = study, dim
        self.groups = groups(study)
        self.singles = {b: [f"{b}-{s}" for s in BASE_SWITCHES[b]] for b in BASES}
        fix = f"{PAIR_BASE}-{GRAVITY_FIX}"
        self.on_fix = [a for a in study.algorithms if a.startswith(f"{fix}+")]
        wanted = [*BASES, *REFERENCES, *(v for b in BASES for v in self.singles[b])]
        missing = [a for a in wanted if a not in study.algorithms]
        if missing:
            raise ValueError(
                f"D = {dim}: the stores lack {', '.join(missing[:4])}"
                f"{f' and {len(missing) - 4} more' if len(missing) > 4 else ''}; name every "
                "store of the component study (variants and references) together"
            )
        self.variants = [a for a in study.algorithms if a not in (*BASES, *REFERENCES)]
        self.data = EffectData(study, dim, [*BASES, *REFERENCES, *self.variants], PAIR_BASE)

    def area(self, algo: str, group: str = "all functions") -> float:
        """Mean ECDF area of ``algo`` over ``group``'s functions, percent."""
        return 100 * float(np.mean([self.data.area[algo, f].mean() for f in self.groups[group]]))

    def effect(self, variant: str, base: str, group: str = "all functions"):
        """``(mean, lo, hi)`` area difference in percentage points over ``group``."""
        return self.data.area_effect(variant, base, self.groups[group])

    def best_switch(self, base: str) -> str:
        """The single switch of ``base`` with the largest effect over all functions."""
        return max(self.singles[base], key=lambda v: self.effect(v, base)[0])

    def family(self) -> list[str]:
        """Every WDO-family algorithm of the stores: the bases and every component variant."""
        return [*BASES, *self.variants]

    def gap(self, group: str) -> float:
        """CMA-ES's area minus the best WDO-family algorithm's over ``group``, points."""
        return self.area("cmaes", group) - max(self.area(a, group) for a in self.family())

    def pull(self, algo: str) -> float:
        """Median ``best_x . x* / |x*|^2`` over every run of ``algo`` (1: at x*, 0: centre)."""
        return centre_pull(self.study, algo, self.study.functions, self.dim)


def _e(v) -> str:
    return f"{v[0]:+.1f} [{v[1]:+.1f}, {v[2]:+.1f}]"


def _switch(label: str) -> str:
    return "+".join(parse_label(label)[1])


def _signs(facts: DimFacts, variant: str, base: str) -> str:
    """``"CI above 0 in 5 of 5 groups, below in 0"`` over the BBOB groups (not 'all')."""
    cis = [facts.effect(variant, base, g) for g in list(facts.groups)[1:]]
    up, down = sum(lo > 0 for _, lo, _ in cis), sum(hi < 0 for _, _, hi in cis)
    return f"above 0 in {up} of {len(cis)} groups, below in {down}"


def areas_line(f: DimFacts) -> str:
    """The bases' and references' areas over all functions, best first."""
    algos = sorted([*BASES, *REFERENCES], key=lambda a: -f.area(a))
    return (
        f"D = {f.dim}, ECDF area over all {len(f.study.functions)} functions: "
        + ", ".join(f"{name(a)} {f.area(a):.1f} %" for a in algos)
        + "."
    )


def base_line(f: DimFacts, base: str) -> str:
    """Each single switch's effect on ``base`` (largest first) and where its CI lies."""
    ranked = sorted(f.singles[base], key=lambda v: -f.effect(v, base)[0])
    parts = [f"{_switch(v)} {_e(f.effect(v, base))} ({_signs(f, v, base)})" for v in ranked]
    return f"D = {f.dim}, {name(base)} ({f.area(base):.1f} %): " + "; ".join(parts) + "."


def culprit_lines(facts: Sequence[DimFacts]) -> list[str]:
    """The largest single effect per base and dimension, and whether gravity's target is it."""
    tops = [(f, b, f.best_switch(b)) for f in facts for b in BASES]
    listing = "; ".join(
        f"D = {f.dim} {name(b)}: {_switch(v)} {f.effect(v, b)[0]:+.1f}" for f, b, v in tops
    )
    gravity = [(f, b) for f, b, v in tops if _switch(v).startswith("grav_")]
    fixed = [(f, b) for f, b, v in tops if _switch(v) == GRAVITY_FIX]
    if len(gravity) == len(tops):
        verdict = "In every case it moves the target of gravity away from the box centre"
    else:
        verdict = f"In {len(gravity)} of {len(tops)} cases it moves gravity's target"
    where = ", ".join(f"{name(b)} at D = {f.dim}" for f, b in fixed)
    lines = [
        f"Largest single effect per base: {listing}. {verdict}; toward the best-so-far "
        f"({GRAVITY_FIX}) for {where or 'none'}."
    ]
    for f in facts:
        pulls = ", ".join(f"{name(a)} {f.pull(a):.2f}" for a in (*REFERENCES, *BASES))
        fixes = ", ".join(f"{name(b)} {f.pull(f'{b}-{GRAVITY_FIX}'):.2f}" for b in BASES)
        lines.append(
            f"D = {f.dim}, where the final best point lies (median over every run of "
            f"best_x . x*/|x*|^2; 1: at the optimum x*, 0: at the box centre): {pulls}; with "
            f"gravity toward the best-so-far: {fixes}."
        )
    return lines


def weights_line(facts: Sequence[DimFacts]) -> str:
    """AWDO's coefficient draws and the rank-divided pressure, the terms that set how hard the
    centre pulls, switched one at a time."""
    parts = []
    for switch in ("coef_mean", "flat"):
        cells = [
            f"{name(b)} D = {f.dim} {_e(f.effect(f'{b}-{switch}', b))}"
            for f in facts
            for b in ("awdo", "mawdo")
        ]
        parts.append(f"{switch}: {', '.join(cells)}")
    return (
        "AWDO's U[0,1] coefficient draws replaced by their means (coef_mean) and the pressure "
        "without the rank (flat), effect on the area over all functions: " + "; ".join(parts)
        + "."
    )  # fmt: skip


def pairs_line(f: DimFacts) -> str:
    """Second switches on top of MAWDO's gravity fix, against the fix alone."""
    fix = f"{PAIR_BASE}-{GRAVITY_FIX}"
    ranked = sorted(f.on_fix, key=lambda v: -f.effect(v, fix)[0])
    parts = [f"{_switch(v).split('+')[1]} {_e(f.effect(v, fix))}" for v in ranked]
    return (
        f"D = {f.dim}, second switches on top of {fix} ({f.area(fix):.1f} %), area difference "
        f"from {fix} alone: " + ", ".join(parts) + "."
    )


def standing_lines(facts: Sequence[DimFacts]) -> list[str]:
    """The best variant against the references overall, and the group where none comes near."""
    lines = []
    for f in facts:
        best = max(f.family(), key=f.area)
        refs = ", ".join(f"{name(a)} {f.area(a):.1f} %" for a in REFERENCES)
        lines.append(
            f"D = {f.dim}, best WDO-family algorithm of the study over all functions: {best} "
            f"{f.area(best):.1f} % (MAWDO {f.area('mawdo'):.1f} %; {refs})."
        )
    hard = max(list(facts[0].groups)[1:], key=lambda g: min(f.gap(g) for f in facts))
    cells = []
    for f in facts:
        best = max(f.family(), key=lambda a: f.area(a, hard))
        cells.append(
            f"D = {f.dim} {best} {f.area(best, hard):.1f} % against CMA-ES's "
            f"{f.area('cmaes', hard):.1f} %"
        )
    lines.append(
        f"The group where the best WDO-family algorithm stays furthest below CMA-ES is "
        f"{GROUP_SHORT.get(hard, hard)}: {'; '.join(cells)}."
    )
    return lines


def findings(facts: Sequence[DimFacts], plans: Sequence) -> list[str]:
    """The sentences of ``findings.md``, one per line (Markdown), in order."""
    lines = [protocol_line(plans), *map(areas_line, facts)]
    lines += [base_line(f, b) for f in facts for b in BASES]
    lines += culprit_lines(facts)
    lines.append(weights_line(facts))
    lines += [pairs_line(f) for f in facts if f.on_fix]
    lines += standing_lines(facts)
    return lines


def plot_selected(f: DimFacts, out: Path) -> list[Path]:
    """ECDF per function group of the bases, each base's best single switch and the
    references (9 curves), as ``ecdf_d{D}.png``, and ``ecdf_d{D}_zoom.png`` with the y axis
    cut to 0.4 (the WDO family's curves stay below it; CMA-ES's leave the panels)."""
    from mawdo.experiments.kinds.suite.plots import plot_ecdfs

    shown = [*BASES, *(f.best_switch(b) for b in BASES), *REFERENCES]
    sub = replace(f.study, algorithms=tuple(shown))
    zoom = plot_ecdfs(sub, f.dim, out, top=ZOOM, stem=f"ecdf_d{f.dim}_zoom")
    return plot_ecdfs(sub, f.dim, out) + zoom


def load_facts(stores: Sequence[str | Path]) -> tuple[list[DimFacts], list]:
    """The stores grouped by dimension (merged per D) and their plans, in the order given."""
    from mawdo.experiments.store import Store

    by_dim: dict[int, list[Path]] = {}
    plans = []
    for p in stores:
        with Store.read(p) as store:
            plans.append((Path(p).name, store.plan, store.meta["library_version"]))
        for d in store.plan.dims:
            by_dim.setdefault(d, []).append(Path(p))
    facts = [DimFacts(load_runs(ps), d) for d, ps in sorted(by_dim.items())]
    return facts, plans


def main(argv: Sequence[str] | None = None) -> int:
    """``python -m mawdo.experiments.kinds.suite.components_summary STORE... --out DIR``."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("stores", nargs="+", type=Path, help="the component study's stores")
    parser.add_argument("--out", type=Path, required=True, help="output folder")
    parser.add_argument("--no-plots", action="store_true", help="skip the figures")
    args = parser.parse_args(argv)
    from mawdo.experiments.store import StoreError

    try:
        facts, plans = load_facts(args.stores)
        lines = findings(facts, plans)
        args.out.mkdir(parents=True, exist_ok=True)
        (args.out / "findings.md").write_text("\n".join(lines) + "\n", encoding="utf-8")
        if not args.no_plots:
            for f in facts:
                plot_selected(f, args.out)
    except (ValueError, OSError, StoreError) as exc:
        print(f"error: {exc}", file=sys.stderr)
        return 2
    print(docs_section(lines, plans))
    return 0


__all__ = ["DimFacts", "command", "findings", "load_facts", "main"]

if __name__ == "__main__":
    raise SystemExit(main())
