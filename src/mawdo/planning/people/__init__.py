"""People who react: pedestrians stepped one time step at a time, CrowdNav's scenes and the
crowd-navigation robot baselines.

Units are the world's: positions in pixels, time in time steps, velocities in pixels per time
step. A metre scene has a resolution ``res`` (metres per pixel) and a time step ``dt``
(seconds): 1 m/s is ``dt / res`` pixels per step.

The people interface
--------------------
Every model is a :class:`~mawdo.planning.people.base.People` of ``n`` people::

    people.radii            # (n,) pixels
    people.preferred_speed  # (n,) pixels per step
    people.goals            # (n, 2) pixels, each person's current goal
    people.positions()      # (n, 2) centres now (a copy)
    people.velocities()     # (n, 2) velocities over the last step (a copy)
    people.step(robot_position, robot_velocity, robot_radius, visible)  # advance one step

built as ``Model(positions, goals, radii, preferred_speed, *, params, bounds, obstacles=(),
goal_policy=None, rng=None, arrival_time=1.0, velocities=None)``: ``bounds`` is the map's
``(width, height)``, ``obstacles`` the static walls as ``(k, 2)`` vertex arrays, ``goal_policy``
what a person who reaches its goal (comes within its radius of it) does (default
:class:`~mawdo.planning.people.base.KeepGoal`; CrowdNav's are
:class:`~mawdo.planning.people.crowdnav.CircleGoals` and
:class:`~mawdo.planning.people.crowdnav.SquareGoals`), ``rng`` the
:class:`numpy.random.Generator` that draws new goals (same seed, same trajectories).

``step`` takes the robot's state at the same time as the people's current one. With
``visible=True`` people avoid the robot as one of them (it does not yield); with
``visible=False`` it does not exist for them. People never enter a wall or leave the map (the
move guard of :class:`~mawdo.planning.people.walls.Walls`).

Models
------
:class:`~mawdo.planning.people.orca.OrcaPeople`
    ORCA through ``pyrvo`` (RVO2), set up as CrowdNav's humans (needs ``mawdo[crowd]``).
:class:`~mawdo.planning.people.social_force.SocialForcePeople`
    The social force model (Helbing & Molnár 1995), in NumPy.

Scenes and robots
-----------------
:func:`~mawdo.planning.people.crowdnav.circle_crossing` and
:func:`~mawdo.planning.people.crowdnav.square_crossing` build CrowdNav's scenes;
:class:`~mawdo.planning.people.robots.OrcaRobot` and
:class:`~mawdo.planning.people.robots.SocialForceRobot` are the robot baselines.
"""

from mawdo.planning.people.base import GoalPolicy, KeepGoal, People, preferred_velocities
from mawdo.planning.people.crowdnav import (
    CircleGoals,
    CrowdScene,
    SquareGoals,
    circle_crossing,
    square_crossing,
)
from mawdo.planning.people.orca import OrcaParams, OrcaPeople
from mawdo.planning.people.robots import OrcaRobot, SocialForceRobot
from mawdo.planning.people.social_force import SocialForceParams, SocialForcePeople

__all__ = [
    "CircleGoals",
    "CrowdScene",
    "GoalPolicy",
    "KeepGoal",
    "OrcaParams",
    "OrcaPeople",
    "OrcaRobot",
    "People",
    "SocialForceParams",
    "SocialForcePeople",
    "SocialForceRobot",
    "SquareGoals",
    "circle_crossing",
    "preferred_velocities",
    "square_crossing",
]
