"""Argument checks shared by the API: every error names the argument, the value and the fix.

Python's numeric tower is too forgiving for an optimiser's inputs: ``True`` is an ``int``,
``float("nan")`` compares False with everything (so a NaN slips through ``x > 0`` guards written
as ``if x <= 0: raise``), and NumPy parses ``"0.4"`` or drops an imaginary part when asked for
floats. These helpers accept real numbers only and say what to pass instead.

A value of the wrong *type* raises :class:`ArgumentTypeError`, which is both a ``TypeError``
(Python's convention) and a ``ValueError`` (so callers that catch bad input as ``ValueError``,
as the command line does, still catch it).
"""

from __future__ import annotations

import dataclasses
import math
import numbers
from typing import Any

import numpy as np


class ArgumentTypeError(TypeError, ValueError):
    """An argument of the wrong type (a string, bool or complex where a real number belongs)."""


def _what(value) -> str:
    return type(value).__name__


def _interval(low, high, low_open: bool, high_open: bool) -> str:
    if low is None and high is None:
        return "a finite number"
    lo = "(-inf" if low is None else ("(" if low_open else "[") + f"{low}"
    hi = "inf)" if high is None else f"{high}" + (")" if high_open else "]")
    return f"a finite number in {lo}, {hi}"


def _text_hint(name: str, value: str, example: str) -> str:
    try:
        return f" (write {name}={float(value)!r}, not {name}={value!r})"
    except ValueError:
        return f" (write a number, e.g. {name}={example})"


def check_real(
    name: str,
    value,
    low=None,
    high=None,
    *,
    low_open: bool = False,
    high_open: bool = False,
) -> float:
    """Return ``float(value)`` if it is a finite real number in the interval, else raise.

    Parameters
    ----------
    name : str
        Argument name, used in the message.
    value : object
        Must be an ``int``/``float`` or a NumPy real scalar; bools, strings and complex numbers
        are refused (``ArgumentTypeError``), as are NaN and +-inf (``ValueError``).
    low, high : float, optional
        Interval ends; ``None`` leaves that side open to infinity.
    low_open, high_open : bool
        Whether the corresponding end is excluded.
    """
    where = _interval(low, high, low_open, high_open)
    if isinstance(value, bool | np.bool_) or not isinstance(value, numbers.Real):
        hint = ""
        if isinstance(value, str):
            hint = _text_hint(name, value, "0.5")
        elif isinstance(value, bool | np.bool_):
            hint = "; bools are not numbers here"
        elif isinstance(value, numbers.Complex):
            hint = "; complex numbers are not accepted"
        raise ArgumentTypeError(f"{name}={value!r} must be {where}, not a {_what(value)}{hint}")
    x = float(value)
    ok = math.isfinite(x)
    if ok and low is not None:
        ok = x > low if low_open else x >= low
    if ok and high is not None:
        ok = x < high if high_open else x <= high
    if not ok:
        raise ValueError(f"{name}={value!r} must be {where}")
    return x


def check_int(
    name: str, value, low: int | None = None, high: int | None = None, *, what: str = ""
) -> int:
    """Return ``int(value)`` if it is an integer (not a bool, not a float) in ``[low, high]``.

    Parameters
    ----------
    name : str
        Argument name, used in the message.
    value : object
        An ``int`` or NumPy integer; ``True``, ``3.0`` and ``"3"`` are refused.
    low, high : int, optional
        Inclusive bounds.
    what : str, optional
        Wording of the requirement in messages (default: "an integer >= low" and the like).
    """
    if low is None and high is None:
        where = "an integer"
    elif high is None:
        where = f"an integer >= {low}"
    elif low is None:
        where = f"an integer <= {high}"
    else:
        where = f"an integer in [{low}, {high}]"
    where = what or where
    if isinstance(value, bool | np.bool_) or not isinstance(value, numbers.Integral):
        hint = "; bools are not integers here" if isinstance(value, bool | np.bool_) else ""
        if isinstance(value, str):
            hint = _text_hint(name, value, "3").replace(".0,", ",")
        elif isinstance(value, float) and value.is_integer():
            hint = f" (write {name}={int(value)})"
        raise ArgumentTypeError(f"{name}={value!r} must be {where}, not a {_what(value)}{hint}")
    n = int(value)
    if (low is not None and n < low) or (high is not None and n > high):
        raise ValueError(f"{name}={value!r} must be {where}")
    return n


def check_bool(name: str, value) -> bool:
    """Return ``value`` if it is a bool (Python or NumPy); ``"no"`` or ``0`` are refused."""
    if not isinstance(value, bool | np.bool_):
        raise ArgumentTypeError(f"{name}={value!r} must be True or False, not a {_what(value)}")
    return bool(value)


