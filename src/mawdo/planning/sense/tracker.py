"""Tracks from readings: a constant-velocity Kalman filter per agent, Hungarian association.

Each track's state is ``(x, y, vx, vy)`` (pixels, pixels per time step) with a 4 x 4 covariance.
A step of the tracker (:meth:`Tracker.update`):

1. predicts every track to the reading's step (constant velocity, white-acceleration process
   noise, :func:`transition` and :func:`process_noise`);
2. associates the detections with the tracks by the Hungarian method
   (:func:`scipy.optimize.linear_sum_assignment`) on the squared Mahalanobis distance of each
   detection from each predicted centre (:func:`mahalanobis2`), pairs outside the gate being
   forbidden unless the detection lies inside the track's predicted disc;
3. corrects the matched tracks with their detections (the Joseph form, which keeps the
   covariance symmetric and positive semi-definite); a pair admitted by the disc alone is a
   maneuver (a turn, a bounce off a wall), and its track's covariance is first widened by
   :func:`velocity_jump` so that it takes the new velocity at once
   (docs/deviations.md#d-track-gate); with ``strays=True`` a second pass then pairs a track and
   a detection both left over when the detection lies within the distance the agent can have
   strayed from the prediction (:meth:`Tracker._strays`), also as a maneuver;
4. counts a miss for every unmatched track, which stays reported at its predicted centre (with
   the predicted, growing covariance) until it has been missed on more than ``max_missed``
   consecutive steps, and then dies;
5. starts a track at every unmatched detection: the detected centre, velocity 0 with a large
   variance, reported at once so that the planner never ignores a person it sees.

The filter is written as array operations over all tracks at once, not with
``filterpy.kalman.KalmanFilter`` objects: filterpy is an optional extra (``crowd``) while
observed knowledge is part of the core planner, and one filter object per track would make the
step a Python loop over agents, with the association's innovation covariances gathered from
each object. The tests check this filter against filterpy's step by step.
"""

from __future__ import annotations

import numpy as np
from scipy.optimize import linear_sum_assignment

from mawdo.planning.sense.reading import Reading, Tracks
from mawdo.util.validate import check_bool, check_int, check_real

__all__ = [
    "NOISE_FLOOR",
    "Tracker",
    "mahalanobis2",
    "process_noise",
    "transition",
    "velocity_jump",
]

#: Smallest measurement noise s.d. the filter assumes (pixels): a noiseless sensor still gets a
#: filter with a positive-definite innovation covariance, and a tenth of a pixel is below any
#: error that matters to the planner.
NOISE_FLOOR = 0.1

# A forbidden pair's cost: finite (linear_sum_assignment refuses a matrix with no complete
# finite matching) and larger than any sum of admissible costs, so the assignment takes as many
# admissible pairs as it can and only then the cheapest.
_FORBIDDEN = 1e12


def transition(dt: float) -> np.ndarray:
    """Constant-velocity transition matrix for a time step ``dt`` (time steps), ``(4, 4)``,
    state ``(x, y, vx, vy)``."""
    return np.kron(np.array([[1.0, dt], [0.0, 1.0]]), np.eye(2))


def process_noise(dt: float, accel_sd: float) -> np.ndarray:
    """White-acceleration process noise over ``dt`` time steps, ``(4, 4)``.

    The discrete white-noise acceleration model (Bar-Shalom, Li & Kirubarajan 2001, Sec. 6.3.3):
    during each step the agent's acceleration is constant, drawn independently per axis and per
    step with s.d. ``accel_sd`` (pixels per time step squared), so per axis
    ``Q = accel_sd^2 g g^T`` with ``g = (dt^2 / 2, dt)``.
    """
    g = np.array([0.5 * dt * dt, dt])
    # x and y independent: the same block on (x, vx) and on (y, vy)
    return np.kron(accel_sd**2 * np.outer(g, g), np.eye(2))


