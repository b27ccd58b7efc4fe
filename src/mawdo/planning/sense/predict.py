"""Predicted motions from tracks: every predictor by name (:data:`PREDICTORS`).

A predictor turns the tracker's :class:`~mawdo.planning.sense.reading.Tracks` at step ``now``
into one :class:`Predicted` per track: a disc of a given radius, centred at the track's centre at
``now``, moving along a :class:`~mawdo.planning.world.motion.Track` whose offsets are absolute
centre positions minus that centre and whose knot times run (in absolute steps) from ``now`` to
``now + horizon``; after the last knot the disc stands still. The planner's stages consume it like
a scenario's scripted mover.

====================  ===========================================================
name                  what
====================  ===========================================================
``constant_velocity``  straight on at the tracked velocity, stopping where the disc
                       would leave the map (people do not walk off it)
``stop``               stands where it is now
``oracle``             the true future centres, given by the world (evaluation only:
                       the upper bound of prediction)
====================  ===========================================================

Uncertainty (``constant_velocity`` and ``stop``): the disc's radius is the agent's radius plus
``k_sd`` standard deviations of the predicted centre at the look-ahead ``tube_horizon``
(:func:`tube_radius`). The stages handle rigid shapes only, so the tube whose radius grows with
look-ahead is replaced by one constant radius (docs/deviations.md#d-uncertainty-tube).

Adding a predictor: a function ``predict(tracks, now, horizon, bounds, **options) ->
list[Predicted]`` and one line::

    PREDICTORS.register("mine", PredictorSpec("mine", predict, description="..."))
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from scipy.optimize import linear_sum_assignment

from mawdo.planning.sense.reading import Tracks
from mawdo.planning.world.motion import Track
from mawdo.planning.world.uncertainty import centre_sd
from mawdo.registry import Registry
from mawdo.util.validate import check_int, check_real

__all__ = [
    "K_SD",
    "PREDICTORS",
    "Predicted",
    "PredictorSpec",
    "border_stop_times",
    "constant_velocity",
    "match_agents",
    "oracle",
    "run_predictor",
    "stop",
    "tube_radius",
]

#: Standard deviations of uncertainty margin a prediction carries by default (``k_sd``).
K_SD = 2.0


@dataclass(frozen=True, eq=False)
class Predicted:
    """One track's predicted motion.

    Attributes
    ----------
    id : int
        The track's id.
    radius : float
        Radius of the predicted disc (pixels), > 0: the agent's, grown by the uncertainty.
    motion : Track
        Offsets (pixels) of the disc's centre from the track's centre at ``now``, at absolute
        times (time steps) from ``now`` to ``now + horizon``.
    spread : tuple of float or None
        ``(own_radius, position_sd, velocity_sd, accel_sd)``: the agent's radius (pixels) and
        the terms of the predicted centre's s.d. bound
        (:func:`~mawdo.planning.world.uncertainty.centre_sd`, look-ahead from ``now``); None
        for an exact prediction (``oracle``).
    """

    id: int
    radius: float
    motion: Track
    spread: tuple[float, float, float, float] | None = None


@dataclass(frozen=True)
class PredictorSpec:
    """A registered predictor.

    Attributes
    ----------
    name : str
        Registered name.
    predict : callable
        ``predict(tracks, now, horizon, bounds, **options) -> list[Predicted]``.
    description : str
        One line.
    needs_truth : bool
        Whether it takes the world's true future (``truth=``): for evaluation only.
    """

    name: str
    predict: Callable[..., list[Predicted]]
    description: str
    needs_truth: bool = False


def _check_window(now, horizon, bounds) -> tuple[float, float, np.ndarray]:
    now = check_real("now", now)
    horizon = check_real("horizon", horizon, 0.0)
    box = np.asarray(bounds, dtype=float).reshape(-1)
    if box.shape != (4,) or not np.all(np.isfinite(box)) or box[2] <= box[0] or box[3] <= box[1]:
        raise ValueError(
            f"bounds={bounds!r} must be the map box (x0, y0, x1, y1) in pixels with x0 < x1 "
            "and y0 < y1, e.g. (0, 0, width, height)"
        )
    return now, horizon, box


def _knot_times(now: float, horizon: float, inner=()) -> np.ndarray:
    """``now``, the inner look-aheads strictly inside ``(0, horizon)``, ``now + horizon``;
    strictly increasing: a look-ahead too small to move ``now`` in floating point (a disc a
    hair from where it stops) is dropped, not repeated."""
    inner = np.asarray(inner, dtype=float).reshape(-1)
    inner = inner[(inner > 0.0) & (inner < horizon)]
    times = now + np.unique(np.concatenate(([0.0], inner, [horizon])))
    return times[np.concatenate(([True], np.diff(times) > 0.0))]


def _stop_knot_times(now: float, horizon: float, stop: float) -> np.ndarray:
    """``_knot_times(now, horizon, [stop])`` on Python floats (the same numbers: one knot
    inside is already in order), for the predictor's loop over tracks."""
    ahead = [0.0, stop, horizon] if 0.0 < stop < horizon else [0.0, horizon]
    times = [now + a for a in ahead]
    kept = [times[0]] + [b for a, b in zip(times[:-1], times[1:], strict=True) if b > a]
    return np.array(kept)


