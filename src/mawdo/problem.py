"""The objective wrapper: the one place that calls user code and counts evaluations.

Optimizers never call the objective themselves (SPEC 1): the driver hands each batch of
candidates ``(R, n, D)`` to an :class:`Evaluator`, which calls the objective once on all ``R*n``
rows, counts ``nfev`` per run, maps NaN/inf to +inf ("worst"), and turns bad output shapes and
exceptions into errors that name the algorithm, run and iteration.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np

from mawdo.streams import RunStreams


class ObjectiveError(RuntimeError):
    """The objective raised or returned something unusable."""


def as_bounds(bounds, dim: int | None = None) -> tuple[np.ndarray, np.ndarray]:
    """Validate box bounds and return ``(lb, ub)`` as float arrays of shape ``(D,)``.

    Parameters
    ----------
    bounds : sequence of (low, high) pairs, or a pair of arrays ``(lb, ub)``
        ``[(-5, 5)] * 10`` and ``(np.full(10, -5), np.full(10, 5))`` are both accepted. A single
        pair ``(-5, 5)`` with ``dim`` given is broadcast to ``dim`` coordinates.
    dim : int, optional
        Expected dimension; required when ``bounds`` is a single pair.

    Raises
    ------
    ValueError
        Mismatched lengths, non-finite values, or ``lb >= ub`` in any coordinate.
    """
    if bounds is None:
        raise ValueError("bounds are required for a callable objective: pass bounds=[(lo, hi)] * D")
    arr = np.asarray(bounds, dtype=float)
    if arr.ndim == 1 and arr.shape == (2,):
        if dim is None:
            raise ValueError(
                "bounds=(lo, hi) is one pair; give dim=D too, or pass bounds=[(lo, hi)] * D"
            )
        lb, ub = np.full(dim, arr[0]), np.full(dim, arr[1])
    elif arr.ndim == 2 and arr.shape[1] == 2 and arr.shape[0] != 2:
        lb, ub = arr[:, 0].copy(), arr[:, 1].copy()
    elif arr.ndim == 2 and arr.shape[0] == 2 and arr.shape[1] != 2:
        lb, ub = arr[0].copy(), arr[1].copy()
    elif arr.ndim == 2 and arr.shape == (2, 2):
        # ambiguous only in shape; read as [(lo, hi), (lo, hi)] like scipy.optimize
        lb, ub = arr[:, 0].copy(), arr[:, 1].copy()
    else:
        raise ValueError(
            f"bounds must be a sequence of (low, high) pairs or (lb_array, ub_array); "
            f"got an array of shape {arr.shape}"
        )
    if dim is not None and lb.shape[0] != dim:
        raise ValueError(f"bounds have {lb.shape[0]} coordinates but dim={dim}")
    if not (np.all(np.isfinite(lb)) and np.all(np.isfinite(ub))):
        raise ValueError("bounds must be finite: every coordinate needs a finite (low, high) box")
    bad = np.flatnonzero(lb >= ub)
    if bad.size:
        i = int(bad[0])
        raise ValueError(
            f"bounds must satisfy low < high in every coordinate; coordinate {i} has "
            f"low={float(lb[i])!r} >= high={float(ub[i])!r}"
        )
    return lb, ub


@dataclass
class Problem:
    """A minimisation problem: a vectorised objective on a box.

    Parameters
    ----------
    fun : callable
        ``fun(X) -> f`` with ``X`` of shape ``(n, D)`` and ``f`` of shape ``(n,)`` when
        ``vectorized`` is true; otherwise ``fun(x) -> float`` for one point ``x`` of shape ``(D,)``.
    lb, ub : numpy.ndarray
        Box bounds, shape ``(D,)``, ``lb < ub``.
    vectorized : bool
        Whether ``fun`` takes a batch of points.
    noise : bool
        Add one U[0, 1) draw per evaluation from the run's noise stream (the quartic F6).
    name : str
        For messages and results.
    f_star : float, optional
        Known optimum value, if any (benchmark functions).
    """

    fun: Callable
    lb: np.ndarray
    ub: np.ndarray
    vectorized: bool = True
    noise: bool = False
    name: str = "objective"
    f_star: float | None = None
    x_star: np.ndarray | None = field(default=None, repr=False)

    @property
    def dim(self) -> int:
        return int(self.lb.shape[0])

    def __call__(self, X: np.ndarray) -> np.ndarray:
        """Evaluate rows of ``X`` (``(n, D)``) and return the raw values, shape ``(n,)``."""
        if self.vectorized:
            out = self.fun(X)
        else:
            out = [self.fun(x) for x in X]
        try:
            out = np.asarray(out, dtype=float)
        except (TypeError, ValueError) as exc:
            raise ObjectiveError(
                f"objective {self.name!r} returned values that are not numbers ({exc})"
            ) from exc
        n = X.shape[0]
        if out.shape != (n,):
            if self.vectorized:
                fix = "return one value per row, shape (n,); use vectorized=False for f(x)->float"
            else:
                fix = "return one float per point"
            raise ObjectiveError(
                f"objective {self.name!r} returned shape {out.shape} for {n} points of dimension "
                f"{X.shape[1]}; expected ({n},): {fix}"
            )
        return out


class Evaluator:
    """Counts evaluations per run and calls the problem once per batch.

    Parameters
    ----------
    problem : Problem
    noise_streams : RunStreams
        One noise generator per run (used only when ``problem.noise``).
    algorithm : str
        Named in error messages.
    """

    def __init__(self, problem: Problem, noise_streams: RunStreams, algorithm: str) -> None:
        self.problem = problem
        self.noise_streams = noise_streams
        self.algorithm = algorithm
        self.nfev = np.zeros(noise_streams.runs, dtype=np.int64)

    def __call__(
        self, X: np.ndarray, iteration: int, active: np.ndarray, limit: int | None = None
    ) -> np.ndarray:
        """Evaluate a batch and return ``F`` of shape ``(R, n)`` with non-finite values as +inf.

        Parameters
        ----------
        X : numpy.ndarray
            Candidates, shape ``(R, n, D)``.
        iteration : int
            1-based iteration, for messages.
        active : numpy.ndarray of bool
            Runs still counting evaluations, shape ``(R,)``; inactive runs are still evaluated
            (their optimizer state keeps moving) but not counted.
        limit : int, optional
            Evaluate only the first ``limit`` candidates of each run (an exact ``max_evals``
            budget); the rest get +inf and are not counted.
        """
        R, n, D = X.shape
        m = n if limit is None else max(0, min(n, limit))
        F = np.full((R, n), np.inf)
        if m == 0:
            return F
        flat = X[:, :m].reshape(R * m, D)
        try:
            vals = self.problem(flat).reshape(R, m)
        except ObjectiveError as exc:
            msg = f"{exc} (algorithm {self.algorithm!r}, iteration {iteration})"
            raise ObjectiveError(msg) from exc
        except Exception as exc:  # the user's objective: locate the failing run for the message
            run = self._failing_run(X[:, :m])
            where = f"run {run}, " if run is not None else ""
            raise ObjectiveError(
                f"objective {self.problem.name!r} raised {type(exc).__name__}: {exc} "
                f"(algorithm {self.algorithm!r}, {where}iteration {iteration})"
            ) from exc
        if self.problem.noise:
            vals = vals + self.noise_streams.random((m,))
        vals[~np.isfinite(vals)] = np.inf
        F[:, :m] = vals
        self.nfev += np.where(active, m, 0)
        return F

    def _failing_run(self, X: np.ndarray) -> int | None:
        for r in range(X.shape[0]):
            try:
                self.problem(X[r])
            except Exception:
                return r
        return None
