"""What ``mawdo plan run`` needs for a stepped run: the knowledge and sensor settings checked,
and the run built (:class:`~mawdo.planning.run.episode.EpisodeRun`).

A scenario with people (a ``[crowd]`` table) always runs in the stepped world; so does any
scenario with ``--knowledge observed``. ``oracle`` knowledge with people is offered only when they
do not see the robot (their future is then theirs alone: the world records it beforehand).
"""

from __future__ import annotations

import math

from mawdo.planning.run.policy import KNOWLEDGE

__all__ = ["sense_of", "stepped_run"]


def sense_of(sc, knowledge, static: bool, sensor_range, sensor_noise, miss_rate,
             predictor: str = "constant_velocity"):  # fmt: skip
    """``(knowledge, sensor, predictor)`` for a stepped run, or ``None`` for the planner's own
    loop.

    Raises
    ------
    ValueError
        An unknown knowledge or predictor, ``observed`` with ``--static``, oracle knowledge of
        people who see the robot, sensor settings or a predictor with oracle knowledge, a
        predictor that needs the true future; each message says what to change.
    """
    crowd = sc.spec.crowd
    if knowledge is not None and knowledge not in KNOWLEDGE:
        raise ValueError(f"--knowledge {knowledge!r}: give one of {', '.join(KNOWLEDGE)}")
    knowledge = knowledge or ("observed" if crowd is not None else "oracle")
    from mawdo.planning.sense.predict import PREDICTORS

    spec = PREDICTORS[predictor]  # an unknown name lists the known ones
    if spec.needs_truth:
        raise ValueError(
            f"--predictor {predictor}: it needs the true future; observed knowledge has none "
            "(use --knowledge oracle for the upper bound)"
        )
    sensed = sensor_range is not None or sensor_noise > 0 or miss_rate > 0
    if knowledge == "oracle" and (sensed or predictor != "constant_velocity"):
        raise ValueError("--sensor-range/--sensor-noise/--miss-rate/--predictor need "
                         "--knowledge observed")  # fmt: skip
    if static and (knowledge == "observed" or crowd is not None):
        raise ValueError("--static plans once on a frozen map: it takes no people and no "
                         "--knowledge observed; drop --static")  # fmt: skip
    if knowledge == "oracle" and crowd is not None and crowd.visible:
        raise ValueError("--knowledge oracle: these people see the robot, so their future is "
                         "not known beforehand; use --knowledge observed")  # fmt: skip
    if crowd is not None and crowd.model == "orca":
        from mawdo.planning.people.orca import require_pyrvo

        require_pyrvo()  # ImportError naming the extra to install
    if knowledge == "oracle" and crowd is None:
        return None
    sensor = _sensor(sc, sensor_range, sensor_noise, miss_rate) if sensed else None
    return knowledge, sensor, predictor


def _sensor(sc, sensor_range, sensor_noise, miss_rate):
    from mawdo.planning.sense.sensor import Sensor

    px = sc.units.length_to_px
    rng = math.inf if sensor_range is None else px(sensor_range)
    return Sensor(range=rng, noise=px(sensor_noise), miss_rate=miss_rate)


def stepped_run(sc, algorithm, seed, preset, max_steps: int, knowledge: str, sensor,
                predictor: str = "constant_velocity", threads=1):  # fmt: skip
    """The :class:`~mawdo.planning.run.episode.EpisodeRun` of ``mawdo plan run``: our planner
    with that knowledge, the people of the scenario, ``max_steps`` steps."""
    from mawdo.planning.run.episode import EpisodeRun
    from mawdo.planning.run.policy import PlannerPolicy
    from mawdo.planning.world.stepped import SteppedWorld, people_future

    run = EpisodeRun(sc, None, seed, max_steps, sensor, name=f"{algorithm}-{knowledge}")
    if knowledge == "observed":
        from mawdo.planning.sense.tracker import Tracker

        tracker = Tracker(noise=0.0) if sensor is None else Tracker.for_sensor(sensor)
        run.policy = PlannerPolicy(algorithm, preset, "observed", predictor=predictor,
                                   tracker=tracker, threads=threads)  # fmt: skip
    else:  # invisible people: their future, walked by a fresh world's people, told the planner
        run.known = people_future(sc, SteppedWorld.of(sc, seed).people, max_steps)
        run.policy = PlannerPolicy(algorithm, preset, "oracle", threads=threads)
    run.config = run.policy.config
    return run
