"""Performance harness (not tests): ``make bench`` / ``python -m benchmarks``."""
