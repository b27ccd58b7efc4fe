"""How uncertain a prediction scenario's movers are: the spread of each predicted centre.

A planner that observes its world (:mod:`mawdo.planning.sense`) plans among *predicted* movers.
Their centres are estimates: the tracker's position and velocity carry standard deviations, and
the agents keep accelerating after the reading. :class:`Uncertainty` keeps, for the movers of a
prediction scenario, what is needed to say how far the true centre may stray from the predicted
one ``tau`` steps ahead (:func:`centre_sd`), and the agents' own radii (the predicted discs are
grown by a margin; a risk is judged on the true shapes).

The bound is the one the predictors' uncertainty margin uses
(:func:`mawdo.planning.sense.predict.tube_radius`): the centre predicted ``tau`` steps ahead is
``X + tau V + W``, with ``X`` and ``V`` the tracked centre and velocity and ``W`` the
displacement by the accelerations still to come (white acceleration of s.d. ``accel_sd`` per
axis and step, ``var W = accel_sd^2 (tau^3 / 3 - tau / 12)``); whatever their correlation,

``sd <= position_sd + tau velocity_sd + accel_sd sqrt(tau^3 / 3 - tau / 12)``   (per axis).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

__all__ = ["Uncertainty", "centre_sd"]


def centre_sd(position_sd, velocity_sd, accel_sd, tau) -> np.ndarray:
    """Per-axis s.d. bound (pixels) of a centre predicted ``tau`` steps ahead.

    Parameters
    ----------
    position_sd : array_like
        S.d. of the tracked centre (pixels, >= 0).
    velocity_sd : array_like
        S.d. of the tracked velocity (pixels per time step, >= 0).
    accel_sd : array_like
        S.d. of the agent's acceleration per axis and step (pixels per time step squared, >= 0).
    tau : array_like
        Look-ahead (time steps, >= 0); broadcast against the others.

    Returns
    -------
    numpy.ndarray
        ``position_sd + tau velocity_sd + accel_sd sqrt(max(tau^3 / 3 - tau / 12, 0))``.
    """
    tau = np.asarray(tau, dtype=float)
    steer = np.sqrt(np.maximum(tau**3 / 3.0 - tau / 12.0, 0.0))
    return position_sd + tau * velocity_sd + accel_sd * steer


@dataclass(frozen=True, eq=False)
class Uncertainty:
    """The spread of a prediction scenario's movers.

    Attributes
    ----------
    index : numpy.ndarray of int, shape (n,)
        The movers' positions in ``Scenario.obstacles`` (circles).
    radius : numpy.ndarray, shape (n,)
        Each agent's own radius (pixels, > 0): its disc without the uncertainty margin.
    position_sd, velocity_sd, accel_sd : numpy.ndarray, shape (n,)
        The terms of :func:`centre_sd` per mover (pixels, pixels per step, pixels per step
        squared; each >= 0).
    origin : float
        The time (time steps) of the reading the prediction starts from: look-ahead is
        ``t - origin``.
    """

    index: np.ndarray
    radius: np.ndarray
    position_sd: np.ndarray
    velocity_sd: np.ndarray
    accel_sd: np.ndarray
    origin: float = 0.0

    def __post_init__(self) -> None:
        n = len(np.asarray(self.index).reshape(-1))
        object.__setattr__(self, "index", np.asarray(self.index, dtype=np.int64).reshape(-1))
        for name in ("radius", "position_sd", "velocity_sd", "accel_sd"):
            value = np.broadcast_to(np.asarray(getattr(self, name), dtype=float), (n,)).copy()
            if not np.all(np.isfinite(value)) or np.any(value < 0):
                raise ValueError(f"Uncertainty.{name} must be finite and >= 0, got {value!r}")
            object.__setattr__(self, name, value)
        if np.any(self.radius <= 0):
            raise ValueError(f"Uncertainty.radius must be > 0 px, got {self.radius!r}")
        object.__setattr__(self, "origin", float(self.origin))

    def __len__(self) -> int:
        return len(self.index)

    def sd(self, times) -> np.ndarray:
        """Per-axis s.d. bound (pixels) of each mover's centre at absolute ``times``.

        Parameters
        ----------
        times : array_like, shape (k,)
            Time steps (at or after ``origin``; earlier ones count as ``origin``).

        Returns
        -------
        numpy.ndarray, shape (k, n)
        """
        tau = np.maximum(np.asarray(times, dtype=float).reshape(-1, 1) - self.origin, 0.0)
        return centre_sd(self.position_sd, self.velocity_sd, self.accel_sd, tau)
