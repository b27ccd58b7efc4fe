"""The optimizer contract: ``Params`` (frozen coefficients) + ``State`` (arrays) + ask/tell.

Every optimizer works on ``R`` independent runs at once. State arrays carry a leading run axis
``(R, N, D)``; ``ask`` returns candidates ``(R, n, D)`` in the problem's coordinates, ``tell``
receives their values ``(R, n)`` (non-finite already mapped to +inf by the evaluator). All random
numbers come from :class:`mawdo.streams.RunStreams`, one generator per run, so a run's trajectory
does not depend on the batch it shares.
"""

from __future__ import annotations

import dataclasses
from abc import ABC, abstractmethod
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any, ClassVar

import numpy as np

from mawdo.streams import RunStreams
from mawdo.util.validate import ArgumentTypeError, check_bool, check_int, check_real


@dataclass
class Space:
    """The search box seen by an optimizer: ``lb, ub`` of shape ``(D,)``."""

    lb: np.ndarray
    ub: np.ndarray

    @property
    def dim(self) -> int:
        return int(self.lb.shape[0])

    def to_unit(self, x: np.ndarray) -> np.ndarray:
        """Map problem coordinates to the normalised box ``[-1, 1]^D`` (WDO's space)."""
        return 2.0 * (x - self.lb) / (self.ub - self.lb) - 1.0

    def from_unit(self, p: np.ndarray, out: np.ndarray | None = None) -> np.ndarray:
        """Map ``[-1, 1]^D`` to problem coordinates: ``x = lb + (p + 1)/2 (ub - lb)``
        (docs/deviations.md#d-wdo).

        Computed in one array (``out`` when given), with no temporaries of ``p``'s size.
        """
        out = np.add(p, 1.0, out=out, dtype=float)
        out *= 0.5
        out *= self.ub - self.lb
        out += self.lb
        return out


@dataclass(frozen=True)
class Constraint:
    """What one option accepts: its type, and for numbers an interval, for text a choice.

    Read by :func:`check_options` from the field's metadata (see :func:`option`); a field
    declared without :func:`option` gets the check of its annotated type alone.

    Attributes
    ----------
    kind : {"int", "float", "bool", "str", "tuple", ""}
        The value's type; ``""`` takes it from the field's annotation.
    lo, hi : float, optional
        Interval ends (``None``: unbounded on that side).
    lo_open, hi_open : bool
        Whether the end is excluded (real options only; integer ends are inclusive).
    choices : tuple of str, optional
        The accepted words of a text option.
    rule : callable, optional
        ``rule(name, value)`` raising ``ValueError``: a further check of this field alone.
    """

    kind: str = ""
    lo: float | None = None
    hi: float | None = None
    lo_open: bool = False
    hi_open: bool = False
    choices: tuple | None = None
    rule: Callable[[str, Any], None] | None = None

    def check(self, name: str, value, annotated: str = "") -> None:
        """Raise ``ValueError`` (``ArgumentTypeError`` for a wrong type) naming ``name`` unless
        ``value`` satisfies the constraint."""
        kind = self.kind or annotated
        if kind == "int":
            check_int(name, value, self.lo, self.hi)
        elif kind == "float":
            check_real(name, value, self.lo, self.hi, low_open=self.lo_open, high_open=self.hi_open)
        elif kind == "bool":
            check_bool(name, value)
        elif kind == "str":
            if not isinstance(value, str):
                what = type(value).__name__
                raise ArgumentTypeError(f"{name}={value!r} must be a string, not a {what}")
            if self.choices is not None and value not in self.choices:
                raise ValueError(f"{name}={value!r} is not valid; choose one of {self.choices}")
        elif kind == "tuple":
            if not isinstance(value, tuple | list) or isinstance(value, str):
                raise ArgumentTypeError(f"{name}={value!r} must be a tuple of numbers")
            for i, v in enumerate(value):
                check_real(f"{name}[{i}]", v)
        if self.rule is not None:
            self.rule(name, value)


