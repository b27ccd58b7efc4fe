"""The :class:`BenchmarkFunction` record: a pure vectorised formula plus its box and optimum.

A benchmark function is data (name, bounds, optimum, flags) around one pure array formula
``func(X: (n, D)) -> (n,)`` (docs/functions.md#f-table). Calling the record validates shapes and,
for F6, adds the
``U[0,1)`` noise from an explicit generator; ``func`` itself stays noiseless and deterministic.
Variants (another dimension, other bounds, a shifted optimum) are new records, never mutations.
"""

from __future__ import annotations

import dataclasses
import re
from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np

Formula = Callable[[np.ndarray], np.ndarray]
"""A pure vectorised formula: ``X`` of shape ``(n, D)`` -> values of shape ``(n,)``."""

OptimumRule = Callable[[int, np.ndarray, np.ndarray], tuple[np.ndarray, float]]
"""``(dim, lb, ub) -> (x_star, f_star)`` for a scalable function at a given dimension and box."""

_PAPER_ID = re.compile(r"F([1-9]|1[0-6])")


def _as_vector(value, dim: int, what: str, owner: str) -> np.ndarray:
    """``value`` (a scalar or a length-``dim`` sequence) as a read-only float64 ``(dim,)`` array."""
    arr = np.array(value, dtype=float)  # a copy: the record never aliases caller arrays
    if arr.ndim == 0:
        arr = np.full(dim, float(arr))
    if arr.shape != (dim,):
        raise ValueError(
            f"{owner}: {what} must be a scalar or have shape ({dim},); got {arr.shape}"
        )
    arr.setflags(write=False)
    return arr