def tube_radius(
    tracks: Tracks, horizon: float, k_sd: float = K_SD, tube_horizon: float = 5.0, accel_sd=0.2
) -> np.ndarray:
    """Radii of the predicted discs: each agent's radius grown by its uncertainty.

    The centre predicted ``tau`` steps ahead is ``X + tau V + W``: the tracked centre ``X``, the
    tracked velocity ``V`` and the displacement ``W`` by the accelerations still to come (the
    tracker's white-acceleration model: per axis ``var W = accel_sd^2 (tau^3 / 3 - tau / 12)``
    after ``tau`` whole steps of ``accel_sd`` each). Whatever their correlation,
    ``sd(X + tau V + W) <= sd(X) + tau sd(V) + sd(W)``, so the radius

    ``radius + k_sd (position_sd + tau_c velocity_sd + sd(W at tau_c))``,
    ``tau_c = min(tube_horizon, horizon)``

    covers ``k_sd`` s.d.s of the predicted centre up to the look-ahead ``tau_c`` (and more at
    shorter ones); it is the tube's width at ``tau_c``, held for the whole prediction
    (docs/deviations.md#d-uncertainty-tube).

    Parameters
    ----------
    tracks : Tracks
        The tracks (their radii and s.d.s).
    horizon : float
        Prediction horizon (time steps), >= 0.
    k_sd : float
        Standard deviations of margin, >= 0 (2: the true centre stays inside with probability
        about 0.86 per step for a 2-D Gaussian error, and far more with the sum bound above).
    tube_horizon : float
        Look-ahead of the held width (time steps), >= 0: 5 steps, about the time the robot
        needs to go round a person at its speed, and the replan comes every step or so.
    accel_sd : float
        The agents' acceleration s.d. per axis and step (pixels per time step squared), >= 0:
        the tracker's ``accel_sd``.

    Returns
    -------
    numpy.ndarray, shape (n,)
        Radii (pixels).
    """
    k_sd = check_real("k_sd", k_sd, 0.0)
    tau = min(check_real("tube_horizon", tube_horizon, 0.0), float(horizon))
    accel_sd = check_real("accel_sd", accel_sd, 0.0)
    return tracks.radii + k_sd * centre_sd(tracks.position_sd, tracks.velocity_sd, accel_sd, tau)


