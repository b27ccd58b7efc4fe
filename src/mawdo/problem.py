"""The objective wrapper: the one place that calls user code and counts evaluations.

Optimizers never call the objective themselves (docs/deviations.md#d-evaluator): the driver hands
each batch of
candidates ``(R, n, D)`` to an :class:`Evaluator`, which calls the objective once on all ``R*n``
rows, counts ``nfev`` per run, maps NaN/inf to +inf ("worst"), and turns bad output shapes and
exceptions into errors that name the algorithm, run and iteration.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np
from numba import njit

from mawdo.streams import RunStreams
from mawdo.util.validate import check_int, real_array


class ObjectiveError(RuntimeError):
    """The objective raised or returned something unusable."""


_LB_UB_FIX = (
    "pass lb=..., ub=... (arrays or scalars) or scipy.optimize.Bounds(lb, ub); "
    "bounds= takes (low, high) pairs, e.g. bounds=list(zip(lb, ub))"
)


def as_bounds(
    bounds=None, dim: int | None = None, *, lb=None, ub=None
) -> tuple[np.ndarray, np.ndarray]:
    """Validate box bounds and return ``(lb, ub)`` as float arrays of shape ``(D,)``.

    Each form has one reading, whatever ``D`` is:

    - ``bounds=[(low, high), ...]`` (or a ``(D, 2)`` array): one pair per coordinate, as in
      ``scipy.optimize.minimize``;
    - ``bounds=(low, high)`` of two scalars with ``dim=D``: the same pair for every coordinate;
    - ``bounds=scipy.optimize.Bounds(lb, ub)`` (any object with ``lb`` and ``ub``), or the
      keywords ``lb=``, ``ub=``: lower and upper arrays (a scalar broadcasts).

    A pair of arrays ``(lb_array, ub_array)`` is refused: for ``D = 2`` it cannot be told from
    two ``(low, high)`` pairs, so it once silently became a different box.

    Parameters
    ----------
    bounds : sequence of (low, high) pairs, (low, high) scalars, or scipy.optimize.Bounds
        See above. ``None`` when ``lb`` and ``ub`` are given.
    dim : int, optional
        Expected dimension D >= 1; required when neither form fixes it (scalar bounds).
    lb, ub : float or array_like, optional
        Lower and upper bounds, shape ``(D,)`` or scalars; only without ``bounds``.

    Raises
    ------
    ValueError
        Ambiguous or malformed bounds, mismatched lengths, no coordinates, non-finite values, or
        ``lb >= ub`` in any coordinate.
    """
    if dim is not None:
        check_int("dim", dim, 1)
    if lb is not None or ub is not None:
        if bounds is not None:
            raise ValueError("give either bounds= or lb=/ub=, not both")
        if lb is None or ub is None:
            raise ValueError("lb= and ub= go together: give both (scalars broadcast with dim=D)")
        lo, hi = _lb_ub(lb, ub, dim, "lb", "ub")
    elif bounds is None:
        raise ValueError(
            "bounds are required for a callable objective: pass bounds=[(lo, hi)] * D "
            "or lb=..., ub=..."
        )
    elif hasattr(bounds, "lb") and hasattr(bounds, "ub"):
        lo, hi = bounds.lb, bounds.ub
        if dim is not None and np.size(lo) == 1 and np.size(hi) == 1:
            # scipy stores Bounds(-1, 2) as 1-element arrays and broadcasts them; so do we
            lo, hi = np.reshape(lo, ()), np.reshape(hi, ())
        lo, hi = _lb_ub(lo, hi, dim, "Bounds.lb", "Bounds.ub")
    else:
        lo, hi = _pairs(bounds, dim)
    return _check_box(lo, hi, dim)


def _pairs(bounds, dim: int | None) -> tuple[np.ndarray, np.ndarray]:
    if (
        isinstance(bounds, list | tuple)
        and len(bounds) == 2
        and all(isinstance(b, np.ndarray) and b.ndim == 1 for b in bounds)
    ):
        raise ValueError(
            "bounds=(lb_array, ub_array) is ambiguous (with D = 2 it reads as two (low, high) "
            f"pairs) and is not accepted: {_LB_UB_FIX}; write pairs as tuples, [(lo, hi), ...]"
        )
    arr = real_array("bounds", bounds)
    if arr.shape == (2,):
        if dim is None:
            raise ValueError(
                "bounds=(lo, hi) is one pair; give dim=D too, or pass bounds=[(lo, hi)] * D"
            )
        return np.full(dim, arr[0]), np.full(dim, arr[1])
    if arr.ndim == 2 and arr.shape[1] == 2:
        return arr[:, 0].copy(), arr[:, 1].copy()
    if arr.ndim == 2 and arr.shape[0] == 2:
        raise ValueError(
            f"bounds has shape {arr.shape}, which looks like (lb, ub) arrays; {_LB_UB_FIX}"
        )
    raise ValueError(
        f"bounds must be a sequence of (low, high) pairs, shape (D, 2); got an array of shape "
        f"{arr.shape}. For lower and upper arrays, {_LB_UB_FIX}"
    )


def _lb_ub(lb, ub, dim, lb_name: str, ub_name: str) -> tuple[np.ndarray, np.ndarray]:
    lo, hi = real_array(lb_name, lb), real_array(ub_name, ub)
    for name, a in ((lb_name, lo), (ub_name, hi)):
        if a.ndim > 1:
            raise ValueError(f"{name} must be a scalar or a 1-D array; got shape {a.shape}")
    sizes = {a.shape[0] for a in (lo, hi) if a.ndim == 1}
    if len(sizes) > 1:
        raise ValueError(f"{lb_name} has {lo.shape[0]} coordinates but {ub_name} has {hi.shape[0]}")
    n = sizes.pop() if sizes else dim
    if n is None:
        raise ValueError(f"{lb_name} and {ub_name} are scalars; give dim=D too")
    return np.broadcast_to(lo, (n,)).copy(), np.broadcast_to(hi, (n,)).copy()


def _check_box(lb: np.ndarray, ub: np.ndarray, dim: int | None) -> tuple[np.ndarray, np.ndarray]:
    if lb.shape[0] == 0:
        raise ValueError("bounds have no coordinates; the box needs D >= 1 (low, high) pairs")
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
    pure : bool
        ``fun`` never writes into its argument (our benchmark functions; a contract test
        checks every one), so the evaluator passes it the candidates without a defensive copy.
        Leave False for a user's objective.
    """

    fun: Callable
    lb: np.ndarray
    ub: np.ndarray
    vectorized: bool = True
    noise: bool = False
    name: str = "objective"
    f_star: float | None = None
    x_star: np.ndarray | None = field(default=None, repr=False)
    pure: bool = False

    @property
    def dim(self) -> int:
        return int(self.lb.shape[0])

    def __call__(self, X: np.ndarray) -> np.ndarray:
        """Evaluate rows of ``X`` (``(n, D)``) and return the raw values, shape ``(n,)``."""
        if self.vectorized:
            out = self.fun(X)
        else:
            out = [self.fun(x) for x in X]
        if type(out) is not np.ndarray or out.dtype != np.float64:  # the usual output passes
            out = self._as_real(out)
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

    def _as_real(self, out) -> np.ndarray:
        """The objective's values as floats; complex, string and bool output is an error, since
        ``np.asarray(..., dtype=float)`` would drop an imaginary part or parse ``"1.5"``."""
        try:
            return real_array("values", out)
        except (TypeError, ValueError) as exc:
            if "complex" in str(exc):
                fix = "minimisation needs real values: return e.g. abs(z), or z.real if exact"
                raise ObjectiveError(
                    f"objective {self.name!r} returned complex values; {fix}"
                ) from exc
            raise ObjectiveError(
                f"objective {self.name!r} returned values that are not numbers ({exc}); "
                f"return floats"
            ) from exc


