"""A planning run: settings, the receding-horizon loop, its result, every planner by name."""