def border_stop_times(centers, velocities, radii, bounds) -> np.ndarray:
    """Time (steps, >= 0, ``inf`` for never) until each disc moving straight on at its velocity
    would first leave the map box: its centre reaching ``[x0 + r, x1 - r] x [y0 + r, y1 - r]``'s
    border. A disc already outside that box, moving away from it, stops at once (0)."""
    c = np.asarray(centers, dtype=float).reshape(-1, 2)
    v = np.asarray(velocities, dtype=float).reshape(-1, 2)
    r = np.asarray(radii, dtype=float).reshape(-1, 1)
    lo = np.asarray(bounds, dtype=float)[:2] + r
    hi = np.asarray(bounds, dtype=float)[2:] - r
    wall = np.where(v > 0, hi, lo)
    moving = v != 0
    t = np.where(moving, (wall - c) / np.where(moving, v, 1.0), np.inf)
    return np.clip(t.min(axis=1), 0.0, None)


def constant_velocity(
    tracks: Tracks, now, horizon, bounds, *, k_sd=K_SD, tube_horizon=5.0, accel_sd=0.2
) -> list[Predicted]:
    """Straight on at the tracked velocity, stopping where the disc would leave the map.

    Parameters
    ----------
    tracks : Tracks
        The tracks at step ``now``.
    now : float
        Current time step.
    horizon : float
        Prediction horizon (time steps), >= 0.
    bounds : array_like, shape (4,)
        Map box ``(x0, y0, x1, y1)`` (pixels): a disc (of the agent's radius) stops where it
        touches the box's border (:func:`border_stop_times`).
    k_sd, tube_horizon, accel_sd
        Uncertainty margin (:func:`tube_radius`).

    Returns
    -------
    list of Predicted
        One per track, in the tracks' order; knots at ``now``, at the border stop (if within
        the horizon) and at ``now + horizon``.
    """
    now, horizon, box = _check_window(now, horizon, bounds)
    radius = tube_radius(tracks, horizon, k_sd, tube_horizon, accel_sd)
    t_stop = border_stop_times(tracks.centers, tracks.velocities, tracks.radii, box)
    t_stop = np.minimum(t_stop, horizon)
    out = []
    for i, track_id in enumerate(tracks.ids):
        times = _stop_knot_times(now, horizon, float(t_stop[i]))
        ahead = np.minimum(times - now, t_stop[i])
        offsets = ahead[:, None] * tracks.velocities[i]
        spread = _spread(tracks, i, accel_sd)
        out.append(Predicted(int(track_id), float(radius[i]), Track(times, offsets), spread))
    return out


def stop(
    tracks: Tracks, now, horizon, bounds, *, k_sd=K_SD, tube_horizon=5.0, accel_sd=0.2
) -> list[Predicted]:
    """Every agent stands where it is now (the baseline that ignores motion).

    Parameters as :func:`constant_velocity`; the uncertainty margin is the same, so a comparison
    with it isolates what the predicted motion brings.
    """
    now, horizon, _ = _check_window(now, horizon, bounds)
    radius = tube_radius(tracks, horizon, k_sd, tube_horizon, accel_sd)
    times = _knot_times(now, horizon)
    still = np.zeros((len(times), 2))
    return [
        Predicted(
            int(track_id), float(radius[i]), Track(times, still), _spread(tracks, i, accel_sd)
        )
        for i, track_id in enumerate(tracks.ids)
    ]


def _spread(tracks: Tracks, i: int, accel_sd) -> tuple[float, float, float, float]:
    """Track ``i``'s ``Predicted.spread``."""
    return (
        float(tracks.radii[i]), float(tracks.position_sd[i]), float(tracks.velocity_sd[i]),
        float(accel_sd),
    )  # fmt: skip


def match_agents(tracks: Tracks, true_centers) -> np.ndarray:
    """Each track's true agent: the assignment of tracks to agents with the least total
    distance between track and true centres (Hungarian method).

    Parameters
    ----------
    tracks : Tracks
        The tracks at some step.
    true_centers : array_like, shape (n_agents, 2)
        The agents' true centres at that step (pixels).

    Returns
    -------
    numpy.ndarray of int, shape (n_tracks,)
        Agent index per track, -1 for a track left over when there are more tracks than agents.
    """
    truth = np.asarray(true_centers, dtype=float).reshape(-1, 2)
    agent = np.full(len(tracks), -1, dtype=np.int64)
    if len(tracks) and len(truth):
        gap = np.hypot(*(tracks.centers[:, None, :] - truth[None, :, :]).transpose(2, 0, 1))
        rows, cols = linear_sum_assignment(gap)
        agent[rows] = cols
    return agent


