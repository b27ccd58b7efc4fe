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

import math
import numbers

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