@dataclass(frozen=True, eq=False, repr=False)
class BenchmarkFunction:
    """A box-constrained benchmark function to be minimised.

    Parameters
    ----------
    name : str
        Canonical registry name, e.g. ``"rastrigin"``; shifted variants end in ``"@shifted"``.
    paper_id : str or None
        ``"F1"`` .. ``"F16"`` for the paper's Table 2 suite, ``None`` for the alternates.
    dim : int
        Dimension ``D >= 1``.
    lb, ub : numpy.ndarray
        Lower and upper box bounds, shape ``(D,)``, ``lb < ub`` elementwise (a scalar is
        broadcast). Stored as read-only copies.
    f_star : float
        Global minimum value over the box (for the noiseless formula).
    x_star : numpy.ndarray
        One global minimiser, shape ``(D,)``, inside the box; ``func(x_star) == f_star``.
    func : callable
        The pure, vectorised, noiseless formula ``(n, D) -> (n,)``. Must be picklable (a
        module-level function or a ``functools.partial`` of one) so runs can go to worker
        processes. Its sums follow numpy's memory-layout-dependent order; calling the record
        passes a C-ordered array, so values are bit-identical whatever the caller's layout.
    multimodal : bool
        Whether the function has more than one local minimum.
    scalable : bool
        Whether the dimension can be changed with :meth:`with_dim`; requires ``optimum``.
    description : str
        One-line formula and source.
    noise : bool, default False
        Add one ``U[0,1)`` draw per evaluated point (paper F6 only). The draw is taken from the
        ``rng`` passed to :meth:`__call__`, which is then required.
    min_dim : int, default 1
        Smallest dimension the formula is defined for (2 for formulas over pairs ``x_i, x_{i+1}``).
    optimum : callable or None, default None
        ``(dim, lb, ub) -> (x_star, f_star)``; used by :meth:`with_dim` and :meth:`with_bounds`
        to place the optimum of a scalable function.

    Notes
    -----
    Records compare by identity (``eq=False``): arrays make value equality ambiguous.
    ``func`` and ``optimum`` are excluded from the repr.
    """

    name: str
    paper_id: str | None
    dim: int
    lb: np.ndarray
    ub: np.ndarray
    f_star: float
    x_star: np.ndarray
    func: Formula = field(repr=False)
    multimodal: bool = False
    scalable: bool = False
    description: str = ""
    noise: bool = False
    min_dim: int = field(default=1, repr=False)
    optimum: OptimumRule | None = field(default=None, repr=False)

    def __post_init__(self) -> None:
        owner = f"function {self.name!r}"
        if isinstance(self.dim, bool) or not isinstance(self.dim, int | np.integer):
            raise TypeError(f"{owner}: dim must be an int, got {type(self.dim).__name__}")
        if self.dim < max(1, self.min_dim):
            raise ValueError(f"{owner}: dim must be >= {max(1, self.min_dim)}, got {self.dim}")
        object.__setattr__(self, "dim", int(self.dim))
        if self.paper_id is not None and not _PAPER_ID.fullmatch(self.paper_id):
            raise ValueError(
                f"{owner}: paper_id must be 'F1'..'F16' or None, got {self.paper_id!r}"
            )
        lb = _as_vector(self.lb, self.dim, "lb", owner)
        ub = _as_vector(self.ub, self.dim, "ub", owner)
        if not (np.all(np.isfinite(lb)) and np.all(np.isfinite(ub)) and np.all(lb < ub)):
            raise ValueError(f"{owner}: bounds must be finite with lb < ub; got lb={lb}, ub={ub}")
        x_star = _as_vector(self.x_star, self.dim, "x_star", owner)
        if not np.all((lb <= x_star) & (x_star <= ub)):
            raise ValueError(f"{owner}: x_star {x_star} lies outside the box [{lb}, {ub}]")
        f_star = float(self.f_star)
        if not np.isfinite(f_star):
            raise ValueError(f"{owner}: f_star must be finite, got {f_star}")
        if not callable(self.func):
            raise TypeError(f"{owner}: func must be callable")
        if self.scalable and self.optimum is None:
            raise ValueError(f"{owner}: a scalable function needs an optimum rule")
        object.__setattr__(self, "lb", lb)
        object.__setattr__(self, "ub", ub)
        object.__setattr__(self, "x_star", x_star)
        object.__setattr__(self, "f_star", f_star)

    def __repr__(self) -> str:
        if np.ptp(self.lb) == 0 and np.ptp(self.ub) == 0:
            box = f"[{self.lb[0]:g}, {self.ub[0]:g}]^{self.dim}"
        else:
            box = f"lb={self.lb.tolist()}, ub={self.ub.tolist()}"
        pid = f" ({self.paper_id})" if self.paper_id else ""
        noise = " + U[0,1) noise" if self.noise else ""
        return (
            f"<BenchmarkFunction {self.name}{pid}: D={self.dim}, {box}, f*={self.f_star!r}{noise}>"
        )

    @property
    def bounds(self) -> tuple[np.ndarray, np.ndarray]:
        """The box as ``(lb, ub)``, each a read-only ``(D,)`` array."""
        return self.lb, self.ub

    def __call__(self, X, rng: np.random.Generator | None = None):
        """Evaluate the function at one point or a batch of points.

        Parameters
        ----------
        X : array_like
            One point, shape ``(D,)``, or ``n`` points, shape ``(n, D)``. Points outside the box
            are evaluated by the same formula (the box is the optimiser's business).
        rng : numpy.random.Generator, optional
            Source of the additive ``U[0,1)`` noise; required when ``self.noise`` is true (one
            ``rng.random(n)`` call per evaluation, one draw per point) and ignored otherwise.

        Returns
        -------
        numpy.float64 or numpy.ndarray
            A scalar for a ``(D,)`` input, else an ``(n,)`` array of float64.

        Raises
        ------
        ValueError
            If ``X`` is not ``(D,)`` or ``(n, D)``, or if noise is on and ``rng`` is missing.
        """
        X = np.asarray(X, dtype=float)
        if X.ndim not in (1, 2) or X.shape[-1] != self.dim:
            raise ValueError(
                f"{self.name} expects points of shape ({self.dim},) or (n, {self.dim}); "
                f"got an array of shape {X.shape}"
            )
        # C order: numpy's sums run in a layout-dependent order, so a Fortran-ordered or strided
        # batch could differ in the last bit from the same points evaluated row by row.
        X = np.ascontiguousarray(X)
        single = X.ndim == 1
        batch = X[None, :] if single else X
        values = np.asarray(self.func(batch), dtype=float)
        if self.noise:
            if not isinstance(rng, np.random.Generator):
                raise ValueError(
                    f"{self.name} is noisy (additive U[0,1) per evaluation): pass an explicit "
                    "generator, rng=np.random.default_rng(seed); "
                    f"got rng={type(rng).__name__ if rng is not None else None}"
                )
            values = values + rng.random(batch.shape[0])
        return values[0] if single else values

    def with_dim(self, dim: int) -> BenchmarkFunction:
        """The same function in another dimension (scalable functions only).

        Parameters
        ----------
        dim : int
            New dimension, ``>= min_dim``. Bounds must be uniform (the same interval on every
            axis); that interval is kept.

        Returns
        -------
        BenchmarkFunction
            A new record with ``(dim,)`` bounds, ``x_star`` and the matching ``f_star``.

        Raises
        ------
        ValueError
            For a fixed-dimension function (unless ``dim`` equals its dimension), for
            ``dim < min_dim``, or for non-uniform bounds.
        """
        if isinstance(dim, bool) or not isinstance(dim, int | np.integer):
            raise TypeError(f"dim must be an int, got {type(dim).__name__}")
        dim = int(dim)
        if dim == self.dim:
            return self
        if not self.scalable or self.optimum is None:
            raise ValueError(
                f"{self.name} has a fixed dimension {self.dim}; cannot change it to {dim}"
            )
        if dim < max(1, self.min_dim):
            raise ValueError(f"{self.name} needs dim >= {max(1, self.min_dim)}, got {dim}")
        if np.ptp(self.lb) != 0 or np.ptp(self.ub) != 0:
            raise ValueError(f"{self.name}: with_dim needs the same bounds on every axis")
        lb, ub = np.full(dim, self.lb[0]), np.full(dim, self.ub[0])
        x_star, f_star = self.optimum(dim, lb, ub)
        return dataclasses.replace(self, dim=dim, lb=lb, ub=ub, x_star=x_star, f_star=f_star)

    def with_bounds(self, lb, ub) -> BenchmarkFunction:
        """The same function on another box.

        Parameters
        ----------
        lb, ub : float or array_like
            New lower and upper bounds, scalars or shape ``(D,)``, ``lb < ub``.

        Returns
        -------
        BenchmarkFunction
            A new record. A scalable function re-places its optimum with its optimum rule; any
            other keeps ``x_star``/``f_star``, which must lie inside the new box.

        Raises
        ------
        ValueError
            If the bounds are malformed or the optimum is not inside the new box.
        """
        owner = f"function {self.name!r}"
        lb = _as_vector(lb, self.dim, "lb", owner)
        ub = _as_vector(ub, self.dim, "ub", owner)
        x_star, f_star = self.x_star, self.f_star
        if self.optimum is not None:
            if not np.all(lb < ub):
                raise ValueError(f"{owner}: bounds must satisfy lb < ub; got lb={lb}, ub={ub}")
            x_star, f_star = self.optimum(self.dim, lb, ub)
        return dataclasses.replace(self, lb=lb, ub=ub, x_star=x_star, f_star=f_star)