@njit(cache=True, nogil=True)
def store_values(vals, F, nfev, active):  # pragma: no cover - compiled
    """``F[:, :m] = vals`` with NaN and +-inf as +inf, ``F[:, m:] = +inf``; ``nfev[active] += m``.

    One pass instead of NumPy's copy, fill, ``isfinite`` and masked adds (about 10 us an
    iteration, a tenth of an ``ioh`` call on 500 points).

    Parameters
    ----------
    vals : float64 (R, m)
        The objective's values of the first ``m`` candidates of each run.
    F : float64 (R, n), n >= m
        Written.
    nfev : int64 (R,)
        Evaluations per run; ``m`` is added where ``active``.
    active : bool (R,)
    """
    R, m = vals.shape
    n = F.shape[1]
    for r in range(R):
        for j in range(m):
            v = vals[r, j]
            F[r, j] = v if -np.inf < v < np.inf else np.inf
        for j in range(m, n):
            F[r, j] = np.inf
        if active[r]:
            nfev[r] += m


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
        if m == 0:
            return np.full((R, n), np.inf)
        # A copy: an objective that writes into its argument must not move the candidates the
        # optimizer keeps (and the driver returns) out of the box. Our own functions do not
        # write (Problem.pure), and skip the copy: one (R, N, D) array less per iteration.
        flat = X[:, :m].reshape(R * m, D)
        if not self.problem.pure:
            flat = flat.copy()
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
        # F is the driver's own array (never the objective's, which it may reuse or keep)
        F = np.empty((R, n))
        store_values(vals, F, self.nfev, active)
        return F

    def _failing_run(self, X: np.ndarray) -> int | None:
        for r in range(X.shape[0]):
            try:
                self.problem(X[r].copy())
            except Exception:
                return r
        return None


