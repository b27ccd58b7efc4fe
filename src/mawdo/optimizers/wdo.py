"""WDO, AWDO and MAWDO as configurations of one implementation.

One iteration (after the population of iteration ``t`` has been evaluated):

1. leaders: ``pbest`` per parcel, ``gbest_g`` = best ``pbest`` of group ``g``, ``tbest`` = best of
   all (the global best-so-far);
2. guidance ``B``: ``tbest`` (WDO/AWDO), ``gbest_g`` (groups only), or the hierarchical mix of
   Eq. 5 with scheduled weights (Eqs. 6-9) and the distance gate (Eqs. 10-11);
3. velocity (WDO Eq. 1 or AWDO Eq. 4), clamped to ``vmax``; position ``p + u`` (Eq. 2);
4. boundary: clip (Eq. 3) or reflect-damp (Eqs. 15-16);
5. every ``restart_every`` iterations the worst ``restart_frac`` parcels restart around ``tbest``
   (PGR, Eqs. 12-13), each also trying its opposite (OBL, Eq. 14).

Low-dimensional stabilisation (D <= ``low_dim``): per-group coefficients (Eqs. 17-20), ``vmax/4``
(Eq. 21) and gravity toward the group centroid (Eqs. 22-23).
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass

import numpy as np

from mawdo.optimizers import wind
from mawdo.optimizers.base import (
    Optimizer,
    Params,
    Space,
    as_x0,
    initial_population,
    option,
)
from mawdo.optimizers.boundary import BOUNDARY_POLICIES, confine_positions
from mawdo.optimizers.kernels import seed_xoshiro, segment_ranks, update_personal_best
from mawdo.optimizers.wind_kernel import wind_step
from mawdo.streams import RunStreams


def _three_weights(name: str, value) -> None:
    if len(value) != 3 or min(value) < 0 or sum(value) <= 0:
        raise ValueError(f"{name}={value!r} must be three non-negative numbers")


@dataclass(frozen=True)
class WindParams(Params):
    """Coefficients and switches of the WDO family (defaults: classic WDO,
    docs/deviations.md#d-wdo).

    Parameters
    ----------
    pop_size : int
        Air parcels per run, >= 2.
    velocity : {"wdo", "awdo"}
        ``"wdo"``: fixed coefficients, pressure weight ``|1 - 1/i|`` (Bayraktar 2013).
        ``"awdo"``: coefficients ``~ U[0, 1]``, pressure and Coriolis divided by the rank (Eq. 4).
    alpha, g, RT, c : float
        Friction, gravity, pressure (RT) and Coriolis coefficients of WDO (0.4, 0.2, 3, 0.4).
    coef_draw : {"iteration", "parcel", "fixed"}
        AWDO: one coefficient draw per iteration (paper) or one per parcel and iteration; or
        ``"fixed"``: no draw, ``alpha, g, RT, c`` as given (a component-study switch; the
        draws' means are 0.5 each).
    gravity_to : {"centre", "mean", "best", "none"}
        Target of the gravity term ``-g (p - target)``: the centre of the normalised box (the
        papers; the group centroid under low-D stabilisation), the mean position of the run's
        population, its best-so-far ``tbest``, or no gravity term. Study switch; the last three
        also replace low-D stabilisation's centroid.
    pressure : {"rank", "flat"}
        ``"rank"``: the pressure and Coriolis weights of ``velocity`` (WDO ``|1 - 1/i| RT``,
        AWDO ``RT/r``; Coriolis ``c/r``). ``"flat"``: rank-free ``RT (B - p) + c u[perm]``
        (study switch).
    vmax : float
        Velocity clamp in normalised units, > 0 (0.3); also the initial velocities' range.
    clamp : bool
        Clamp velocities to ``vmax`` at every step (papers); false: no clamp (study switch).
    groups : int
        Number of contiguous groups G, 1 <= G <= pop_size.
    guidance : {"global", "group", "hierarchical"}
        Target ``B``: global best-so-far, the group's best, or Eq. 5's mix.
    rank_scope : {"population", "group"}
        Ranks ``r_i`` over the whole population or within each group.
    schedule : bool
        Scheduled mixing (Eqs. 6-9); when false, ``weights`` stay fixed.
    weights : tuple of 3 floats
        Fixed ``(w1, w2, w3)`` when ``schedule`` is off.
    gate : bool
        Distance gate on ``w3`` (Eqs. 10-11).
    restart : bool
        Periodic Guided Restart (Eqs. 12-13).
    restart_every : int
        PGR interval K in iterations, >= 1.
    restart_frac : float
        Fraction rho of the population restarted, in (0, 1].
    sigma0, sigma_end : float
        PGR step size at the start and the end of the run, normalised units (> 0).
    obl : bool
        Opposition-based learning for restarted parcels (Eq. 14); needs ``restart``.
    boundary : {"clip", "reflect"}
        Boundary policy; ``eta`` is the reflection damping (0.5).
    low_dim_stabilization : bool
        Enable the low-dimensional mechanisms when D <= ``low_dim``.
    low_dim : int
        Dimension threshold (3).
    hetero_redraw : bool
        Redraw the per-group coefficients every iteration instead of once.
    """

    velocity: str = option("wdo", choices=("wdo", "awdo"))
    alpha: float = option(0.4, lo=0, hi=1)  # friction: u <- (1 - alpha) u + ...
    g: float = option(0.2, lo=0)
    RT: float = option(3.0, lo=0)
    c: float = option(0.4, lo=0)
    coef_draw: str = option("iteration", choices=("iteration", "parcel", "fixed"))
    gravity_to: str = option("centre", choices=("centre", "mean", "best", "none"))
    pressure: str = option("rank", choices=("rank", "flat"))
    vmax: float = option(0.3, lo=0, lo_open=True)
    clamp: bool = True
    groups: int = option(1, lo=1)
    guidance: str = option("global", choices=("global", "group", "hierarchical"))
    rank_scope: str = option("population", choices=("population", "group"))
    schedule: bool = True
    weights: tuple = option((0.6, 0.3, 0.1), rule=_three_weights)
    gate: bool = True
    restart: bool = False
    restart_every: int = option(50, lo=1)
    restart_frac: float = option(0.1, lo=0, hi=1, lo_open=True)
    sigma0: float = option(0.5, lo=0, lo_open=True)
    sigma_end: float = option(0.05, lo=0, lo_open=True)
    obl: bool = False
    boundary: str = option("clip", choices=BOUNDARY_POLICIES)
    eta: float = option(0.5, lo=0, hi=1)
    low_dim_stabilization: bool = False
    low_dim: int = option(3, lo=0)
    hetero_redraw: bool = False

    def __post_init__(self) -> None:
        super().__post_init__()
        if self.groups > self.pop_size:
            raise ValueError(f"groups={self.groups!r} must be an integer in [1, pop_size]")
        if self.obl and not self.restart:
            raise ValueError("obl=True acts on restarted parcels: set restart=True as well")

    @property
    def n_restart(self) -> int:
        return max(1, int(round(self.restart_frac * self.pop_size)))


_NO_PERM = np.zeros((1, 1, 1), np.int16)
_NO_RNG = np.ones((1, 4), np.uint64)
_NO_COEF = np.zeros((1, 1, 4))


@functools.cache
def group_starts(N: int, G: int) -> np.ndarray:
    """Boundaries ``(G + 1,)`` of :func:`wind.partition`'s contiguous groups (cached)."""
    starts = np.zeros(G + 1, np.intp)
    starts[1:] = np.cumsum(np.bincount(wind.partition(N, G), minlength=G))
    starts.flags.writeable = False
    return starts


def _box_arrays(space: Space) -> tuple[np.ndarray, np.ndarray]:
    """``(lb, ub - lb)`` as float arrays for the kernel."""
    return np.asarray(space.lb, float), np.asarray(space.ub - space.lb, float)


@dataclass
class WindState:
    """Arrays of ``R`` runs in normalised space (``p, u, pbest`` are ``(R, N, D)``)."""

    p: np.ndarray
    u: np.ndarray
    f: np.ndarray  # current fitness (R, N)
    pbest: np.ndarray
    pbest_f: np.ndarray
    gid: np.ndarray  # (N,) group index
    coef: np.ndarray | None  # per-group (alpha, g, RT, c) (R, G, 4) in low-D mode
    vmax: float
    low_dim: bool
    t: int
    T: int
    space: Space
    streams: RunStreams
    restarted: np.ndarray | None = None  # (R, m) parcels restarted in the last ask
    rng: np.ndarray | None = None  # (R, 4) xoshiro256** state per run, for the permutations
    # the kernel's fixed per-group coefficients ``(R, N, 4)`` and the ``coef`` they were laid
    # out from: rebuilt only when ``coef`` is replaced (a redraw), not at every ask
    coef_kernel: tuple | None = None
    # Wind._step_args: the kernel's arguments that stay the same at every ask
    step_args: tuple | None = None


class Wind(Optimizer):
    """The WDO family (WDO, AWDO, MAWDO and its ablations); see the module docstring."""

    name = "wdo"
    params_class = WindParams

    # -- set-up --------------------------------------------------------------------------------
    def init(self, space: Space, streams: RunStreams, max_iter: int, x0=None) -> WindState:
        P = self.params
        N, D = P.pop_size, space.dim
        low = P.low_dim_stabilization and D <= P.low_dim
        vmax = 0.25 * P.vmax if low else P.vmax  # Eq. 21
        p0 = None if x0 is None else space.to_unit(as_x0(x0, streams.runs, D, N))
        p = initial_population(streams, N, -np.ones(D), np.ones(D), p0)
        u = streams.uniform(-vmax, vmax, (N, D))
        coef = self._group_coefficients(streams) if low else None
        R = streams.runs
        return WindState(
            p=p,
            u=u,
            f=np.full((R, N), np.inf),
            pbest=p.copy(),
            pbest_f=np.full((R, N), np.inf),
            gid=wind.partition(N, P.groups),
            coef=coef,
            vmax=vmax,
            low_dim=low,
            t=0,
            T=max_iter,
            space=space,
            streams=streams,
        )

    def _group_coefficients(self, streams: RunStreams) -> np.ndarray:
        """Heterogeneous coefficients per group (Eqs. 17-20), shape ``(R, G, 4)``."""
        lo = np.array([0.15, 0.15, 0.90, 0.10])
        hi = np.array([0.45, 0.45, 1.50, 0.50])
        return streams.uniform(lo, hi, (self.params.groups, 4))

    # -- ask -------------------------------------------------------------------------------------
    def ask(self, state: WindState) -> np.ndarray:
        """Move every parcel (one fused kernel pass) and return the positions to evaluate.

        The returned array is new at each call (the evaluator and user objectives may keep it);
        ``p``, ``u`` and the permutation buffer are updated in place.
        """
        s = state
        if s.t == 0:
            return s.space.from_unit(s.p)
        P = self.params
        R, N, D = s.p.shape
        s.p = np.ascontiguousarray(s.p, dtype=float)
        s.u = np.ascontiguousarray(s.u, dtype=float)
        perm, rng = self._permutation_draw(s)
        coef_draw, coef = self._coefficient_array(s, R, N, rng is not _NO_RNG)
        if s.step_args is None:
            s.step_args = self._step_args(s)
        rank, rank_starts, gstarts, guidance, fixed_w, tail = s.step_args
        segment_ranks(s.f, rank_starts, rank)
        w = fixed_w if guidance != 2 or not P.schedule else wind.schedule_weights(s.t, s.T)
        restart = P.restart and s.t % P.restart_every == 0
        m = P.n_restart if restart else 0
        X = np.empty((R, N + (m if P.obl else 0), D))
        wind_step(
            s.p, s.u, s.pbest, s.pbest_f, rank, perm, rng, rng is not _NO_RNG,
            coef_draw, coef, gstarts, guidance, np.array(w, float), *tail, X,
        )  # fmt: skip
        s.restarted = None
        if restart:
            self._restart(s, X, m)
        return X

    def _step_args(self, s: WindState) -> tuple:
        """What every ask of ``s`` hands :func:`wind_step` unchanged, laid out once per state:
        ``(rank, rank_starts, gstarts, guidance, fixed_w, tail)``; ``rank`` is the ranks'
        work array (overwritten at each ask, read only by the kernel), ``fixed_w`` the
        weights when they are not scheduled and ``tail`` the arguments after the weights
        (``gate`` .. ``width``). The parameters and the box of a state never change."""
        P = self.params
        R, N, D = s.p.shape
        gstarts = group_starts(N, P.groups)
        rank_starts = gstarts if P.rank_scope == "group" else group_starts(N, 1)
        if P.guidance == "hierarchical":
            fixed_w, guidance = P.weights, 2
        else:
            fixed_w, guidance = (0.0, 0.0, 0.0), 0 if P.guidance == "global" else 1
        lb, width = _box_arrays(s.space)
        tail = (
            P.gate, 2.0 * math.sqrt(D), self._gravity_mode(s),
            2 if P.pressure == "flat" else int(P.velocity == "awdo"),
            float(s.vmax) if P.clamp else math.inf, P.boundary == "reflect", float(P.eta),
            lb, width,
        )  # fmt: skip
        return np.empty((R, N)), rank_starts, gstarts, guidance, fixed_w, tail

    def _gravity_mode(self, s: WindState) -> int:
        """The kernel's ``gravity`` code: 0 origin, 1 group centroid (low-D), 2 population
        mean, 3 tbest, 4 none."""
        to = self.params.gravity_to
        if to == "centre":
            return int(s.low_dim)
        return {"mean": 2, "best": 3, "none": 4}[to]

    def _permutation_draw(self, s: WindState):
        """``(perm, rng)`` for the kernel: with real streams, the per-run xoshiro256** states
        the kernel draws the permutations from (seeded once from each run's generator); from
        stand-in streams without ``raw_words``, an explicit permutation array."""
        if hasattr(s.streams, "raw_words"):
            if s.rng is None:
                s.rng = seed_xoshiro(s.streams)
            return _NO_PERM, s.rng
        D = s.p.shape[2]
        perm = s.streams.shuffle_rows(np.empty(s.p.shape, np.int16 if D < 2**15 else np.int32))
        return perm, _NO_RNG

    def _restart(self, s: WindState, X: np.ndarray, m: int) -> None:
        """Periodic guided restart of the ``m`` worst parcels (Eqs. 12-13), plus OBL (Eq. 14)."""
        P = self.params
        R, N, D = s.p.shape
        rows = np.arange(R)[:, None]
        worst = np.argsort(s.f, axis=1, kind="stable")[:, N - m :]  # (R, m)
        tbest = s.pbest[np.arange(R), np.argmin(s.pbest_f, axis=1)]  # (R, D)
        sigma = wind.restart_sigma(s.t, s.T, P.sigma0, P.sigma_end)
        fresh = s.streams.normal((m, D))  # (R, m, D), turned into the new positions in place
        fresh *= sigma
        fresh += tbest[:, None, :]  # Eq. 12: tbest + sigma z
        confine_positions(P.boundary, fresh, -1.0, 1.0)
        s.p[rows, worst] = fresh
        s.u[rows, worst] = 0.0
        s.restarted = worst
        # one (R, m, D) scratch at a time: ufuncs on strided views of X would buffer copies
        X[rows, worst] = s.space.from_unit(fresh, out=fresh)
        del fresh
        if P.obl:  # Eq. 14
            opp = s.p[rows, worst]
            X[:, N:] = s.space.from_unit(np.negative(opp, out=opp), out=opp)

    def _coefficient_array(self, s: WindState, R: int, N: int, kernel_rng: bool):
        """``(coef_draw, coef)`` for the kernel: AWDO's U[0,1) coefficients are drawn inside it
        from the run's generator when it has one (``coef_draw`` 1 per iteration, 2 per parcel);
        otherwise ``_coefficients`` (which subclasses may override) stacked into
        ``(R or 1, N or 1, 4)``."""
        P = self.params
        builtin = type(self)._coefficients is Wind._coefficients
        fixed = P.velocity == "wdo" or P.coef_draw == "fixed"
        if builtin and not s.low_dim and fixed:
            # WDO's four fixed scalars: laid out once per state, not broadcast at every ask
            if s.coef_kernel is None:
                s.coef_kernel = (None, np.array([[[P.alpha, P.g, P.RT, P.c]]], dtype=float))
            return 0, s.coef_kernel[1]
        if kernel_rng and P.velocity == "awdo" and not s.low_dim and builtin:
            return (1 if P.coef_draw == "iteration" else 2), _NO_COEF
        if s.low_dim and not P.hetero_redraw and builtin:
            # fixed per-group coefficients: the same array every iteration, laid out once
            if s.coef_kernel is None or s.coef_kernel[0] is not s.coef:
                s.coef_kernel = (s.coef, np.ascontiguousarray(s.coef[:, s.gid], dtype=float))
            return 0, s.coef_kernel[1]
        parts = np.broadcast_arrays(*(np.asarray(c, float) for c in self._coefficients(s)))
        arr = np.stack(parts, axis=-1)
        if arr.ndim == 1:  # four scalars
            return 0, arr[None, None, :]
        return 0, np.ascontiguousarray(arr.reshape(arr.shape[0], arr.shape[1], 4))  # (., ., 1, 4)

    def _coefficients(self, s: WindState):
        """(alpha, g, RT, c), each broadcastable to ``(R, N, 1)``."""
        P = self.params
        if s.low_dim:
            if P.hetero_redraw:
                s.coef = self._group_coefficients(s.streams)
            per = s.coef[:, s.gid]  # (R, N, 4)
            return tuple(per[..., k : k + 1] for k in range(4))
        if P.velocity == "awdo" and P.coef_draw != "fixed":
            shape = (1, 4) if P.coef_draw == "iteration" else (s.p.shape[1], 4)
            draw = s.streams.random(shape)  # a_t, g_t, RT_t, c_t ~ U[0, 1] (Eq. 4)
            return tuple(draw[..., k : k + 1] for k in range(4))
        return P.alpha, P.g, P.RT, P.c

    # -- tell ------------------------------------------------------------------------------------
    def tell(self, state: WindState, X: np.ndarray, F: np.ndarray) -> WindState:
        s = state
        R, N = s.f.shape
        Fn = F[:, :N].copy()
        if s.restarted is not None and F.shape[1] > N:
            # OBL: keep the better of each restarted parcel and its opposite.
            rows = np.arange(R)[:, None]
            f_opp = F[:, N:]
            take = f_opp < Fn[rows, s.restarted]
            idx_r, idx_k = np.nonzero(take)
            tgt = s.restarted[idx_r, idx_k]
            s.p[idx_r, tgt] = -s.p[idx_r, tgt]
            Fn[idx_r, tgt] = f_opp[idx_r, idx_k]
        s.f = Fn
        update_personal_best(s.p, Fn, s.pbest, s.pbest_f)
        s.t += 1
        return s
