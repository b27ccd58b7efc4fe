"""The tracker against filterpy's Kalman filter, the alpha-beta steady state, and its track
management: association through a crossing, misses, deaths and births."""

import numpy as np
import pytest
from filterpy.common import Q_discrete_white_noise
from filterpy.kalman import KalmanFilter

from mawdo.planning.sense.reading import Reading
from mawdo.planning.sense.tracker import (
    NOISE_FLOOR,
    Tracker,
    mahalanobis2,
    process_noise,
    transition,
    velocity_jump,
)


def reading(step, centers, radii=None):
    centers = np.asarray(centers, dtype=float).reshape(-1, 2)
    radii = np.full(len(centers), 5.0) if radii is None else radii
    return Reading(step, (0.0, 0.0), (0.0, 0.0), (0.0, 0.0), centers, radii)


def walker(start, velocity, steps):
    return np.asarray(start, float) + np.arange(steps)[:, None] * np.asarray(velocity, float)


def reference_filter(noise, accel_sd, birth_speed_sd, first):
    """filterpy's filter for one track, born at detection ``first``."""
    kf = KalmanFilter(dim_x=4, dim_z=2)
    kf.F = np.array([[1, 0, 1, 0], [0, 1, 0, 1], [0, 0, 1, 0], [0, 0, 0, 1]], dtype=float)
    kf.H = np.array([[1, 0, 0, 0], [0, 1, 0, 0]], dtype=float)
    kf.R = np.eye(2) * max(noise, NOISE_FLOOR) ** 2
    kf.Q = Q_discrete_white_noise(2, dt=1.0, var=accel_sd**2, block_size=2, order_by_dim=False)
    kf.x = np.array([first[0], first[1], 0.0, 0.0])
    kf.P = np.diag([max(noise, NOISE_FLOOR) ** 2] * 2 + [birth_speed_sd**2] * 2)
    return kf


@pytest.mark.parametrize(("noise", "accel_sd"), [(1.5, 0.2), (0.0, 0.05), (0.4, 1.0)])
def test_one_track_follows_filterpy_step_by_step(noise, accel_sd):
    rng = np.random.default_rng(3)
    truth = walker((20.0, 30.0), (1.5, 0.7), 40) + rng.normal(0, 0.3, (40, 2)).cumsum(axis=0)
    z = truth + rng.normal(0.0, noise, truth.shape)
    missed = {7, 8, 20}  # steps without a detection: filterpy predicts only
    tracker = Tracker(noise, accel_sd=accel_sd, gate=50.0, max_missed=3, birth_speed_sd=3.0)
    kf = reference_filter(noise, accel_sd, 3.0, z[0])
    tracker.update(reading(0, z[:1]))
    for k in range(1, 40):
        kf.predict()
        if k in missed:
            tracks = tracker.update(reading(k, np.empty((0, 2))))
        else:
            kf.update(z[k])
            tracks = tracker.update(reading(k, z[k : k + 1]))
        assert tracks.ids.tolist() == [0]
        assert np.allclose(tracks.centers[0], kf.x[:2], rtol=0, atol=1e-9)
        assert np.allclose(tracks.velocities[0], kf.x[2:], rtol=0, atol=1e-9)
        p = kf.P
        assert np.isclose(tracks.position_sd[0], np.sqrt(np.linalg.eigvalsh(p[:2, :2])[-1]))
        assert np.isclose(tracks.velocity_sd[0], np.sqrt(np.linalg.eigvalsh(p[2:, 2:])[-1]))


@pytest.mark.parametrize(("noise", "accel_sd"), [(1.0, 0.2), (2.0, 0.1), (0.5, 0.5)])
def test_steady_state_is_the_alpha_beta_filter(noise, accel_sd):
    # Kalata's tracking index and the steady-state gains of the alpha-beta filter
    # (Bar-Shalom, Li & Kirubarajan 2001, Sec. 6.5.3): posterior variances
    # alpha sigma^2 (position) and beta (alpha - beta / 2) / (1 - alpha) sigma^2 (velocity)
    lam = accel_sd / noise
    root = np.sqrt(lam**2 + 8 * lam)
    alpha = -(lam**2 + 8 * lam - (lam + 4) * root) / 8
    beta = (lam**2 + 4 * lam - lam * root) / 4
    tracker = Tracker(noise, accel_sd=accel_sd)
    for k in range(300):  # the centre does not matter to the covariance: one still agent
        tracks = tracker.update(reading(k, [(50.0, 50.0)]))
    assert np.isclose(tracks.position_sd[0], np.sqrt(alpha) * noise, rtol=1e-9)
    vel_var = beta * (alpha - beta / 2) / (1 - alpha) * noise**2
    assert np.isclose(tracks.velocity_sd[0], np.sqrt(vel_var), rtol=1e-9)


