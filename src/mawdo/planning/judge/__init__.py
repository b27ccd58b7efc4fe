"""Judging a run: the independent collision and kinematic checkers, per-run metrics."""