def real_array(name: str, value) -> np.ndarray:
    """``value`` as a float array, refusing strings, bools, complex and other non-numbers.

    ``np.asarray(["1", "2"], dtype=float)`` parses strings and ``np.asarray([1j], dtype=float)``
    drops the imaginary part (with a warning); both hide a mistake, so both are errors here.
    Finiteness is left to the caller (some arrays may hold inf).
    """
    try:
        arr = np.asarray(value)
    except ValueError as exc:  # ragged nested sequences
        raise ValueError(f"{name} must be a rectangular array of numbers ({exc})") from exc
    kind = arr.dtype.kind
    if kind == "O":
        bad = [v for v in arr.flat if not _is_real_scalar(v)]
        if bad:
            raise ArgumentTypeError(
                f"{name} must contain real numbers only; found {bad[0]!r} ({_what(bad[0])})"
            )
        return arr.astype(float)
    if kind not in "iuf":
        label = {"U": "strings", "S": "bytes", "c": "complex numbers", "b": "bools"}.get(
            kind, f"values of dtype {arr.dtype}"
        )
        fix = "; convert text with float() first" if kind in "US" else ""
        raise ArgumentTypeError(f"{name} must contain real numbers, not {label}{fix}")
    return arr.astype(float, copy=False)


def _is_real_scalar(v) -> bool:
    return isinstance(v, numbers.Real) and not isinstance(v, bool | np.bool_)


def check_seed(seed, name: str = "seed"):
    """Validate a master seed: None, a non-negative integer, a sequence of them, or a
    ``numpy.random.SeedSequence``. Returns it unchanged."""
    if seed is None or isinstance(seed, np.random.SeedSequence):
        return seed
    fix = (
        f"pass {name}=<integer >= 0> (e.g. {name}=1), a sequence of such integers, "
        f"a numpy.random.SeedSequence, or None for fresh entropy"
    )
    if isinstance(seed, np.random.Generator | np.random.RandomState):
        raise ArgumentTypeError(
            f"{name} got a {_what(seed)}, which cannot be split into reproducible per-run "
            f"streams; {fix}"
        )
    if isinstance(seed, list | tuple | np.ndarray):
        items = list(np.asarray(seed, dtype=object).ravel()) or [None]
    else:
        items = [seed]
    for v in items:
        if isinstance(v, bool | np.bool_) or not isinstance(v, numbers.Integral):
            extra = "; bools are not integers here" if isinstance(v, bool | np.bool_) else ""
            raise ArgumentTypeError(f"{name}={seed!r} is not a valid seed{extra}: {fix}")
        if v < 0:
            raise ValueError(f"{name}={seed!r} is negative: {fix}")
    return seed


# The range of every numeric algorithm option, by name. The Params classes check their own
# cross-field rules (groups <= pop_size, obl needs restart, q_min <= 1/3); this table adds what
# a comparison-based check cannot see: NaN, inf, bools and strings. Options missing here still get
# the type-derived check (finite real for ``float``, integer for ``int``).
# name -> (kind, low, high, low_open, high_open)
OPTION_RANGES: dict[str, tuple] = {
    "pop_size": ("int", 2, None),
    "groups": ("int", 1, None),
    "restart_every": ("int", 1, None),
    "low_dim": ("int", 0, None),
    "alpha": ("real", 0, 1, False, False),  # friction: u <- (1 - alpha) u + ...
    "g": ("real", 0, None, False, False),
    "RT": ("real", 0, None, False, False),
    "c": ("real", 0, None, False, False),
    "vmax": ("real", 0, None, True, False),
    "restart_frac": ("real", 0, 1, True, False),
    "sigma0": ("real", 0, None, True, False),
    "sigma_end": ("real", 0, None, True, False),
    "eta": ("real", 0, 1, False, False),
    "lr": ("real", 0, 1, True, False),
    "q_min": ("real", 0, 1, False, False),
    "b": ("real", None, None, False, False),
    "cma_sigma": ("real", 0, None, True, False),
}


def _field_kind(f: dataclasses.Field) -> str:
    t = f.type if isinstance(f.type, str) else getattr(f.type, "__name__", str(f.type))
    return t.split("|")[0].strip()


def check_option(name: str, value, declared: str = "") -> None:
    """Check one algorithm option against :data:`OPTION_RANGES` or its declared type."""
    spec = OPTION_RANGES.get(name)
    if spec is not None and spec[0] == "int":
        check_int(name, value, spec[1], spec[2])
    elif spec is not None:
        check_real(name, value, spec[1], spec[2], low_open=spec[3], high_open=spec[4])
    elif declared == "float":
        check_real(name, value)
    elif declared == "int":
        check_int(name, value)
    elif declared == "bool":
        check_bool(name, value)
    elif declared == "str" and not isinstance(value, str):
        raise ArgumentTypeError(f"{name}={value!r} must be a string, not a {_what(value)}")
    elif declared == "tuple":
        if not isinstance(value, tuple | list) or isinstance(value, str):
            raise ArgumentTypeError(f"{name}={value!r} must be a tuple of numbers")
        for i, v in enumerate(value):
            check_real(f"{name}[{i}]", v)


def check_options(params_class: type, options: dict[str, Any]) -> None:
    """Check the known options of ``params_class`` (unknown names are left to ``make_params``,
    which suggests close names)."""
    fields = {f.name: f for f in dataclasses.fields(params_class)}
    for key, value in options.items():
        if key in fields:
            check_option(key, value, _field_kind(fields[key]))


def check_params(params) -> None:
    """Check every field of a built ``Params`` instance (presets and defaults included)."""
    for f in dataclasses.fields(params):
        check_option(f.name, getattr(params, f.name), _field_kind(f))
