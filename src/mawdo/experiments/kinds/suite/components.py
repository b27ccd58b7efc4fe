"""The WDO family's component study: which part of the design costs what on BBOB.

Every suspect of the issue is a switch of :class:`~mawdo.optimizers.wdo.WindParams`, default
off so ``wdo``, ``awdo`` and ``mawdo`` stay the papers' algorithms. A *component variant* is a
base algorithm with one switch (or two) turned: ``mawdo-grav_mean = mawdo:gravity_to="mean"``.
The plans run the bases and their variants under common random numbers (a run's seed depends on
its problem and index only), so a variant's difference from its base is the switch's effect
(:mod:`.effects` reports it).

The switches (``SWITCHES``): gravity off / toward the population mean / toward the best-so-far
(instead of the box centre), AWDO's U[0,1] coefficient draws replaced by their means, pressure
and Coriolis weights without the rank, no velocity clamp, the other boundary policy, and, for
MAWDO, no groups, no hierarchical guidance, no gate, no restart + OBL, no OBL. Low-dimensional
stabilisation acts only at D <= 3 and is left out of the D 5 and 20 plans.

WDO+ (:mod:`mawdo.optimizers.wdo_plus`) is a base of its own (``PLUS_SWITCHES``): each switch
turns one of its five changes back to WDO's choice (``wdo_plus-origin``, ``-nopressure``,
``-noadapt``, ``-norestart``, ``-clip``), and ``-best`` moves its gravity reference from the
mean of the personal bests to the best. The preset ``wdo-plus-components-cec2017`` runs them
with WDO and jSO on the official CEC 2017 at D = 10.
"""

from __future__ import annotations

from itertools import combinations
from typing import Any

from mawdo.experiments.kinds.suite.official import OFFICIAL_SEED

MEANS = {"coef_draw": "fixed", "alpha": 0.5, "g": 0.5, "RT": 0.5, "c": 0.5}
"""AWDO's coefficient draws U[0, 1] replaced by their means (0.5 each)."""

SWITCHES: dict[str, dict[str, Any]] = {
    "grav_none": {"gravity_to": "none"},
    "grav_mean": {"gravity_to": "mean"},
    "grav_best": {"gravity_to": "best"},
    "coef_mean": MEANS,
    "flat": {"pressure": "flat"},
    "noclamp": {"clamp": False},
    "bound": {},  # the other boundary policy: filled in per base by :func:`switch_options`
    "nogroups": {"groups": 1, "rank_scope": "population"},
    "noguide": {"guidance": "global"},
    "nogate": {"gate": False},
    "norestart": {"restart": False, "obl": False},
    "noobl": {"obl": False},
}
"""Component switches by short name: the options that turn each one."""

BASE_SWITCHES: dict[str, tuple[str, ...]] = {
    "wdo": ("grav_none", "grav_mean", "grav_best", "flat", "noclamp", "bound"),
    "awdo": ("grav_none", "grav_mean", "grav_best", "coef_mean", "flat", "noclamp", "bound"),
    "mawdo": (
        "grav_none",
        "grav_mean",
        "grav_best",
        "coef_mean",
        "flat",
        "noclamp",
        "bound",
        "nogroups",
        "noguide",
        "nogate",
        "norestart",
        "noobl",
    ),
}
"""The switches that mean something for each base (WDO has no draws, no groups, ...)."""

BOUNDARY = {"wdo": "reflect", "awdo": "reflect", "mawdo": "clip"}
"""``bound``: the policy each base does not use (MAWDO reflects; WDO and AWDO clip)."""

PAIR_BASE = "mawdo"
"""Pairs of switches are studied on MAWDO, the algorithm the issue is about."""

PLUS_BASE = "wdo_plus"
"""WDO+, whose switches (``PLUS_SWITCHES``) are not those of the wind family's parameters."""

PLUS_SWITCHES: dict[str, dict[str, Any]] = {
    "origin": {"centre": "origin"},
    "best": {"centre": "best"},
    "nopressure": {"random_pressure": False},
    "noadapt": {"adapt": False, "sigma0": 0.0},
    "norestart": {"restart": False},
    "clip": {"boundary": "clip"},
}
"""WDO+'s switches: each of its five changes back to WDO's choice (gravity toward the box
centre, one pressure weight for every coordinate, no noise term, no restarts, clipping), and
gravity toward the best instead of the mean of the personal bests."""


def base_switches(base: str) -> tuple[str, ...]:
    """The switch names that mean something for ``base`` (a wind base or WDO+)."""
    return tuple(PLUS_SWITCHES) if base == PLUS_BASE else BASE_SWITCHES[base]


def switch_options(base: str, names: tuple[str, ...]) -> dict[str, Any]:
    """The options of ``base`` with the switches ``names`` turned."""
    out: dict[str, Any] = {}
    for name in names:
        if base == PLUS_BASE:
            out.update(PLUS_SWITCHES[name])
        else:
            out.update(SWITCHES[name] or {"boundary": BOUNDARY[base]})
    return out