def test_velocity_is_recovered_without_noise():
    tracker = Tracker(0.0)
    path = walker((10.0, 10.0), (2.0, -1.0), 6)
    for k, z in enumerate(path):
        tracks = tracker.update(reading(k, [z]))
        if k >= 2:
            assert np.allclose(tracks.velocities[0], (2.0, -1.0), atol=1e-3)
    assert np.allclose(tracks.centers[0], path[-1], atol=1e-3)


def test_velocity_is_recovered_with_noise():
    errors = []
    for seed in range(20):
        rng = np.random.default_rng(seed)
        z = walker((10.0, 10.0), (2.0, -1.0), 30) + rng.normal(0.0, 1.0, (30, 2))
        tracker = Tracker(1.0)
        for k in range(30):
            tracks = tracker.update(reading(k, z[k : k + 1]))
        err = tracks.velocities[0] - (2.0, -1.0)
        assert np.all(np.abs(err) < 4.0 * tracks.velocity_sd[0])
        errors.append(err)
    # unbiased: the mean of 20 errors is well inside its own s.d. (0.33 / sqrt(20) = 0.07)
    assert np.all(np.abs(np.mean(errors, axis=0)) < 0.25)
    assert np.mean(np.hypot(*np.transpose(errors))) < 0.4


def test_crossing_walkers_keep_their_identities():
    rng = np.random.default_rng(1)
    a = walker((0.0, 50.0), (2.0, 0.0), 50)  # the two centres coincide at step 25
    b = walker((50.0, 0.0), (0.0, 2.0), 50)
    tracker = Tracker(0.5)
    for k in range(50):
        z = np.vstack([a[k], b[k]]) + rng.normal(0.0, 0.5, (2, 2))
        tracks = tracker.update(reading(k, z[rng.permutation(2)]))
        if k == 0:
            id_a = tracks.ids[np.argmin(np.hypot(*(tracks.centers - a[0]).T))]
        if k == 24:  # just before they meet: the estimates are on their walkers
            assert np.hypot(*(tracks.centers[tracks.ids == id_a][0] - a[k])) < 2.0
    assert len(tracks) == 2 and sorted(tracks.ids) == [0, 1]
    est_a = tracks.centers[tracks.ids == id_a][0]
    est_b = tracks.centers[tracks.ids != id_a][0]
    assert np.hypot(*(est_a - a[-1])) < 3.0 and np.hypot(*(est_b - b[-1])) < 3.0
    assert np.allclose(tracks.velocities[tracks.ids == id_a][0], (2.0, 0.0), atol=0.6)


def test_a_missed_track_is_predicted_and_found_again():
    tracker = Tracker(0.0, max_missed=2)
    path = walker((10.0, 10.0), (3.0, 1.0), 12)
    for k in range(8):
        before = tracker.update(reading(k, path[k : k + 1]))
    coast = tracker.update(reading(8, np.empty((0, 2))))
    assert coast.ids.tolist() == [0]
    assert np.allclose(coast.centers[0], before.centers[0] + before.velocities[0])
    assert np.allclose(coast.velocities[0], before.velocities[0])
    assert coast.position_sd[0] > before.position_sd[0]
    coast2 = tracker.update(reading(9, np.empty((0, 2))))
    assert coast2.position_sd[0] > coast.position_sd[0]
    back = tracker.update(reading(10, path[10:11]))
    assert back.ids.tolist() == [0]
    assert back.position_sd[0] < coast2.position_sd[0]


def test_a_track_dies_after_max_missed_steps_and_a_new_one_is_born():
    tracker = Tracker(0.0, max_missed=2)
    for k in range(3):
        tracker.update(reading(k, [(10.0 + k, 10.0)]))
    assert len(tracker.update(reading(3, []))) == 1
    assert len(tracker.update(reading(4, []))) == 1
    assert len(tracker.update(reading(5, []))) == 0  # missed a third time
    reborn = tracker.update(reading(6, [(16.0, 10.0)]))
    assert reborn.ids.tolist() == [1]
    assert np.array_equal(reborn.velocities, [[0.0, 0.0]])
    never = Tracker(0.0, max_missed=0)
    never.update(reading(0, [(1.0, 1.0)]))
    assert len(never.update(reading(1, []))) == 0


