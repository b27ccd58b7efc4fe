"""WDO+'s component study on the official CEC 2017: which of its changes to WDO holds it back
against jSO, function group by function group, in sentences made from the store.

``findings.md`` (in ``docs/results/wdo-plus-components-cec2017``) and the subsection
``#wdo-plus-components-cec`` of ``docs/algorithms.md`` are this module's output;
tests/test_plus_component_results.py checks both against the committed store and recomputes
their numbers from the raw rows. Run as a module to rewrite ``findings.md`` and print the
docs subsection::

    python -m mawdo.experiments.kinds.suite.plus_components_summary store.db --out DIR

Two measures, each a run's value averaged over a group's functions and compared *paired*: a
variant shares every seed with WDO+ (the preset ``wdo-plus-components-cec2017``):

- **final error**, in decades: ``log10(max(f - f*, 1e-8))`` after the whole budget (the
  competition counts errors up to 1e-8 as 0). A switch's effect is its variant's value minus
  WDO+'s: below 0, turning that change back to WDO's lowers the error, so the change holds
  WDO+ back there;
- **ECDF area** (:mod:`.effects`: COCO's 51 targets 1e2..1e-8 on the error), percentage points;
  above 0, turning the change back helps.

Intervals: the percentile bootstrap of :class:`.effects.EffectData` (95 %, 1000 resamples of
the runs, one resample shared by every function of a group). A change *holds WDO+ back* in a
group when the interval of its final-error effect lies below 0.
"""

from __future__ import annotations

import argparse
import sys
from collections.abc import Sequence
from pathlib import Path

import numpy as np

from mawdo.experiments.kinds.suite.components import PLUS_BASE, PLUS_SWITCHES
from mawdo.experiments.kinds.suite.components_text import command, name
from mawdo.experiments.kinds.suite.data import StudyRuns, load_runs
from mawdo.experiments.kinds.suite.effects import EffectData, unit_runs
from mawdo.experiments.kinds.suite.measures import groups

REFERENCE = "jso"
"""The winner WDO+ is compared with."""
OTHERS = (REFERENCE, "wdo")
FLOOR = 1e-8
"""Errors up to this count as 0 (CEC 2017's rule): the final error's floor."""

CHANGES = {
    "origin": ("gravity toward the mean", "gravity toward the box centre as in WDO, not toward "
               "the mean of the personal bests"),
    "nopressure": ("random pressure weights", "one pressure weight for every coordinate as in "
                   "WDO, not a U[0,1) draw each"),
    "noadapt": ("adapted noise", "no success-adapted noise term: WDO's noiseless move"),
    "norestart": ("restarts", "no restarts of a stalled run, as in WDO"),
    "clip": ("midpoint bounds", "clipping at the bounds as in WDO, not the midpoint rule"),
}  # fmt: skip
"""WDO+'s five changes by the switch that turns each back to WDO's choice: (the change's short
name, what the switch does)."""
ALTERNATIVE = {"best": ("", "gravity toward the best-so-far, not the mean of the personal bests")}
"""A switch that is not one of the five changes but another choice for the first."""


def group_label(group: str, fids: Sequence[int]) -> str:
    """``"hybrid (F11-F20)"``; ``"all functions"`` as it is."""
    if group == "all functions":
        return group
    return f"{group} (F{min(fids)}-F{max(fids)})" if len(fids) > 1 else f"{group} (F{fids[0]})"