def velocity_jump(dt: float, speed_sd: float) -> np.ndarray:
    """Covariance added to a track that maneuvered, ``(4, 4)``: its velocity jumped at the start
    of the last ``dt`` steps by a change of s.d. ``speed_sd`` per axis (pixels per time step), so
    per axis ``speed_sd^2 h h^T`` with ``h = (dt, 1)``; the correction then takes the velocity
    the detection shows instead of averaging it with the old one."""
    h = np.array([dt, 1.0])
    return np.kron(speed_sd**2 * np.outer(h, h), np.eye(2))


def mahalanobis2(centers, cov, detections, noise_var: float) -> np.ndarray:
    """Squared Mahalanobis distance of each detection from each predicted centre.

    Parameters
    ----------
    centers : array_like, shape (n, 2)
        Predicted track centres (pixels).
    cov : array_like, shape (n, 2, 2)
        Their position covariances (pixels squared).
    detections : array_like, shape (m, 2)
        Detected centres (pixels).
    noise_var : float
        Measurement noise variance per axis (pixels squared), > 0.

    Returns
    -------
    numpy.ndarray, shape (n, m)
        ``y^T S^-1 y`` with ``y`` the innovation and ``S = cov + noise_var I``.
    """
    y = np.asarray(detections, float)[None, :, :] - np.asarray(centers, float)[:, None, :]
    s_inv = np.linalg.inv(np.asarray(cov, float) + noise_var * np.eye(2))
    return np.einsum("nmi,nij,nmj->nm", y, s_inv, y)


def _largest_sd(block: np.ndarray) -> np.ndarray:
    """Square root of the largest eigenvalue of each symmetric 2 x 2 block ``(n, 2, 2)``: the
    s.d. along the worst direction."""
    a, b, c = block[:, 0, 0], block[:, 0, 1], block[:, 1, 1]
    top = 0.5 * (a + c) + np.sqrt((0.5 * (a - c)) ** 2 + b * b)
    return np.sqrt(np.clip(top, 0.0, None))


