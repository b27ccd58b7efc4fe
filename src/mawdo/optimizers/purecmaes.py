"""Batched port of ``purecmaes_wdo.m``, the CMA-ES of Bayraktar's ``AWDO_v03.m``.

``purecmaes_wdo`` is Hansen's ``purecmaes.m`` cut into one call per WDO iteration: it is told
the pressures of the ``lambda`` coefficient samples the parcels just used, updates mean, paths,
covariance and step size, and draws ``lambda`` new samples. Here one such CMA-ES runs per run of a
batch (state arrays with a leading run axis): the update and the sampling are one compiled loop
over the runs (:mod:`mawdo.optimizers.purecmaes_kernel`), the eigen decompositions one NumPy call
for all runs, and each run's samples come from its own stream, so a run is the same alone or in
any batch.

Line for line as the MATLAB source (minimisation: ascending sort), with its particulars kept:
``hsig`` in the older squared-norm form, the covariance clipped at ``1e5`` before each eigen
decomposition, and ``counteval`` the WDO iteration number (first call at 2), not an evaluation
count. Two guards the source lacks, both as in the ``cmaes`` library this port replaces: the step
size is capped at ``SIGMA_MAX`` (left alone it grows without bound on some problems, 0.5 -> 3e8
in 2000 iterations on Rosenbrock, and would overflow into NaN coefficients on long runs), and
eigenvalues are floored at ``EIG_FLOOR`` so that a covariance made singular by rounding cannot
give NaN scales (docs/deviations.md#d-awdo-cmaes).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from mawdo.optimizers import purecmaes_kernel as kernel
from mawdo.util import libm

EIG_FLOOR = 1e-20
"""Least eigenvalue of the covariance (the source takes ``sqrt`` of whatever ``eig`` returns)."""

SIGMA_MAX = 1e32
"""Largest step size (the ``cmaes`` library's ``_SIGMA_MAX``); the source has no cap."""

CLIP = 100000.0
"""``rec.C = min(100000, rec.C)`` of the source, applied before each eigen decomposition."""


@dataclass(frozen=True)
class Settings:
    """Strategy parameters of ``purecmaes_wdo`` for dimension ``n`` and ``lam`` samples."""

    n: int
    lam: int
    mu: int
    weights: np.ndarray  # (mu,), sum 1
    mueff: float
    cc: float
    cs: float
    c1: float
    cmu: float
    damps: float
    chin: float

    @property
    def consts(self) -> np.ndarray:
        """``(mueff, cc, cs, c1, cmu, damps, chin)``, as the compiled update takes them."""
        return np.array([self.mueff, self.cc, self.cs, self.c1, self.cmu, self.damps, self.chin])

    @classmethod
    def make(cls, n: int, lam: int) -> Settings:
        """The source's ``counteval == 2`` block: selection and adaptation constants.

        Parameters
        ----------
        n : int
            Dimension of the search (4 in AWDO: ``alpha, g, RT, c``), >= 1.
        lam : int
            Samples per generation (the air population), >= 2.
        """
        half = lam / 2
        w = libm.log(half + 0.5) - libm.log(np.arange(1, math.floor(half) + 1))
        w = w / w.sum()
        mueff = float(w.sum() ** 2 / (w**2).sum())
        c1 = 2 / ((n + 1.3) ** 2 + mueff)
        cs = (mueff + 2) / (n + mueff + 5)
        return cls(
            n=n,
            lam=lam,
            mu=len(w),
            weights=w,
            mueff=mueff,
            cc=(4 + mueff / n) / (n + 4 + 2 * mueff / n),
            cs=cs,
            c1=c1,
            cmu=min(1 - c1, 2 * (mueff - 2 + 1 / mueff) / ((n + 2) ** 2 + mueff)),
            damps=1 + 2 * max(0.0, math.sqrt((mueff - 1) / (n + 1)) - 1) + cs,
            chin=n**0.5 * (1 - 1 / (4 * n) + 1 / (21 * n**2)),
        )


@dataclass
class PureCMAES:
    """Dynamic state of one CMA-ES per run (``rec`` of the source, batched over runs R)."""

    cfg: Settings
    xmean: np.ndarray  # (R, n)
    sigma: np.ndarray  # (R,)
    pc: np.ndarray  # (R, n)
    ps: np.ndarray  # (R, n)
    B: np.ndarray  # (R, n, n), eigenvectors in columns
    D: np.ndarray  # (R, n), standard deviations along them
    C: np.ndarray  # (R, n, n)
    invsqrtC: np.ndarray  # (R, n, n)
    eigeneval: int = 0

    @classmethod
    def start(cls, xmean: np.ndarray, sigma: float, lam: int) -> PureCMAES:
        """Initial state of R CMA-ES: identity covariance, zero paths.

        Parameters
        ----------
        xmean : array_like, shape (R, n)
            Initial means (AWDO: ``U[0, 1]^4`` draws, the source's ``rand(4, 1)``).
        sigma : float
            Initial step size, > 0 (0.5 in the source).
        lam : int
            Samples per generation, >= 2 (AWDO: the air population).
        """
        xmean = np.array(xmean, dtype=float)
        R, n = xmean.shape
        eye = np.broadcast_to(np.eye(n), (R, n, n)).copy()
        return cls(
            cfg=Settings.make(n, lam),
            xmean=xmean,
            sigma=np.full(R, float(sigma)),
            pc=np.zeros((R, n)),
            ps=np.zeros((R, n)),
            B=eye.copy(),
            D=np.ones((R, n)),
            C=eye.copy(),
            invsqrtC=eye,
        )

    def tell(self, arx: np.ndarray, fitness: np.ndarray, counteval: int) -> None:
        """One update of every run, in place: mean, paths, covariance, step size, and every
        few generations ``B`` and ``D``.

        Parameters
        ----------
        arx : numpy.ndarray, shape (R, lam, n)
            The samples the fitness belongs to.
        fitness : numpy.ndarray, shape (R, lam)
            Their fitness, minimised; finite (callers rank NaN and infinities last first).
        counteval : int
            The source's iteration number, >= 2 (2 at the first call); it sets ``hsig``'s
            normalisation and when ``B`` and ``D`` are recomputed.
        """
        c = self.cfg
        kernel.update(
            np.ascontiguousarray(arx, dtype=float), np.ascontiguousarray(fitness, dtype=float),
            c.weights, c.consts, counteval, self.xmean, self.sigma, self.pc, self.ps, self.C,
            self.invsqrtC, SIGMA_MAX,
        )  # fmt: skip
        if counteval - self.eigeneval > c.lam / (c.c1 + c.cmu) / c.n / 10:
            self.eigeneval = counteval
            upper = np.triu(self.C)
            self.C = np.minimum(CLIP, upper + np.swapaxes(np.triu(self.C, 1), 1, 2))
            vals, self.B = np.linalg.eigh(self.C)
            self.D = np.sqrt(np.maximum(vals, EIG_FLOOR))
            self.invsqrtC = (self.B / self.D[:, None, :]) @ np.swapaxes(self.B, 1, 2)

    def sample(self, z: np.ndarray) -> np.ndarray:
        """New samples ``xmean + sigma B (D z)``, the source's ``arx``.

        Parameters
        ----------
        z : numpy.ndarray, shape (R, lam, n)
            Standard normal draws, one ``randn(n, 1)`` per sample, from each run's stream.

        Returns
        -------
        numpy.ndarray, shape (R, lam, n)
        """
        return kernel.sample(self.xmean, self.sigma, self.B, self.D, np.ascontiguousarray(z))