def option(
    default,
    *,
    kind: str = "",
    lo=None,
    hi=None,
    lo_open: bool = False,
    hi_open: bool = False,
    choices=None,
    rule=None,
):
    """A ``Params`` field that declares what it accepts (checked by :func:`check_options`).

    Parameters
    ----------
    default : object
        The field's default (immutable: a number, a string, a bool or a tuple).
    kind, lo, hi, lo_open, hi_open, choices, rule
        See :class:`Constraint`; ``kind`` defaults to the field's annotation.

    Examples
    --------
    ``alpha: float = option(0.4, lo=0, hi=1)`` accepts finite reals in ``[0, 1]``;
    ``velocity: str = option("wdo", choices=("wdo", "awdo"))`` one of two words.
    """
    choices = None if choices is None else tuple(choices)
    rule_ = Constraint(kind, lo, hi, lo_open, hi_open, choices, rule)
    return dataclasses.field(default=default, metadata={"option": rule_})


def _annotated(f: dataclasses.Field) -> str:
    t = f.type if isinstance(f.type, str) else getattr(f.type, "__name__", str(f.type))
    return t.split("|")[0].strip()


def check_options(params) -> None:
    """Check every field of a ``Params`` instance against its declared :class:`Constraint`
    (its annotated type when it declares none), in declaration order.

    Called by ``Params.__post_init__`` before the cross-field rules of a subclass, so a
    comparison there never meets NaN, a bool or a string, and a built ``Params`` is valid
    however it was made (registry, optimizer class, ``dataclasses.replace``).
    """
    for f in dataclasses.fields(params):
        f.metadata.get("option", _PLAIN).check(f.name, getattr(params, f.name), _annotated(f))


_PLAIN = Constraint()


@dataclass(frozen=True)
class Params:
    """Base class of every optimizer's coefficients.

    Each field declares its own constraint with :func:`option` (checked by
    :func:`check_options` on construction); a subclass's ``__post_init__`` adds only the
    rules that tie fields together (after calling ``super().__post_init__()``).
    """

    pop_size: int = option(50, lo=2)

    def __post_init__(self) -> None:
        check_options(self)

    def as_dict(self) -> dict[str, Any]:
        """The fields as a new dict (what ``dataclasses.asdict`` gives)."""
        # asdict's recursive deep copy costs ~0.2 ms per result; immutable values need none,
        # and the fields of a frozen instance never change: their dict is made once (kept
        # beside the fields, which equality, hashing and repr do not look at) and copied
        kept = self.__dict__.get("_as_dict")
        if kept is not None:
            return dict(kept)
        out = {f.name: getattr(self, f.name) for f in dataclasses.fields(self)}
        if all(_immutable(v) for v in out.values()):
            object.__setattr__(self, "_as_dict", out)
            return dict(out)
        return dataclasses.asdict(self)


_SCALARS = (int, float, str, bool, type(None), np.integer, np.floating, np.bool_)


def _immutable(v) -> bool:
    """A scalar, or a tuple of scalars: nothing a copy could protect."""
    return isinstance(v, _SCALARS) or (type(v) is tuple and all(isinstance(x, _SCALARS) for x in v))


class Optimizer(ABC):
    """Ask/tell optimizer over a batch of independent runs.

    Subclasses set ``params_class`` and implement ``init``, ``ask`` and ``tell``.
    """

    name: ClassVar[str] = "optimizer"
    params_class: ClassVar[type[Params]] = Params
    per_run_metadata: ClassVar[tuple[str, ...]] = ()
    """Keys of ``metadata`` that hold one entry per run (joined when runs go in blocks)."""
    sequential: ClassVar[bool] = False
    """True when ``ask`` gives one candidate per run, each depending on the value of the last
    (an iteration is then one evaluation, not ``pop_size``): budgets set in iterations mean
    ``pop_size`` times fewer evaluations for such an algorithm."""
    shrinking: ClassVar[bool] = False
    """True when the population shrinks during a run (L-SHADE's population size reduction): an
    iteration then evaluates between ``pop_size`` and 4 candidates per run."""

    def __init__(self, params: Params | None = None, name: str | None = None, **options) -> None:
        if name is not None:
            self.name = name  # before the params, so option errors name the registered entry
        if params is None:
            params = make_params(self.params_class, options, self.name)
        elif options:
            params = dataclasses.replace(params, **options)
        self.params = params
        self.metadata: dict[str, Any] = {}

    @abstractmethod
    def init(self, space: Space, streams: RunStreams, max_iter: int, x0=None):
        """Create the state of ``streams.runs`` runs.

        ``max_iter`` feeds iteration schedules; ``x0`` (problem coordinates, ``(k, D)`` or
        ``(R, k, D)``) seeds the first ``k`` members of the initial population (warm start).
        """

    def horizon(self, budget, dim: int) -> int:
        """What :meth:`init` gets as ``max_iter`` from the driver for ``budget`` (a
        :class:`mawdo.budget.Budget`) in dimension ``dim``: the iterations its schedules run
        over, :meth:`~mawdo.budget.Budget.horizon`. An optimizer whose schedules run on
        evaluations (L-SHADE) returns the evaluation budget it plans instead."""
        return budget.horizon(self.params.pop_size)

    @abstractmethod
    def ask(self, state) -> np.ndarray:
        """Candidates to evaluate next, shape ``(R, n, D)`` in problem coordinates."""

    @abstractmethod
    def tell(self, state, X: np.ndarray, F: np.ndarray):
        """Take the values ``F`` (``(R, n)``) of the candidates ``X`` and return the new state."""

    def __repr__(self) -> str:
        return f"{type(self).__name__}({self.name!r}, {self.params})"