def oracle(
    tracks: Tracks,
    now,
    horizon,
    bounds,
    *,
    truth,
    agents=None,
    substeps=1,
    k_sd=K_SD,
    tube_horizon=5.0,
    accel_sd=0.2,
) -> list[Predicted]:
    """The true future: the upper bound of prediction, for evaluation only.

    Parameters
    ----------
    tracks : Tracks
        The tracks at step ``now``.
    now, horizon, bounds
        As :func:`constant_velocity` (``bounds`` is only checked: the truth stays in the map).
    truth : callable
        ``truth(times) -> array (n_times, n_agents, 2)``: the true centres (pixels) of every
        agent at the given absolute times (time steps), given by the world.
    agents : array_like of int, shape (n_tracks,), optional
        Which true agent (column of ``truth``) each track follows, -1 for none; None: matched
        by :func:`match_agents` at ``now``. A track with no agent is a ghost and is dropped.
    substeps : int
        Samples of the truth per time step (>= 1); the motion is linear between samples. The
        world moves its agents linearly between steps, so 1 is exact there; a scripted mover
        that bounces between two steps is cut short by at most half a step's travel.
    k_sd, tube_horizon, accel_sd
        Checked as for :func:`tube_radius` and otherwise unused, so that every predictor takes
        the same options: the oracle's motion is exact and needs no margin.

    Returns
    -------
    list of Predicted
        One per track that follows an agent, in the tracks' order, of the track's radius (no
        uncertainty margin: the motion is the truth), starting at the agent's true centre.
    """
    now, horizon, _ = _check_window(now, horizon, bounds)
    tube_radius(tracks, horizon, k_sd, tube_horizon, accel_sd)  # the same checks as the others
    substeps = check_int("substeps", substeps, 1)
    n_samples = int(np.ceil(horizon * substeps))
    times = _knot_times(now, horizon, np.arange(1, n_samples) / substeps)
    future = np.asarray(truth(times), dtype=float)
    if future.ndim != 3 or future.shape[0] != len(times) or future.shape[2] != 2:
        raise ValueError(
            f"truth(times) must return the centres as (n_times={len(times)}, n_agents, 2), "
            f"got shape {future.shape}"
        )
    if agents is None:
        agents = match_agents(tracks, future[0])
    agents = np.asarray(agents, dtype=np.int64).reshape(-1)
    if agents.shape != (len(tracks),) or np.any((agents < -1) | (agents >= future.shape[1])):
        raise ValueError(
            f"agents must give one agent index (< {future.shape[1]}, or -1) per track "
            f"({len(tracks)}), got {agents!r}"
        )
    out = []
    for i in np.flatnonzero(agents >= 0):
        offsets = future[:, agents[i]] - tracks.centers[i]
        out.append(Predicted(int(tracks.ids[i]), float(tracks.radii[i]), Track(times, offsets)))
    return out


#: Every predictor by name.
PREDICTORS: Registry[PredictorSpec] = Registry("predictor")
PREDICTORS.register(
    "constant_velocity",
    PredictorSpec("constant_velocity", constant_velocity, "straight on, stops at the map border"),
)
PREDICTORS.register("stop", PredictorSpec("stop", stop, "stands where it is"))
PREDICTORS.register(
    "oracle",
    PredictorSpec("oracle", oracle, "the true future (evaluation only)", needs_truth=True),
)


def run_predictor(name: str, tracks: Tracks, now, horizon, bounds, **options) -> list[Predicted]:
    """Run the predictor registered as ``name`` (see :data:`PREDICTORS`); an unknown name is an
    error listing the known ones."""
    return PREDICTORS[name].predict(tracks, now, horizon, bounds, **options)