class PlusFacts:
    """The measures of the study's store at one dimension that the sentences quote.

    Parameters
    ----------
    study : StudyRuns
        The store's runs: WDO+, each of its single-switch variants, WDO and jSO.
    dim : int
        Dimension D.
    """

    def __init__(self, study: StudyRuns, dim: int):
        self.study, self.dim = study, dim
        self.variants = [f"{PLUS_BASE}-{s}" for s in PLUS_SWITCHES]
        algos = [PLUS_BASE, *self.variants, *OTHERS]
        missing = [a for a in algos if a not in study.algorithms]
        if missing:
            raise ValueError(
                f"D = {dim}: the store lacks {', '.join(missing)}; give the store of the preset "
                "wdo-plus-components-cec2017"
            )
        self.groups = groups(study)
        self.data = EffectData(study, dim, algos, PLUS_BASE)
        self.log_err: dict[tuple[str, int], np.ndarray] = {}
        self.mean_err: dict[tuple[str, int], float] = {}
        for algo in algos:
            for fid in study.functions:
                runs = unit_runs(study, algo, fid, dim, self.data.units)
                err = np.array([r.precision[-1] for r in runs])
                self.log_err[algo, fid] = np.log10(np.maximum(err, FLOOR))
                self.mean_err[algo, fid] = float(np.where(err <= FLOOR, 0.0, err).mean())

    def log_error(self, algo: str, group: str) -> float:
        """Mean ``log10`` final error of ``algo`` over ``group``'s functions and the runs."""
        return float(np.mean([self.log_err[algo, f].mean() for f in self.groups[group]]))

    def area(self, algo: str, group: str) -> float:
        """Mean ECDF area of ``algo`` over ``group``'s functions, percent."""
        return 100 * float(np.mean([self.data.area[algo, f].mean() for f in self.groups[group]]))

    def error_effect(self, switch: str, group: str) -> tuple[float, float, float]:
        """Final-error effect of ``switch`` (decades, variant - WDO+) and its interval."""
        v = f"{PLUS_BASE}-{switch}"
        fids = self.groups[group]
        d = np.mean([self.log_err[v, f] - self.log_err[PLUS_BASE, f] for f in fids], axis=0)
        return self.data.interval(d)

    def area_effect(self, switch: str, group: str) -> tuple[float, float, float]:
        """ECDF-area effect of ``switch`` (points, variant - WDO+) and its interval."""
        return self.data.area_effect(f"{PLUS_BASE}-{switch}", PLUS_BASE, self.groups[group])

    def against(self, group: str) -> tuple[int, int, int]:
        """Functions of ``group`` where WDO+'s mean error (errors <= 1e-8 as 0) is below,
        above and equal to jSO's."""
        pairs = [(self.mean_err[PLUS_BASE, f], self.mean_err[REFERENCE, f])
                 for f in self.groups[group]]  # fmt: skip
        return (sum(a < b for a, b in pairs), sum(a > b for a, b in pairs),
                sum(a == b for a, b in pairs))  # fmt: skip


def _e(v: tuple[float, float, float], digits: int = 2) -> str:
    return f"{v[0]:+.{digits}f} [{v[1]:+.{digits}f}, {v[2]:+.{digits}f}]"


def protocol_line(f: PlusFacts, plan, version: str) -> str:
    """What the store holds."""
    official = plan.budget == 1e4 and plan.runs == 51 and plan.functions == tuple(range(1, 31))
    return (
        f"WDO+'s component study on CEC 2017 (the official functions) F{min(plan.functions)}-"
        f"F{max(plan.functions)}, D = {f.dim}, {plan.budget:g} x D evaluations, {plan.runs} "
        f"runs{' (the competition protocol)' if official else ''}, seed {plan.seed}: WDO+ and "
        f"its {len(f.variants)} single-switch variants under common random numbers, WDO and "
        f"jSO; store made by mawdo {version}."
    )


def standing_line(f: PlusFacts, group: str) -> str:
    """WDO+, jSO and WDO on ``group``: final error, ECDF area, functions won against jSO."""
    algos = (PLUS_BASE, *OTHERS)
    better, worse, tied = f.against(group)
    errs = ", ".join(f"{name(a)} {f.log_error(a, group):+.2f}" for a in algos)
    areas = ", ".join(f"{name(a)} {f.area(a, group):.1f} %" for a in algos)
    return (
        f"{group_label(group, f.groups[group])}: mean log10 final error {errs}; ECDF area "
        f"{areas}; WDO+'s mean error below jSO's on {better} of {len(f.groups[group])} "
        f"functions, above on {worse}, equal on {tied}."
    )


def switch_line(f: PlusFacts, switch: str) -> str:
    """One switch's effects on the final error and the ECDF area, every group."""
    text = {**CHANGES, **ALTERNATIVE}[switch][1]
    errs = "; ".join(f"{g} {_e(f.error_effect(switch, g))}" for g in f.groups)
    areas = "; ".join(f"{g} {_e(f.area_effect(switch, g), 1)}" for g in f.groups)
    return (
        f"`{switch}`, {text}. Final error, decades against WDO+: {errs}. ECDF area, points: "
        f"{areas}."
    )


def _changes(switches, effects) -> str:
    """``"its restarts (norestart -2.77 [-2.90, -2.62]), its ... and its ..."``."""
    parts = [f"its {CHANGES[s][0]} ({s} {_e(effects[s])})" for s in switches]
    return parts[0] if len(parts) == 1 else ", ".join(parts[:-1]) + " and " + parts[-1]