def initial_population(streams: RunStreams, n: int, low, high, x0=None) -> np.ndarray:
    """``n`` points per run, uniform in ``[low, high]``, the first ones replaced by ``x0``.

    Parameters
    ----------
    streams : RunStreams
        One generator per run; the uniform draw is made whether or not ``x0`` is given, so a warm
        start does not shift the rest of the run's random numbers.
    n : int
        Population size.
    low, high : float or numpy.ndarray
        Box of the optimizer's own coordinates, broadcastable to ``(D,)``.
    x0 : numpy.ndarray, optional
        Seed points in the same coordinates, ``(k, D)`` (shared by every run) or ``(R, k, D)``,
        ``k <= n``; clipped into the box.
    """
    D = np.broadcast_shapes(np.shape(low), np.shape(high))[-1]
    pop = streams.uniform(low, high, (n, D))
    if x0 is not None:
        x0 = as_x0(x0, streams.runs, D, n)
        pop[:, : x0.shape[1]] = np.clip(x0, low, high)
    return pop


def as_x0(x0, runs: int, D: int, n: int) -> np.ndarray:
    """Validate warm-start points and return them as ``(runs, k, D)``."""
    x0 = np.asarray(x0, dtype=float)
    if x0.ndim == 2:
        x0 = np.broadcast_to(x0, (runs, *x0.shape))
    if x0.ndim != 3 or x0.shape[0] != runs or x0.shape[2] != D:
        raise ValueError(f"x0 must have shape (k, {D}) or ({runs}, k, {D}); got {x0.shape}")
    if x0.shape[1] > n:
        raise ValueError(f"x0 has {x0.shape[1]} points but pop_size is {n}")
    if not np.all(np.isfinite(x0)):
        raise ValueError("x0 must be finite")
    return x0


def make_params(cls: type[Params], options: dict, algorithm: str) -> Params:
    """Build ``cls(**options)``, naming unknown options and suggesting the valid ones."""
    import difflib

    names = [f.name for f in dataclasses.fields(cls)]
    for key in options:
        if key not in names:
            close = difflib.get_close_matches(key, names, n=2)
            hint = f" Did you mean {', '.join(map(repr, close))}?" if close else ""
            raise ValueError(
                f"{algorithm} has no option {key!r}.{hint} Its options are: {', '.join(names)}"
            )
    return cls(**options)


def ranks(F: np.ndarray) -> np.ndarray:
    """1-based fitness ranks along the last axis (1 = best; ties broken by index, stable)."""
    order = np.argsort(F, axis=-1, kind="stable")
    r = np.empty_like(order)
    np.put_along_axis(r, order, np.arange(1, F.shape[-1] + 1), axis=-1)
    return r


def finite_last(F: np.ndarray) -> np.ndarray:
    """Fitness ``F`` (..., N) with NaN and infinities replaced by a finite value worse than every
    finite one of their row (``1`` where a row has none), for CMA-ES updates that rank by value.

    The replacement is ``worst + 1 + |worst|``: strictly above ``worst`` even where ``worst + 1``
    rounds back to ``worst`` (``|worst|`` above 2**53). ``F`` is returned as is when all finite.
    """
    finite = np.isfinite(F)
    if finite.all():
        return F
    worst = np.where(finite, F, -np.inf).max(axis=-1, keepdims=True)
    some = np.isfinite(worst)
    worst = np.where(some, worst, 0.0)
    return np.where(finite, F, np.where(some, worst + 1.0 + np.abs(worst), 1.0))