def _compatible(a: str, b: str) -> bool:
    """Two switches form a pair when they touch different options (not two gravity targets)
    and neither contains the other (``norestart`` already drops OBL)."""
    keys_a = set(switch_options(PAIR_BASE, (a,)))
    keys_b = set(switch_options(PAIR_BASE, (b,)))
    return not keys_a & keys_b


def component_variants(pairs: bool = True, bases=tuple(BASE_SWITCHES)) -> dict[str, Any]:
    """Plan fields ``algorithms``, ``variants`` and ``options`` of a component study.

    Parameters
    ----------
    pairs : bool
        Also every compatible pair of switches on MAWDO (``mawdo-flat+noclamp``).
    bases : sequence of str
        The base algorithms, among ``wdo``, ``awdo``, ``mawdo`` and ``wdo_plus``.

    Returns
    -------
    dict
        ``{"algorithms": [...], "variants": {label: base}, "options": {label: {...}}}``; labels
        are ``BASE-SWITCH`` or ``BASE-SWITCH+SWITCH``.
    """
    algorithms, variants, options = list(bases), {}, {}
    combos = [(b, (s,)) for b in bases for s in base_switches(b)]
    if pairs and PAIR_BASE in bases:
        combos += [
            (PAIR_BASE, pair)
            for pair in combinations(BASE_SWITCHES[PAIR_BASE], 2)
            if _compatible(*pair)
        ]
    for base, names in combos:
        label = f"{base}-{'+'.join(names)}"
        algorithms.append(label)
        variants[label] = base
        options[label] = switch_options(base, names)
    return {"algorithms": algorithms, "variants": variants, "options": options}


def parse_label(label: str) -> tuple[str, tuple[str, ...]]:
    """``"mawdo-flat+noclamp"`` -> ``("mawdo", ("flat", "noclamp"))``; a base -> ``(base, ())``.

    Raises ``ValueError`` for a label that is not a component variant's.
    """
    base, _, rest = label.partition("-")
    names = tuple(rest.split("+")) if rest else ()
    known = base_switches(base) if base in (*BASE_SWITCHES, PLUS_BASE) else None
    if known is None or any(n not in known for n in names):
        raise ValueError(f"{label!r} is not a component variant (BASE-SWITCH[+SWITCH])")
    return base, names


def component_presets(seed: int) -> tuple[dict[str, dict[str, Any]], dict[str, str]]:
    """The registered component-study presets and their help lines.

    ``wdo-components``: BBOB f1-f24, instances 1-5, D 5 and 20, 2000 x D evaluations (the
    issue's protocol), 3 runs; the three bases, each switch on each, every compatible pair on
    MAWDO. ``wdo-components-quick``: the single switches only, D 5, instances 1-3, 1000 x D, 2
    runs (a loaded laptop's hour).
    """
    full = {
        "name": "wdo-components",
        "suite": "bbob",
        **component_variants(pairs=True),
        "functions": list(range(1, 25)),
        "instances": [1, 2, 3, 4, 5],
        "dims": [5, 20],
        "budget": 2e3,
        "runs": 3,
        "seed": seed,
    }
    quick = {
        **full,
        "name": "wdo-components-quick",
        **component_variants(pairs=False),
        "instances": [1, 2, 3],
        "dims": [5],
        "budget": 1e3,
        "runs": 2,
    }
    helps = {
        "wdo-components": "the component study: WDO, AWDO, MAWDO with each component "
        "switch and every pair on MAWDO; BBOB f1-f24, instances 1-5, D 5 and 20, 2e3 x D, 3 runs",
        "wdo-components-quick": "the component study's single switches at D 5, instances 1-3, "
        "1e3 x D, 2 runs",
    }
    return {"wdo-components": full, "wdo-components-quick": quick}, helps


def plus_component_presets() -> tuple[dict[str, dict[str, Any]], dict[str, str]]:
    """WDO+'s component-study preset on the official CEC 2017 and its help line.

    ``wdo-plus-components-cec2017``: F1-F30 at D = 10, ``1e4 x D`` evaluations, 51 runs (the
    competition's protocol at D = 10, and the official presets' seed, so WDO+, WDO and jSO make
    the runs of ``cec2017-official`` at D = 10); WDO+ with each switch of ``PLUS_SWITCHES``, WDO,
    and jSO as the reference it loses to.
    """
    name = "wdo-plus-components-cec2017"
    plus = component_variants(pairs=False, bases=(PLUS_BASE,))
    plan = {
        "name": name,
        "suite": "cec2017",
        **plus,
        "algorithms": [*plus["algorithms"], "wdo", "jso"],
        "functions": list(range(1, 31)),
        "instances": [1],
        "dims": [10],
        "budget": 1e4,
        "runs": 51,
        "seed": OFFICIAL_SEED,
    }
    helps = {
        name: "WDO+'s component study on CEC 2017 F1-F30, D 10, 1e4 x D, 51 runs: WDO+ with each "
        "of its changes turned back to WDO's, WDO, and jSO",
    }
    return {name: plan}, helps