def test_births_are_reported_at_once_with_a_wide_velocity():
    tracker = Tracker(2.0, birth_speed_sd=3.0)
    first = tracker.update(reading(0, [(10.0, 10.0)], [4.0]))
    tracks = tracker.update(reading(1, [(11.0, 10.0), (80.0, 60.0)], [4.0, 7.0]))
    assert tracks.ids.tolist() == [0, 1]
    born = 1
    assert np.array_equal(tracks.centers[born], [80.0, 60.0])
    assert np.array_equal(tracks.velocities[born], [0.0, 0.0])
    assert tracks.velocity_sd[born] == 3.0 and tracks.position_sd[born] == 2.0
    assert tracks.radii.tolist() == [4.0, 7.0]
    assert first.position_sd[0] == 2.0
    # two detections at once, no track yet: two births
    assert Tracker(0.0).update(reading(0, [(1.0, 1.0), (9.0, 9.0)])).ids.tolist() == [0, 1]


def test_the_radius_is_the_running_mean_of_the_detections():
    tracker = Tracker(0.0)
    for k, r in enumerate([4.0, 6.0, 8.0]):
        tracks = tracker.update(reading(k, [(10.0 + k, 0.0)], [r]))
    assert tracks.radii.tolist() == [6.0]


def test_a_reversal_inside_the_disc_keeps_the_track():
    # the agent turns back at step 6 (a bounce): its detection is far outside the Mahalanobis
    # gate of a low-noise track, but inside the track's disc (radius 5), so the track follows it
    tracker = Tracker(0.0, accel_sd=0.05, gate=4.0)
    xs = [10.0 + 2.0 * min(k, 6) - 2.0 * max(k - 6, 0) for k in range(12)]
    for k, x in enumerate(xs[:7]):
        tracks = tracker.update(reading(k, [(x, 20.0)]))
    f = transition(1.0)
    cov = (f @ tracker._cov[0] @ f.T + process_noise(1.0, 0.05))[None, :2, :2]  # noqa: SLF001
    d2 = mahalanobis2(tracks.centers + tracks.velocities, cov, [(xs[7], 20.0)], tracker.noise_var)
    assert d2[0, 0] > 16.0  # the gate alone would drop it
    for k in range(7, 12):
        tracks = tracker.update(reading(k, [(xs[k], 20.0)]))
        assert tracks.ids.tolist() == [0]
        # a maneuver: the velocity is taken from the detection at once, not averaged in
        assert np.allclose(tracks.velocities[0], (-2.0, 0.0), atol=0.01)


def test_a_velocity_jump_is_a_widened_velocity_before_the_step():
    rng = np.random.default_rng(2)
    a = rng.normal(size=(4, 4))
    p = a @ a.T
    for dt in (1.0, 2.5):
        f = transition(dt)
        widened = p + np.diag([0.0, 0.0, 9.0, 9.0])
        assert np.allclose(f @ widened @ f.T - f @ p @ f.T, velocity_jump(dt, 3.0))


def test_readings_must_come_in_order_and_reset_restarts():
    tracker = Tracker(1.0)
    tracker.update(reading(4, [(1.0, 1.0)]))
    with pytest.raises(ValueError, match="increasing steps"):
        tracker.update(reading(4, [(1.0, 1.0)]))
    tracker.reset()
    assert len(tracker) == 0
    assert tracker.update(reading(0, [(5.0, 5.0)])).ids.tolist() == [0]


def test_uneven_steps_predict_over_the_gap():
    tracker = Tracker(0.0)
    for k in (0, 1, 2):
        tracker.update(reading(k, [(2.0 * k, 0.0)]))
    coast = tracker.update(reading(5, []))
    assert np.allclose(coast.centers[0], (10.0, 0.0), atol=1e-2)


