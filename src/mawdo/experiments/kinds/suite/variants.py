"""Named variants of a suite study: one registered optimizer under a label with its own options.

A plan's ``variants`` maps a label to a registered optimizer (``{"mawdo-r10": "mawdo"}``); the
label is then an entry of ``algorithms`` like any optimizer, its options are
``options["mawdo-r10"]``, its runs are stored and reported under the label, and it shares the
seeds of every other algorithm (common random numbers). On the command line::

    --variant mawdo-r10=mawdo:restart_every=10     # LABEL=ALGORITHM[:OPTION=VALUE,...]
    --option mawdo.groups=4                        # NAME.OPTION=VALUE (algorithm or label)

Values are read as TOML values (``10``, ``0.2``, ``true``, ``[1, 2]``, ``"clip"``); a bare word
that is not one (``clip``) is a string.
"""

from __future__ import annotations

import re
import tomllib
from typing import Any

from mawdo.optimizers import OPTIMIZERS

LABEL = re.compile(r"[a-z0-9][a-z0-9_.+-]*")
"""A variant label, lower-cased: also the name of its export folder."""

VARIANT_FORM = "LABEL=ALGORITHM[:OPTION=VALUE,...], e.g. --variant mawdo-r10=mawdo:restart_every=10"
OPTION_FORM = "NAME.OPTION=VALUE, e.g. --option mawdo.groups=4 (NAME: an algorithm or a label)"


def check_variants(variants: dict[str, Any]) -> dict[str, str]:
    """Lower-cased labels mapped to canonical optimizer names.

    Raises
    ------
    ValueError
        A label that is not a plain name, that names a registered optimizer or that is given
        twice, or an unknown optimizer; the message starts with ``variants.<label>``.
    """
    out: dict[str, str] = {}
    for raw, algo in variants.items():
        label = str(raw).strip().lower()
        where = f"variants.{raw}"
        if not LABEL.fullmatch(label):
            raise ValueError(
                f"{where}: a label is letters, digits and _ . + - (starting with a letter or "
                f"digit), e.g. mawdo-r10"
            )
        if label in OPTIMIZERS:
            raise ValueError(
                f"{where}: {label!r} is a registered algorithm; give the variant its own label "
                f"(e.g. {label}-v2)"
            )
        if label in out:
            raise ValueError(f"{where}: the label {label!r} is given twice")
        if not isinstance(algo, str):
            raise ValueError(f"{where}: must name a registered algorithm (got {algo!r})")
        try:
            out[label] = OPTIMIZERS[algo].name
        except KeyError as exc:
            raise ValueError(f"{where}: {exc.args[0]}") from None
    return out


def canonical_name(name: str, variants: dict[str, str]) -> str:
    """A variant's label or a registered optimizer's canonical name; raises ``KeyError`` with
    the close names (and how to define a variant) for anything else."""
    low = str(name).strip().lower()
    if low in variants:
        return low
    try:
        return OPTIMIZERS[name].name
    except KeyError as exc:
        raise KeyError(
            f"{exc.args[0]} A variant needs a definition: variants.{low} = 'ALGORITHM' in a "
            f"plan, or --variant {low}=ALGORITHM:OPTION=VALUE"
        ) from None


def describe_setup(label: str, variants: dict[str, str], options: dict[str, Any]) -> str:
    """``"mawdo (restart_every=10)"``: what runs under ``label``."""
    opts = options.get(label) or {}
    inner = ", ".join(f"{k}={v!r}" if isinstance(v, str) else f"{k}={v}" for k, v in opts.items())
    return f"{variants.get(label, label)}" + (f" ({inner})" if inner else "")


def _split_top(text: str) -> list[str]:
    # commas inside [...] or quotes belong to a value (weights=[0.5, 0.5])
    parts, depth, quote, cur = [], 0, "", ""
    for ch in text:
        if quote:
            quote = "" if ch == quote else quote
        elif ch in "\"'":
            quote = ch
        elif ch in "[{":
            depth += 1
        elif ch in "]}":
            depth -= 1
        elif ch == "," and depth == 0:
            parts.append(cur)
            cur = ""
            continue
        cur += ch
    return [*parts, cur]


def parse_value(text: str) -> Any:
    """A TOML value (``10``, ``0.5``, ``true``, ``[1, 2]``), else the text as a string."""
    try:
        return tomllib.loads(f"v = {text.strip()}")["v"]
    except tomllib.TOMLDecodeError:
        return text.strip()


def parse_assignments(text: str, flag: str, form: str) -> dict[str, Any]:
    """``"a=1,b=[2, 3]"`` -> ``{"a": 1, "b": [2, 3]}``; raises ``ValueError`` naming ``flag``."""
    out: dict[str, Any] = {}
    for item in _split_top(text):
        key, eq, value = item.partition("=")
        if not eq or not key.strip() or not value.strip():
            raise ValueError(f"{flag} {text!r}: {item.strip()!r} is not OPTION=VALUE; write {form}")
        out[key.strip()] = parse_value(value)
    return out


def parse_variant(text: str) -> tuple[str, str, dict[str, Any]]:
    """``"mawdo-r10=mawdo:restart_every=10"`` -> ``("mawdo-r10", "mawdo", {"restart_every":
    10})``; the names are checked by the plan. Raises ``ValueError`` showing the form."""
    head, _, opts = text.partition(":")
    label, eq, algo = head.partition("=")
    if not eq or not label.strip() or not algo.strip():
        raise ValueError(f"--variant {text!r}: write {VARIANT_FORM}")
    options = parse_assignments(opts, "--variant", VARIANT_FORM) if opts.strip() else {}
    return label.strip().lower(), algo.strip(), options


def parse_option(text: str) -> tuple[str, str, Any]:
    """``"mawdo.groups=4"`` -> ``("mawdo", "groups", 4)``. Raises ``ValueError`` showing the
    form."""
    target, eq, value = text.partition("=")
    name, dot, key = target.rpartition(".")
    if not eq or not dot or not name.strip() or not key.strip() or not value.strip():
        raise ValueError(f"--option {text!r}: write {OPTION_FORM}")
    return name.strip(), key.strip(), parse_value(value)


def cli_fields(
    algorithms: list[str], variants: list[str], options: list[str], base: dict[str, Any]
) -> dict[str, Any]:
    """Plan fields ``algorithms``, ``variants`` and ``options`` from command-line flags.

    Parameters
    ----------
    algorithms : list of str
        The plan's algorithms so far (a preset's, a plan file's or ``--algorithms``); each
        ``--variant`` label not among them is appended, in the order given.
    variants, options : list of str
        ``--variant`` and ``--option`` texts.
    base : dict
        The plan's ``variants`` and ``options`` so far; the flags' entries are added (an option
        given again replaces the earlier value).
    """
    out_alg = list(algorithms)
    out_var = dict(base.get("variants") or {})
    out_opt = {k: dict(v) for k, v in (base.get("options") or {}).items()}
    for text in variants:
        label, algo, opts = parse_variant(text)
        if label in out_var and out_var[label] != algo:
            raise ValueError(f"--variant {text!r}: {label!r} is already {out_var[label]!r}")
        out_var[label] = algo
        if opts:  # no empty entry: a plan file without one hashes the same
            out_opt.setdefault(label, {}).update(opts)
        if label not in [str(a).lower() for a in out_alg]:
            out_alg.append(label)
    for text in options:
        name, key, value = parse_option(text)
        out_opt.setdefault(name.lower(), {})[key] = value
    return {"algorithms": out_alg, "variants": out_var, "options": out_opt}