# A box wider than this (in any coordinate) is searched in coordinates divided by a power of two:
# optimizers compute widths, centres and steps from ``ub - lb``, which overflows to inf for
# bounds such as (-1e308, 1e308); 2**1000 (about 1e301) leaves room for their arithmetic.
_WIDEST = 2.0**1000


def box_scale(lb: np.ndarray, ub: np.ndarray) -> float:
    """The power of two ``s`` (1.0 for every box narrower than about 1e301) such that the box
    ``[lb / s, ub / s]`` has a finite width with room to spare.

    Dividing and multiplying by a power of two is exact for normal floats, so the optimizer may
    work on ``[lb / s, ub / s]`` and its candidates ``X`` map back to ``X * s`` in the box.
    """
    s = 1.0
    with np.errstate(over="ignore"):  # the overflowing width is the question asked
        while not np.all(ub / s - lb / s <= _WIDEST):
            s *= 2.0
    return s


def check_x0(x0, runs: int, lb: np.ndarray, ub: np.ndarray) -> np.ndarray | None:
    """Validate warm-start points: shape ``(k, D)`` (shared by every run) or ``(runs, k, D)``,
    finite, and inside the box ``[lb, ub]`` (a point outside is an error, not silently clipped).

    Parameters
    ----------
    x0 : array_like or None
        The warm start given to :func:`mawdo.minimize`.
    runs : int
        Runs of the batch.
    lb, ub : numpy.ndarray
        The box, shape ``(D,)``.

    Returns
    -------
    numpy.ndarray or None
        ``x0`` as a float array (``None`` stays ``None``).
    """
    if x0 is None:
        return None
    x0 = real_array("x0", x0)
    D = lb.shape[0]
    shapes = f"(k, {D}) shared by every run or (runs, k, {D}) = ({runs}, k, {D}) per run"
    if x0.ndim not in (2, 3) or x0.shape[-1] != D:
        raise ValueError(f"x0 must have shape {shapes}; got shape {x0.shape}")
    if x0.ndim == 3 and x0.shape[0] != runs:
        raise ValueError(
            f"x0 has shape {x0.shape}: {x0.shape[0]} per-run sets of points for runs={runs}; "
            f"give shape {shapes}"
        )
    if not np.all(np.isfinite(x0)):
        raise ValueError("x0 must be finite (no NaN or inf)")
    outside = (x0 < lb) | (x0 > ub)
    if outside.any():
        idx = tuple(int(i) for i in np.argwhere(outside)[0])
        j = idx[-1]
        raise ValueError(
            f"x0[{', '.join(map(str, idx))}] = {float(x0[idx])!r} lies outside the box: "
            f"coordinate {j} must be in [{float(lb[j])!r}, {float(ub[j])!r}] "
            f"({int(outside.sum())} values of x0 are outside); warm-start points must lie in "
            "the bounds, use np.clip(x0, lb, ub) if clipping is what you mean"
        )
    return x0
