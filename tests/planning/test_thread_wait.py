"""OpenMP threads sleep between calls unless the user chose otherwise (issue 28, item 10).

Each case imports the kernel in a fresh process (the policy is decided at import, before the
OpenMP runtime starts) with a controlled environment, and reads what the process ended with.
The numbers stay those of one thread: ``test_cost_threads.py`` runs under the new policy.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

from mawdo.planning.refine.kernel.threads import WAIT_VARIABLES

SRC = str(Path(__file__).resolve().parents[2] / "src")

PROBE = """
import json, os, sys
if sys.argv[1] == "started":  # Numba's threads already running when mawdo is imported
    from numba.np.ufunc import parallel
    parallel._launch_threads()
from mawdo.planning.refine.kernel.threads import passive_wait
print(json.dumps({"policy": os.environ.get("OMP_WAIT_POLICY"), "again": passive_wait()}))
"""


def _probe(env_extra: dict, started: bool = False) -> dict:
    env = {k: v for k, v in os.environ.items() if k not in WAIT_VARIABLES}
    env.update(env_extra, PYTHONPATH=SRC)
    out = subprocess.run(
        [sys.executable, "-c", PROBE, "started" if started else "fresh"],
        env=env,
        capture_output=True,
        text=True,
        check=True,
    ).stdout
    return json.loads(out.strip().splitlines()[-1])


def test_passive_by_default():
    got = _probe({})
    # set once, at import; a second call finds it set and leaves it
    assert got == {"policy": "passive", "again": False}


@pytest.mark.parametrize(
    "env",
    [{"OMP_WAIT_POLICY": "active"}, {"GOMP_SPINCOUNT": "300000"}, {"KMP_BLOCKTIME": "200"}],
)
def test_the_users_choice_is_kept(env):
    got = _probe(env)
    assert got["policy"] == env.get("OMP_WAIT_POLICY") and got["again"] is False


def test_not_set_once_the_runtime_runs():
    # the runtime read its environment when it started: setting it now would claim a policy
    # that is not in force
    assert _probe({}, started=True)["policy"] is None
