"""What the robot knows: sensor readings, tracks and predicted motion.

The stepped world hands a planner a :class:`~mawdo.planning.sense.reading.Reading` each step
(its own state and the agents its sensor detects, :class:`~mawdo.planning.sense.sensor.Sensor`);
a tracker (:class:`~mawdo.planning.sense.tracker.Tracker`) turns readings into
:class:`~mawdo.planning.sense.reading.Tracks` (estimated centres and velocities); a predictor
(:data:`~mawdo.planning.sense.predict.PREDICTORS`) turns tracks into motions the planner's stages
consume like the scenario's scripted ones.
"""

from mawdo.planning.sense.predict import PREDICTORS, Predicted, PredictorSpec, run_predictor
from mawdo.planning.sense.reading import Policy, Reading, Tracks
from mawdo.planning.sense.sensor import Sensor, Walls
from mawdo.planning.sense.tracker import Tracker

__all__ = [
    "PREDICTORS",
    "Policy",
    "Predicted",
    "PredictorSpec",
    "Reading",
    "Sensor",
    "Tracker",
    "Tracks",
    "Walls",
    "run_predictor",
]
