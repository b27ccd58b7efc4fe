"""Safety: the guard, the inevitable-collision rule and the robot's kinematic limits."""