@pytest.mark.parametrize(
    ("kwargs", "field"),
    [
        ({"noise": -0.5}, "noise"),
        ({"noise": 1.0, "accel_sd": -1.0}, "accel_sd"),
        ({"noise": 1.0, "gate": 0.0}, "gate"),
        ({"noise": 1.0, "max_missed": -1}, "max_missed"),
        ({"noise": 1.0, "max_missed": 2.5}, "max_missed"),
        ({"noise": 1.0, "birth_speed_sd": 0.0}, "birth_speed_sd"),
    ],
)
def test_bad_parameters_name_the_field(kwargs, field):
    with pytest.raises(ValueError, match=field):
        Tracker(**kwargs)


def test_for_sensor_takes_the_sensor_noise():
    from mawdo.planning.sense.sensor import Sensor

    assert Tracker.for_sensor(Sensor(noise=2.5), gate=3.0).noise_var == 2.5**2


def _turning_walker(strays):
    # a small agent (radius 2) walking at 3 px a step turns round at step 6: its detection lands
    # 6 px from the prediction, outside the disc (radius 2) and the Mahalanobis gate
    tracker = Tracker(0.0, gate=4.0, birth_speed_sd=4.0, strays=strays)
    xs = [10.0 + 3.0 * min(k, 6) - 3.0 * max(k - 6, 0) for k in range(12)]
    out = [tracker.update(reading(k, [(x, 20.0)], radii=np.array([2.0]))) for k, x in enumerate(xs)]
    return tracker, xs, out


def test_a_turn_beyond_the_disc_and_the_gate_leaves_a_ghost_without_strays():
    tracker, xs, out = _turning_walker(strays=False)
    assert out[6].ids.tolist() == [0]
    assert out[7].ids.tolist() == [0, 1]  # the old track coasts on, missed; a new one is born
    assert out[7].missed.tolist() == [1, 0]
    assert out[7].centers[0, 0] > xs[6]  # the ghost goes on where the walker was going


def test_a_turn_within_its_stray_keeps_the_track_with_strays():
    # 6 px from the prediction is within 2 + 2 x 4 px of a track detected a step ago
    tracker, xs, out = _turning_walker(strays=True)
    for k, tracks in enumerate(out):
        assert tracks.ids.tolist() == [0], k
        assert tracks.missed.tolist() == [0], k
    # paired as a maneuver: the new velocity is taken at once
    assert np.allclose(out[-1].velocities[0], (-3.0, 0.0), atol=0.01)


@pytest.mark.parametrize(("offset", "same"), [(20.0, True), (30.0, False)])
def test_the_stray_distance_grows_with_the_steps_unseen(offset, same):
    # a walker (radius 5, 2 px a step) unseen at steps 5 and 6 reappears at step 7 ``offset`` px
    # aside of where it was going: its stray distance is 5 + 2 x 4 x 3 = 29 px (three steps since
    # its last detection), so 20 px is the same agent and 30 px someone else
    tracker = Tracker(0.0, birth_speed_sd=4.0, strays=True)
    for k in range(5):
        tracker.update(reading(k, [(10.0 + 2.0 * k, 20.0)]))
    tracker.update(reading(5, []))
    tracker.update(reading(6, []))
    tracks = tracker.update(reading(7, [(24.0, 20.0 + offset)]))
    assert tracks.ids.tolist() == ([0] if same else [0, 1])
    assert tracks.missed.tolist() == ([0] if same else [3, 0])


def test_a_detection_beyond_any_stray_is_a_new_agent():
    # the walker is missed at step 5 while someone appears 60 px away: farther than the
    # walker's radius plus 2 x 4 px a step could take it, so a new track, the walker's coasting
    tracker = Tracker(0.0, birth_speed_sd=4.0, strays=True)
    for k in range(5):
        tracker.update(reading(k, [(10.0 + 2.0 * k, 20.0)]))
    tracks = tracker.update(reading(5, [(80.0, 20.0)]))
    assert tracks.ids.tolist() == [0, 1]
    assert tracks.missed.tolist() == [1, 0]
    assert np.allclose(tracks.centers[0], (20.0, 20.0))


def test_strays_must_be_a_bool_and_for_sensor_turns_them_on():
    from mawdo.planning.sense.sensor import Sensor

    with pytest.raises(TypeError, match="strays"):
        Tracker(1.0, strays="yes")
    assert Tracker(1.0).strays is False
    assert Tracker.for_sensor(Sensor(noise=1.0)).strays is True
    assert Tracker.for_sensor(Sensor(noise=1.0), strays=False).strays is False
