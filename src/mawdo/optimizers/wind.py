"""The WDO family's update equations as pure array functions.

Shapes: ``R`` runs, ``N`` parcels, ``G`` groups, ``D`` dimensions. Positions ``p`` live in the
normalised box ``[-1, 1]^D`` (docs/deviations.md#d-wdo). Equation numbers refer to the MAWDO paper
(Liu, Mohd Zain & Mao, arXiv 2511.20394) unless stated otherwise.
"""

from __future__ import annotations

import numpy as np


def wdo_velocity(u, p, B, rank, u_perm, alpha, g, RT, c, centre=0.0):
    """WDO velocity (Bayraktar et al. 2013, Eq. 1 with the authors' rank weighting)::

        u' = (1 - alpha) u - g (p - centre) + |1 - 1/i| RT (B - p) + c u[perm] / i

    ``i`` is the parcel's 1-based rank (1 = best); the best parcel feels no pressure term.
    Coefficients broadcast against ``(R, N, 1)``; ``centre`` is 0 (the origin) in WDO.
    """
    return (
        (1.0 - alpha) * u
        - g * (p - centre)
        + np.abs(1.0 - 1.0 / rank) * RT * (B - p)
        + (c * u_perm / rank)
    )


def awdo_velocity(u, p, B, rank, u_perm, alpha, g, RT, c, centre=0.0):
    """AWDO velocity as the MAWDO paper writes it (Eq. 4)::

        u' = (1 - a_t) u - g_t (p - centre) + RT_t (B - p) / r_i + c_t u[perm] / r_i

    ``centre`` is the origin, or the group centroid under low-dimensional stabilisation
    (Eqs. 22-23: ``grav = -g (X - mean(X_group))``).
    """
    return (1.0 - alpha) * u - g * (p - centre) + RT * (B - p) / rank + c * u_perm / rank


def schedule_weights(t, T):
    """Scheduled mixing (Eqs. 6-9): guidance weights at iteration ``t`` of ``T`` (1-based).

    ``lambda = (t-1)/(T-1)``; ``w1 = 0.6(1-lambda) + 0.2 lambda``, ``w2 = 0.3``,
    ``w3 = 0.1(1-lambda) + 0.5 lambda``. For ``T = 1`` lambda is 0.
    """
    lam = 0.0 if T <= 1 else min(max((t - 1) / (T - 1), 0.0), 1.0)
    return 0.6 * (1 - lam) + 0.2 * lam, 0.3, 0.1 * (1 - lam) + 0.5 * lam


def distance_gate(gbest, tbest, d_max):
    """Distance gate (Eq. 10): ``gate_g = min(1, ||gbest_g - tbest|| / d_max)``.

    ``gbest`` ``(R, G, D)``, ``tbest`` ``(R, D)``; returns ``(R, G)``.
    """
    return np.minimum(1.0, np.linalg.norm(gbest - tbest[:, None, :], axis=-1) / d_max)


def hierarchical_guidance(pbest, gbest, tbest, w1, w2, w3_eff):
    """Hierarchical guidance vector (Eq. 5), renormalised::

        B = (w1 pbest + w2 gbest_g + w3_eff tbest) / (w1 + w2 + w3_eff)

    The paper states ``w1 + w2 + w3 = 1`` but the gate (Eq. 11) breaks that sum; without the
    division B would shrink toward the origin (docs/deviations.md#d-mawdo-renorm).

    ``pbest`` ``(R, N, D)``; ``gbest`` ``(R, N, D)`` (each parcel's group best); ``tbest``
    ``(R, D)``; ``w3_eff`` scalar or ``(R, N)``.
    """
    w3 = np.asarray(w3_eff, float)
    w3 = w3[..., None] if w3.ndim else w3
    return (w1 * pbest + w2 * gbest + w3 * tbest[:, None, :]) / (w1 + w2 + w3)


def restart_sigma(t, T, sigma0, sigma_end):
    """PGR step size (Eq. 13, decay made explicit).

    ``sigma_t = sigma0 - (sigma0 - sigma_end) t/T``.
    """
    return sigma0 - (sigma0 - sigma_end) * min(t / T, 1.0)


def opposite(p):
    """Opposition-based learning (Eq. 14): ``lb + ub - x``, which is ``-p`` in ``[-1, 1]^D``."""
    return -p


def partition(N: int, G: int) -> np.ndarray:
    """Group index of each parcel: ``G`` contiguous near-equal groups.

    ``N = 50, G = 8`` gives sizes 7, 7, 6, 6, 6, 6, 6, 6.
    """
    if not 1 <= G <= N:
        raise ValueError(f"groups={G} must lie in [1, pop_size={N}]")
    sizes = np.full(G, N // G)
    sizes[: N % G] += 1
    return np.repeat(np.arange(G), sizes)


def group_ranks(F, gid, G):
    """1-based rank of each parcel within its group by ``F`` ``(R, N)`` (stable on ties)."""
    R, N = F.shape
    pop_rank = np.argsort(np.argsort(F, axis=1, kind="stable"), axis=1, kind="stable")
    key = gid[None, :] * N + pop_rank  # sort by group, then by fitness
    order = np.argsort(key, axis=1)
    pos = np.empty_like(order)
    np.put_along_axis(pos, order, np.arange(N)[None, :].repeat(R, 0), axis=1)
    starts = np.concatenate([[0], np.cumsum(np.bincount(gid, minlength=G))[:-1]])
    return pos - starts[gid][None, :] + 1


def group_argmin(F, gid, G):
    """Index (into ``N``) of the best parcel of each group, shape ``(R, G)``."""
    R, N = F.shape
    sizes = np.bincount(gid, minlength=G)
    S = sizes.max()
    starts = np.concatenate([[0], np.cumsum(sizes)[:-1]])
    idx = starts[:, None] + np.arange(S)[None, :]  # (G, S), groups are contiguous
    valid = np.arange(S)[None, :] < sizes[:, None]
    idx = np.where(valid, idx, N)  # padding points at a +inf sentinel column
    Fp = np.concatenate([F, np.full((R, 1), np.inf)], axis=1)
    j = np.argmin(Fp[:, idx], axis=2)  # (R, G)
    return np.take_along_axis(np.broadcast_to(idx, (R, G, S)), j[..., None], 2)[..., 0]


def group_centroid(p, gid, G):
    """Mean position of each group ``(R, G, D)`` (Eq. 23, per group)."""
    M = np.zeros((G, gid.size))
    M[gid, np.arange(gid.size)] = 1.0
    M /= M.sum(axis=1, keepdims=True)
    return np.einsum("gn,rnd->rgd", M, p)
