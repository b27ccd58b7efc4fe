"""WDO+: a WDO-family variant designed on BBOB (docs/algorithms.md#wdo-plus).

WDO's velocity (Bayraktar et al. 2013, Eq. 1) with five changes, each a switch:

1. **gravity toward a moving reference** (``centre``): ``-g (p - m)`` with ``m`` the mean of the
   run's personal bests (``"mean"``) or the global best (``"best"``) instead of WDO's box
   centre (``"origin"``), which drags every run toward the middle of the box;
2. **random pressure weights** (``random_pressure``): each coordinate's pull toward ``tbest``
   is weighed by its own ``w ~ U[0, 1)``, so the pull is no longer the same straight line for
   every coordinate;
3. **success-adapted noise** (``adapt``): a velocity term ``sigma_r xi``, ``xi`` of unit
   variance per coordinate, whose step ``sigma_r`` each run adapts by the 1/5-th success rule
   on the fraction ``s`` of parcels that improved their personal best::

       sigma <- min(vmax, sigma exp((s - success_target) / ((1 - success_target) damp)))

4. **restarts** (``restart``): a run whose best has not improved for ``stall`` iterations, or
   whose ``sigma`` fell below ``sigma_min``, redraws its population uniformly in the box (same
   size: the runs of a batch share one candidate count, docs/deviations.md#d-wdo-plus);
5. **midpoint bounds** (``boundary``): a coordinate that would leave the box lands halfway
   between its old value and the bound, instead of being clipped onto it.

Per parcel ``i`` of rank ``r_i`` (1 = best), in ``[-1, 1]^D``::

    u' = clamp((1 - alpha) u - g (p - m) + |1 - 1/r_i| RT w (tbest - p) + c u[perm] / r_i
               + sigma xi,  -vmax, vmax)
    p' = p + u'   (then the boundary rule)

With ``centre="origin"``, ``random_pressure=False``, ``adapt=False, sigma0=0``,
``restart=False`` and ``boundary="clip"`` the move is WDO's (tests/optimizers/test_wdo_plus.py
checks it against ``wdo``'s kernel). Every draw comes from the run's own stream, so a run is
the same alone or in any batch.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from mawdo.optimizers.base import Optimizer, Params, Space, as_x0, initial_population, option
from mawdo.optimizers.kernels import seed_xoshiro, segment_ranks
from mawdo.optimizers.wdo import group_starts
from mawdo.optimizers.wdo_plus_kernel import BOUNDS, CENTRES, plus_step, plus_tell
from mawdo.streams import RunStreams
from mawdo.util import libm


@dataclass(frozen=True)
class WDOPlusParams(Params):
    """Coefficients and switches of WDO+ (defaults: the variant as registered).

    Parameters
    ----------
    pop_size : int
        Air parcels per run, >= 2 (20).
    alpha, g, RT, c : float
        WDO's friction, gravity, pressure and Coriolis coefficients (0.4, 0.2, 3, 0.4).
    vmax : float
        Velocity clamp in normalised units, > 0 (0.3).
    centre : {"origin", "mean", "best"}
        Gravity reference (change 1).
    random_pressure : bool
        Weigh each coordinate's pressure term by its own ``U[0, 1)`` draw (change 2).
    adapt : bool
        Adapt each run's noise step by the success rule (change 3); when false ``sigma``
        stays ``sigma0`` (0 gives WDO's noiseless move).
    sigma0 : float
        Initial noise step, normalised units, in [0, vmax] (0.05).
    success_target, damp : float
        Success-rule target rate in (0, 1) (0.2) and damping > 0 (1).
    restart : bool
        Restart stalled runs (change 4).
    stall : int
        Iterations without improvement of the run's best before a restart, >= 1 (60).
    sigma_min : float
        Restart when the noise step falls below this, >= 0 (1e-9).
    boundary : {"clip", "midpoint"}
        Boundary rule (change 5).
    """

    pop_size: int = option(20, lo=2)
    alpha: float = option(0.4, lo=0, hi=1)
    g: float = option(0.2, lo=0)
    RT: float = option(3.0, lo=0)
    c: float = option(0.4, lo=0)
    vmax: float = option(0.3, lo=0, lo_open=True)
    centre: str = option("mean", choices=CENTRES)
    random_pressure: bool = True
    adapt: bool = True
    sigma0: float = option(0.05, lo=0)
    success_target: float = option(0.2, lo=0, hi=1, lo_open=True, hi_open=True)
    damp: float = option(1.0, lo=0, lo_open=True)
    restart: bool = True
    stall: int = option(60, lo=1)
    sigma_min: float = option(1e-9, lo=0)
    boundary: str = option("midpoint", choices=BOUNDS)

    def __post_init__(self) -> None:
        super().__post_init__()
        if self.sigma0 > self.vmax:
            raise ValueError(f"sigma0={self.sigma0!r} must not exceed vmax={self.vmax!r}")
        if self.adapt and self.sigma0 == 0:
            # the rule multiplies sigma: from 0 it stays 0, below sigma_min, a restart each step
            raise ValueError("sigma0=0 cannot adapt: give sigma0 > 0, or adapt=False for no noise")


@dataclass
class WDOPlusState:
    """Arrays of ``R`` runs in normalised space (``p, u, pbest`` are ``(R, N, D)``)."""

    p: np.ndarray
    u: np.ndarray
    f: np.ndarray  # current values (R, N)
    pbest: np.ndarray
    pbest_f: np.ndarray
    sigma: np.ndarray  # (R,) noise step
    best: np.ndarray  # (R,) best pbest_f since the last (re)start
    stall: np.ndarray  # (R,) iterations since ``best`` last improved
    hold: np.ndarray  # (R,) bool: population just drawn, to be evaluated unmoved
    restarts: np.ndarray  # (R,) restarts so far
    t: int
    space: Space
    streams: RunStreams
    gain: np.ndarray  # (N + 1,) success_gain of k/N improved parcels; empty: no adaptation
    rng: np.ndarray | None = None  # (R, 4) xoshiro256** state per run


_NO_PERM = np.zeros((1, 1, 1), np.int16)
_NO_DRAWS = np.zeros((1, 1, 1))
_NO_RNG = np.ones((1, 4), np.uint64)


def success_sigma(sigma, success, target, damp, vmax):
    """The 1/5-th success rule (Rechenberg; Kern et al. 2004's exponential form)::

        sigma * exp((success - target) / ((1 - target) damp)),  clamped to [0, vmax]

    ``success`` ``(R,)`` is the fraction of parcels in ``[0, 1]`` that improved their
    personal best this iteration; returns a new ``(R,)`` array.
    """
    return np.minimum(sigma * success_gain(success, target, damp), vmax)


def success_gain(success, target, damp):
    """The success rule's factor ``exp((success - target) / ((1 - target) damp))`` (the C
    library's ``exp``, :mod:`mawdo.util.libm`); the kernel reads it from a table over the
    ``N + 1`` possible fractions ``k/N``."""
    return libm.exp((success - target) / ((1.0 - target) * damp))


def stalled(best, stall, run_best, limit, sigma, sigma_min):
    """Restart test: ``(best, stall, mask)`` after one iteration.

    ``run_best`` ``(R,)`` is each run's least personal best now; ``best`` improves when
    ``run_best`` is below it by more than ``1e-12 |best|`` (a stall counter reset), else the
    counter grows. ``mask`` marks the runs with ``stall >= limit`` or ``sigma < sigma_min``.
    """
    finite = np.isfinite(best)
    tol = np.where(finite, 1e-12 * np.abs(np.where(finite, best, 0.0)), 0.0)
    better = run_best < best - tol
    stall = np.where(better, 0, stall + 1)
    best = np.minimum(best, run_best)
    return best, stall, (stall >= limit) | (sigma < sigma_min)


class WDOPlus(Optimizer):
    """WDO+ (see the module docstring); one fused Numba pass per iteration."""

    name = "wdo_plus"
    params_class = WDOPlusParams
    per_run_metadata = ("restarts",)

    def init(self, space: Space, streams: RunStreams, max_iter: int, x0=None) -> WDOPlusState:
        P = self.params
        N, D, R = P.pop_size, space.dim, streams.runs
        p0 = None if x0 is None else space.to_unit(as_x0(x0, R, D, N))
        p = initial_population(streams, N, -np.ones(D), np.ones(D), p0)
        return WDOPlusState(
            p=p,
            u=np.zeros((R, N, D)),
            f=np.full((R, N), np.inf),
            pbest=p.copy(),
            pbest_f=np.full((R, N), np.inf),
            sigma=np.full(R, float(P.sigma0)),
            best=np.full(R, np.inf),
            stall=np.zeros(R, np.int64),
            hold=np.ones(R, bool),
            restarts=np.zeros(R, np.int64),
            t=0,
            gain=(
                success_gain(np.arange(N + 1) / N, P.success_target, P.damp)
                if P.adapt
                else np.empty(0)
            ),
            space=space,
            streams=streams,
        )

    def ask(self, state: WDOPlusState) -> np.ndarray:
        """Move every run's parcels (runs in ``hold`` are returned unmoved)."""
        s = state
        P = self.params
        R, N, D = s.p.shape
        if s.hold.all():
            return s.space.from_unit(s.p)
        if hasattr(s.streams, "raw_words"):
            if s.rng is None:
                s.rng = seed_xoshiro(s.streams)
            perm, noise, press, rng = _NO_PERM, _NO_DRAWS, _NO_DRAWS, s.rng
        else:  # stand-in streams (tests): explicit draws, permutations, noise, pressure weights
            perm = s.streams.shuffle_rows(np.empty((R, N, D), np.int16 if D < 2**15 else np.int32))
            noise = (2.0 * s.streams.random((N, D)) - 1.0) * np.sqrt(3.0)
            press = s.streams.random((N, D)) if P.random_pressure else _NO_DRAWS
            rng = _NO_RNG
        rank = np.empty((R, N))
        segment_ranks(s.f, group_starts(N, 1), rank)
        X = np.empty((R, N, D))
        coef = np.array([P.alpha, P.g, P.RT, P.c], float)
        lb = np.asarray(s.space.lb, float)
        width = np.asarray(s.space.ub - s.space.lb, float)
        plus_step(
            s.p, s.u, s.pbest, s.pbest_f, rank, s.sigma, s.hold, coef,
            CENTRES.index(P.centre), float(P.vmax), P.boundary == "midpoint",
            P.random_pressure, perm, noise, press, rng, rng is not _NO_RNG, lb, width, X,
        )  # fmt: skip
        return X

    def tell(self, state: WDOPlusState, X: np.ndarray, F: np.ndarray) -> WDOPlusState:
        """Success rule, personal bests and restart test in one kernel pass (:func:`plus_tell`,
        the numbers of :func:`success_sigma`, ``update_personal_best`` and :func:`stalled`)."""
        s = state
        P = self.params
        mask = np.empty(s.hold.shape, bool)
        # sigma_min < 0 never restarts a run whose sigma does not adapt
        n = plus_tell(
            np.asarray(F, dtype=float), s.p, s.f, s.pbest, s.pbest_f, s.sigma, s.hold,
            s.gain, float(P.vmax), s.best, s.stall, P.stall,
            P.sigma_min if P.adapt else -1.0, P.restart, mask,
        )  # fmt: skip
        s.t += 1
        if n:
            self._restart(s, np.flatnonzero(mask))
        self.metadata["restarts"] = s.restarts.copy()
        return s

    def _restart(self, s: WDOPlusState, idx: np.ndarray) -> None:
        """Redraw the populations of runs ``idx`` uniformly (each from its own stream)."""
        P = self.params
        N, D = s.p.shape[1:]
        fresh = s.streams.subset(idx).uniform(-1.0, 1.0, (N, D))
        s.p[idx] = fresh
        s.pbest[idx] = fresh
        s.u[idx] = 0.0
        s.f[idx] = np.inf
        s.pbest_f[idx] = np.inf
        s.sigma[idx] = P.sigma0
        s.best[idx] = np.inf
        s.stall[idx] = 0
        s.hold[idx] = True
        s.restarts[idx] += 1