def verdict_line(f: PlusFacts, group: str) -> str:
    """Where WDO+ loses to jSO in ``group``: which of its changes holds it back, if any."""
    label = group_label(group, f.groups[group])
    better, worse, _ = f.against(group)
    n = len(f.groups[group])
    if worse <= better:
        return (
            f"{label}: WDO+ does not lose to jSO (mean error below on {better} of {n} "
            f"functions, above on {worse})."
        )
    effects = {s: f.error_effect(s, group) for s in CHANGES}
    back = sorted((s for s, v in effects.items() if v[2] < 0), key=lambda s: effects[s][0])
    needed = sorted((s for s, v in effects.items() if v[1] > 0), key=lambda s: -effects[s][0])
    head = f"{label}: WDO+ loses to jSO (mean error above on {worse} of {n} functions)"
    if back:
        what = (
            f"held back by {_changes(back, effects)}: turning "
            f"{'either' if len(back) == 2 else 'any one' if back[2:] else 'it'} back to WDO's "
            "lowers its final error"
        )
    else:
        least = min(effects, key=lambda s: effects[s][0])
        what = (
            "none of its five changes holds it back: turning any one back to WDO's raises its "
            f"final error or leaves it within the interval (lowest: {least} "
            f"{_e(effects[least])})"
        )
    helps = _changes(needed, effects) if needed else "none"
    alt = "; ".join(f"{s} {_e(f.error_effect(s, group))}" for s in ALTERNATIVE)
    return (
        f"{head}; {what}. The changes it needs there (turning one back raises the error): "
        f"{helps}. Gravity toward the best instead of the mean: {alt}."
    )


def findings(f: PlusFacts, plan, version: str) -> list[str]:
    """The sentences of ``findings.md``, one per line (Markdown), in order."""
    lines = [protocol_line(f, plan, version)]
    lines += [standing_line(f, g) for g in f.groups]
    lines += [switch_line(f, s) for s in (*CHANGES, *ALTERNATIVE)]
    lines += [verdict_line(f, g) for g in list(f.groups)[1:]]
    return lines


def docs_section(lines: Sequence[str], plan, out: str) -> str:
    """The subsection of ``docs/algorithms.md`` (Markdown), without its heading."""
    head = [
        "WDO+ (`wdo_plus`) beside its variants `wdo_plus-SWITCH`, each of which turns one of "
        "its five changes back to WDO's choice (`origin`, `nopressure`, `noadapt`, "
        "`norestart`, `clip`; `best`: gravity toward the best-so-far instead), under common "
        "random numbers, with WDO and jSO. A switch's effect on the final error is the "
        "variant's mean log10 error minus WDO+'s (below 0: the change holds WDO+ back); on "
        "the ECDF area, the variant's minus WDO+'s (above 0: the change holds it back); "
        f"bootstrap 95 % intervals over the {plan.runs} runs; decades of the final error "
        "f - f*, floored at 1e-8.",
        "",
        "Generated from the store in "
        "[results/wdo-plus-components-cec2017](results/wdo-plus-components-cec2017/) by "
        "`python -m mawdo.experiments.kinds.suite.plus_components_summary` "
        "(`tests/test_plus_component_results.py` recomputes the numbers from the raw rows; "
        "the report with the per-group effect tables is in that folder). The store was made by",
        "",
        f"    {command(plan, out)}",
        "",
    ]
    return "\n".join([*head, *(f"- {s}" for s in lines)]) + "\n"


def load_facts(store: str | Path) -> tuple[PlusFacts, object, str]:
    """The store's facts at its one dimension, its plan and the mawdo version that made it."""
    from mawdo.experiments.store import Store

    with Store.read(store) as s:
        plan, version = s.plan, s.meta["library_version"]
    if len(plan.dims) != 1:
        raise ValueError(f"{store}: one dimension expected, the plan has {plan.dims}")
    return PlusFacts(load_runs([Path(store)]), plan.dims[0]), plan, version


def main(argv: Sequence[str] | None = None) -> int:
    """``python -m mawdo.experiments.kinds.suite.plus_components_summary STORE --out DIR``."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("store", type=Path, help="the store of wdo-plus-components-cec2017")
    parser.add_argument("--out", type=Path, required=True, help="output folder")
    args = parser.parse_args(argv)
    from mawdo.experiments.store import StoreError

    try:
        facts, plan, version = load_facts(args.store)
        lines = findings(facts, plan, version)
        section = docs_section(lines, plan, args.store.name)
        args.out.mkdir(parents=True, exist_ok=True)
        (args.out / "findings.md").write_text("\n".join(lines) + "\n", encoding="utf-8")
    except (ValueError, OSError, StoreError) as exc:
        print(f"error: {exc}", file=sys.stderr)
        return 2
    print(section)
    return 0


__all__ = ["PlusFacts", "docs_section", "findings", "load_facts", "main"]

if __name__ == "__main__":
    raise SystemExit(main())