class Tracker:
    """Multi-agent tracker: constant-velocity Kalman filters and Hungarian association.

    Parameters
    ----------
    noise : float
        Measurement noise s.d. per coordinate (pixels), >= 0: the sensor's ``noise``; the filter
        uses at least :data:`NOISE_FLOOR`.
    accel_sd : float
        Process noise: s.d. of an agent's acceleration per axis and step (pixels per time step
        squared), >= 0. The default 0.2 is 5 % of the default robot speed (4 px per step) per
        step: a person who turns around at 2 px per step is followed within a few steps, while a
        straight walker's velocity is still averaged over several readings.
    gate : float
        Association gate, a Mahalanobis distance (standard deviations), > 0: a detection may be
        matched with a track only when it is within ``gate`` of the predicted centre, or inside
        the track's disc there (a centre inside an agent's disc is that agent's under any noise
        the filter expects; this lets a track follow an agent that bounced off a wall, as a
        maneuver, see :func:`velocity_jump`). The default 4 leaves a detection outside it with
        probability ``exp(-8) = 3e-4``.
    max_missed : int
        Most consecutive missed steps a track survives, >= 0: while missed it is predicted
        forward and reported; missed once more, it is dropped. The default 5 keeps a person who
        walks behind a pillar for five steps.
    birth_speed_sd : float
        S.d. of a new track's velocity per axis (pixels per time step), > 0: its velocity is 0
        with this uncertainty until a second detection; also the s.d. of a maneuver's velocity
        jump. The default 4 is the default robot speed, above the speed of the scenes' movers.
    strays : bool
        Pair the tracks and detections the gated assignment left over in a second pass, a
        detection with a track when it lies within the track's radius plus ``2
        birth_speed_sd`` pixels per step since the track's last detection (a velocity changed
        by up to twice the speed prior: a person who turned round at their goal, or walked on
        unseen for a few steps). Without it such an agent is tracked twice for up to
        ``max_missed`` steps: a new track at the detection, and a ghost coasting on where it was
        going. Off by default, as the committed crowd studies were made; on in
        :meth:`for_sensor`. It matters most behind an imperfect sensor (measured in
        ``benchmarks/log/crowd.md``, "A second association pass").

    Notes
    -----
    Reported s.d.s are along the worst direction: ``position_sd`` and ``velocity_sd`` are the
    square roots of the largest eigenvalues of the position and velocity blocks of a track's
    covariance.
    """

    def __init__(
        self,
        noise: float,
        accel_sd: float = 0.2,
        gate: float = 4.0,
        max_missed: int = 5,
        birth_speed_sd: float = 4.0,
        strays: bool = False,
    ) -> None:
        self.noise = check_real("noise", noise, 0.0)
        self.accel_sd = check_real("accel_sd", accel_sd, 0.0)
        self.gate = check_real("gate", gate, 0.0, low_open=True)
        self.max_missed = check_int("max_missed", max_missed, 0)
        self.birth_speed_sd = check_real("birth_speed_sd", birth_speed_sd, 0.0, low_open=True)
        self.strays = check_bool("strays", strays)
        self.noise_var = max(self.noise, NOISE_FLOOR) ** 2
        self.reset()

    @classmethod
    def for_sensor(cls, sensor, **options) -> Tracker:
        """A tracker whose measurement noise is ``sensor.noise``, pairing strays (``strays``
        True unless given; other options as given)."""
        return cls(sensor.noise, **{"strays": True, **options})

    def reset(self) -> None:
        """Forget every track; ids start again at 0 (a new episode)."""
        self._ids = np.empty(0, dtype=np.int64)
        self._x = np.empty((0, 4))
        self._cov = np.empty((0, 4, 4))
        self._missed = np.empty(0, dtype=np.int64)
        self._radius_sum = np.empty(0)
        self._hits = np.empty(0, dtype=np.int64)
        self._step: int | None = None
        self._next_id = 0

    def __len__(self) -> int:
        return len(self._ids)

    def update(self, reading: Reading) -> Tracks:
        """Take one step's reading; return the tracks at its step.

        Parameters
        ----------
        reading : Reading
            This step's detections; its ``step`` must be later than the previous reading's
            (call :meth:`reset` for a new episode).

        Returns
        -------
        Tracks
            Every live track (matched, newly born, or predicted while missed), by increasing id.
        """
        step = int(reading.step)
        dt = 1.0  # no track before the first reading: nothing is predicted or turned
        if self._step is not None:
            if step <= self._step:
                raise ValueError(
                    f"reading of step {step} after step {self._step}: readings must come in "
                    "increasing steps; call reset() to start a new episode"
                )
            dt = float(step - self._step)
            self._predict(dt)
        self._step = step
        z, radii = reading.centers, reading.radii
        rows, cols, turned = self._associate(z, dt)
        if turned.any():
            self._cov[rows[turned]] += velocity_jump(dt, self.birth_speed_sd)
        self._correct(rows, z[cols], radii[cols])
        missed = np.ones(len(self._ids), dtype=bool)
        missed[rows] = False
        self._missed[missed] += 1
        self._drop(self._missed > self.max_missed)
        born = np.ones(len(z), dtype=bool)
        born[cols] = False
        self._birth(z[born], radii[born])
        return self.tracks()

    def tracks(self) -> Tracks:
        """The live tracks now (see :meth:`update`)."""
        return Tracks(
            ids=self._ids.copy(),
            centers=self._x[:, :2].copy(),
            velocities=self._x[:, 2:].copy(),
            radii=self._radius_sum / self._hits,
            position_sd=_largest_sd(self._cov[:, :2, :2]),
            velocity_sd=_largest_sd(self._cov[:, 2:, 2:]),
            missed=self._missed.copy(),
        )

    def _predict(self, dt: float) -> None:
        f = transition(dt)
        self._x = self._x @ f.T
        self._cov = f @ self._cov @ f.T + process_noise(dt, self.accel_sd)

    def _associate(self, z: np.ndarray, dt: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Matched (track row, detection index) pairs, sorted by track row, and whether each
        pair is outside the Mahalanobis gate (a maneuver: admitted by the disc rule or, with
        ``strays``, by :meth:`_strays`); ``dt`` steps since the last reading."""
        if len(self._ids) == 0 or len(z) == 0:
            none = np.empty(0, dtype=np.int64)
            return none, none, np.empty(0, dtype=bool)
        centers = self._x[:, :2]
        d2 = mahalanobis2(centers, self._cov[:, :2, :2], z, self.noise_var)
        gap = np.hypot(*(z[None, :, :] - centers[:, None, :]).transpose(2, 0, 1))
        radius = self._radius_sum / self._hits
        inside = gap <= radius[:, None]
        gated = d2 <= self.gate**2
        allowed = gated | inside
        rows, cols = linear_sum_assignment(np.where(allowed, d2, _FORBIDDEN))
        keep = allowed[rows, cols]
        rows, cols = rows[keep], cols[keep]
        if self.strays and len(rows) < min(gap.shape):  # a track and a detection left over
            more_r, more_c = self._strays(gap, radius, rows, cols, dt)
            rows, cols = np.concatenate([rows, more_r]), np.concatenate([cols, more_c])
            order = np.argsort(rows, kind="stable")
            rows, cols = rows[order], cols[order]
        return rows, cols, ~gated[rows, cols]

    def _strays(self, gap, radius, rows, cols, dt: float) -> tuple[np.ndarray, np.ndarray]:
        """(track row, detection index) pairs among those the first assignment left over: each
        detection within its track's radius plus ``2 birth_speed_sd`` px per step since the
        track's last detection (``gap``: centre distances, tracks x detections, px; ``radius``:
        the tracks' radii, px), nearest first by the Hungarian method."""
        left_r = np.setdiff1d(np.arange(gap.shape[0]), rows)
        left_c = np.setdiff1d(np.arange(gap.shape[1]), cols)
        sub = gap[np.ix_(left_r, left_c)]
        steps = self._missed[left_r] + dt  # the missed count is the previous step's here
        reach = radius[left_r] + 2.0 * self.birth_speed_sd * steps
        allowed = sub <= reach[:, None]
        r, c = linear_sum_assignment(np.where(allowed, sub, _FORBIDDEN))
        keep = allowed[r, c]
        return left_r[r[keep]], left_c[c[keep]]

    def _correct(self, rows: np.ndarray, z: np.ndarray, radii: np.ndarray) -> None:
        if len(rows) == 0:
            return
        x, p = self._x[rows], self._cov[rows]
        r = self.noise_var * np.eye(2)
        s = p[:, :2, :2] + r
        gain = p[:, :, :2] @ np.linalg.inv(s)  # K = P H^T S^-1, (k, 4, 2)
        x = x + np.einsum("kij,kj->ki", gain, z - x[:, :2])
        i_kh = np.broadcast_to(np.eye(4), p.shape).copy()
        i_kh[:, :, :2] -= gain  # I - K H, H picking (x, y)
        p = i_kh @ p @ i_kh.transpose(0, 2, 1) + gain @ r @ gain.transpose(0, 2, 1)
        self._x[rows] = x
        self._cov[rows] = 0.5 * (p + p.transpose(0, 2, 1))
        self._missed[rows] = 0
        self._radius_sum[rows] += radii
        self._hits[rows] += 1

    def _drop(self, dead: np.ndarray) -> None:
        if not dead.any():
            return
        live = ~dead
        self._ids, self._x, self._cov = self._ids[live], self._x[live], self._cov[live]
        self._missed, self._hits = self._missed[live], self._hits[live]
        self._radius_sum = self._radius_sum[live]

    def _birth(self, z: np.ndarray, radii: np.ndarray) -> None:
        k = len(z)
        if k == 0:
            return
        x = np.column_stack([z, np.zeros((k, 2))])
        var = [self.noise_var, self.noise_var, self.birth_speed_sd**2, self.birth_speed_sd**2]
        ids = np.arange(self._next_id, self._next_id + k, dtype=np.int64)
        self._next_id += k
        self._ids = np.concatenate([self._ids, ids])
        self._x = np.vstack([self._x, x])
        self._cov = np.concatenate([self._cov, np.broadcast_to(np.diag(var), (k, 4, 4))])
        self._missed = np.concatenate([self._missed, np.zeros(k, dtype=np.int64)])
        self._radius_sum = np.concatenate([self._radius_sum, radii])
        self._hits = np.concatenate([self._hits, np.ones(k, dtype=np.int64)])
