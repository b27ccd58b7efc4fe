"""What the robot knows: sensor readings, tracks and predicted motion.

The stepped world hands a planner a :class:`~mawdo.planning.sense.reading.Reading` each step
(its own state and the agents its sensor detects); a tracker turns readings into
:class:`~mawdo.planning.sense.reading.Tracks` (estimated centres and velocities); a predictor turns
tracks into motions the planner's stages consume like the scenario's scripted ones.
"""

from mawdo.planning.sense.reading import Policy, Reading, Tracks

__all__ = ["Policy", "Reading", "Tracks"]
