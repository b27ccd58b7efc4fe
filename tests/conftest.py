import os
import sys

os.environ.setdefault("MPLBACKEND", "Agg")

from hypothesis import settings  # noqa: E402

# CI runs the same examples every time (a red build must be reproducible locally with CI=true).
settings.register_profile("ci", derandomize=True, deadline=None, print_blob=True)
if os.environ.get("CI", "").lower() in ("1", "true", "yes"):
    settings.load_profile("ci")


_EXIT = {}


def pytest_sessionfinish(session, exitstatus):
    _EXIT["status"] = int(exitstatus)


def pytest_unconfigure(config):
    # OMPL's nanobind bindings list every type still alive when the interpreter finalizes
    # ("nanobind: leaked 174 types!", ~30 lines after the summary of every run that used OMPL):
    # a report of the binding's teardown order, not of our code, and the bindings expose no
    # switch for it. Once pytest has written its summary, a run that imported OMPL ends here
    # with pytest's exit status, so those lines never reach the output.
    if "ompl" in sys.modules and "status" in _EXIT:
        sys.stdout.flush()
        sys.stderr.flush()
        os._exit(_EXIT["status"])
