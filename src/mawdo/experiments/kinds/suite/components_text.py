"""Wording of the component study's findings: display names, the command that made each store
(recovered from its plan and checked against the plan's hash), the protocol line and the docs
section (:mod:`.components_summary` computes the numbers)."""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

from mawdo.experiments.kinds.suite.holdout_summary import name

__all__ = ["GROUP_SHORT", "SWITCH_TEXT", "command", "docs_section", "name", "protocol_line"]

GROUP_SHORT = {
    "separable": "separable (f1-f5)",
    "low or moderate conditioning": "low or moderate conditioning (f6-f9)",
    "high conditioning, unimodal": "high conditioning, unimodal (f10-f14)",
    "multimodal, adequate global structure": "multimodal with adequate structure (f15-f19)",
    "multimodal, weak global structure": "multimodal with weak structure (f20-f24)",
}
"""COCO's BBOB groups with their functions, for sentences."""

SWITCH_TEXT = {
    "grav_none": "no gravity term",
    "grav_mean": "gravity toward the population mean instead of the box centre",
    "grav_best": "gravity toward the best-so-far instead of the box centre",
    "coef_mean": "AWDO's U[0,1] coefficient draws replaced by their means (0.5)",
    "flat": "pressure and Coriolis weights without the rank",
    "noclamp": "no velocity clamp",
    "bound": "the other boundary policy (WDO, AWDO: reflect; MAWDO: clip)",
    "nogroups": "MAWDO without groups",
    "noguide": "MAWDO without hierarchical guidance",
    "nogate": "MAWDO without the gate",
    "norestart": "MAWDO without restart and OBL",
    "noobl": "MAWDO without OBL",
}
"""What each switch of :data:`.components.SWITCHES` does, for the docs."""

_FIELDS = ("dims", "instances", "runs", "budget", "algorithms", "functions")
"""The plan fields a component store may set on top of its preset (``--set``)."""


def _value(v: Any) -> str:
    if isinstance(v, (list, tuple)):
        return ",".join(map(_value, v))
    return f"{v:g}" if isinstance(v, float) else str(v)


def command(plan: Any, out: str) -> str:
    """The ``mawdo study run`` command that makes ``plan``'s store ``out``.

    Raises
    ------
    ValueError
        The plan is not its preset with ``--set`` of the fields ``dims``, ``instances``,
        ``runs``, ``budget`` and ``algorithms`` (the rebuilt plan's hash differs).
    """
    from mawdo.experiments.protocol import find_preset

    preset = find_preset(plan.name)
    sets = {k: getattr(plan, k) for k in _FIELDS if getattr(plan, k) != getattr(preset, k)}
    rebuilt = preset.with_overrides(**{k: list(v) if isinstance(v, tuple) else v
                                       for k, v in sets.items()})  # fmt: skip
    if rebuilt.plan_hash != plan.plan_hash:
        raise ValueError(f"{out}: its plan is not preset {plan.name} with --set of {_FIELDS}")
    flags = "".join(f" --set {k}={_value(v)}" for k, v in sets.items())
    return f"mawdo study run {plan.name}{flags} -o {out}"


def _ranges(ids: Sequence[int]) -> str:
    ids = sorted(ids)
    consecutive = ids == list(range(ids[0], ids[-1] + 1))
    return f"{ids[0]}-{ids[-1]}" if consecutive and len(ids) > 2 else ", ".join(map(str, ids))


def protocol_line(plans: Sequence[tuple[str, Any, str]]) -> str:
    """What the stores hold against the preset ``wdo-components`` asks.

    ``plans``: ``(store file name, plan, mawdo version)`` per store.
    """
    from mawdo.experiments.protocol import find_preset

    full = find_preset("wdo-components")
    per_dim = {}
    for _, plan, _ in plans:
        for d in plan.dims:
            per_dim.setdefault(d, (plan.instances, set()))[1].update(plan.algorithms)
    dims = "; ".join(
        f"D = {d}, instances {_ranges(inst)}, {len(algos)} algorithms"
        for d, (inst, algos) in sorted(per_dim.items())
    )
    runs = sorted({p.runs for _, p, _ in plans})
    budgets = sorted({p.budget for _, p, _ in plans})
    versions = sorted({v for _, _, v in plans})
    return (
        f"Component study of WDO, AWDO and MAWDO on BBOB f1-f24, a reduced "
        f"protocol: {dims}; {' or '.join(map(str, runs))} runs, "
        f"{' or '.join(f'{b:g}' for b in budgets)} x D evaluations (the preset "
        f"`wdo-components` asks D = {' and '.join(map(str, full.dims))}, instances "
        f"{_ranges(full.instances)}, {full.runs} runs, {full.budget:g} x D); stores made by "
        f"mawdo {' and '.join(versions)}, whose component switches the current code runs "
        "bit-identically."
    )


def docs_section(lines: Sequence[str], plans: Sequence[tuple[str, Any, str]]) -> str:
    """The component-study section of ``docs/algorithms.md`` (Markdown)."""
    cmds = [command(plan, f) for f, plan, _ in plans]
    switches = "; ".join(f"`{k}`: {v}" for k, v in SWITCH_TEXT.items())
    head = [
        "Each base (`wdo`, `awdo`, `mawdo`, as the papers give them) runs beside its component "
        "variants `BASE-SWITCH` (and, on MAWDO, `mawdo-SWITCH+SWITCH`) under common random "
        f"numbers. The switches: {switches}.",
        "",
        "Generated from the stores in [results/wdo-components](results/wdo-components/) by "
        "`python -m mawdo.experiments.kinds.suite.components_summary` "
        "(`tests/test_component_results.py` recomputes the numbers from the raw rows; the "
        "per-group effect tables with their intervals, the aRT tables and the ECDF figures "
        "are in that folder). Each store was made by",
        "",
        *(f"    {c}" for c in cmds),
        "",
    ]
    return "\n".join([*head, *(f"- {s}" for s in lines)]) + "\n"
