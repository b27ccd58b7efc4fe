"""The guard's later counts (inevitable steps, kinematic violations) reach the payload and the
metrics, and payloads written before them read back as zero."""

import dataclasses
import io

import numpy as np

from mawdo.planning import plan
from mawdo.planning.judge.metrics import METRICS, run_metrics
from mawdo.planning.run.result import result_from_bytes, result_to_bytes
from mawdo.planning.scenes import generate_scene


def test_inevitable_and_kinematic_counts_round_trip_and_reach_the_metrics():
    sc = generate_scene("forest", 1, 0).scenario
    res = dataclasses.replace(
        plan(sc, "mawdo", seed=1, config="quick"), inevitable=3, kinematic_violations=2
    )
    back = result_from_bytes(result_to_bytes(res), sc)
    assert (back.inevitable, back.kinematic_violations) == (3, 2)
    assert (back.holds, back.waits) == (res.holds, res.waits)
    m = run_metrics(back, snapshots=0)
    assert (m["inevitable"], m["kinematic_violations"]) == (3, 2)
    assert {"inevitable", "kinematic_violations"} <= set(METRICS) <= set(m)
    # a payload of mawdo 0.7 has five events (holds the last)
    z = dict(np.load(io.BytesIO(result_to_bytes(res)), allow_pickle=False))
    z["events"] = z["events"][:5]
    buf = io.BytesIO()
    np.savez_compressed(buf, **z)
    old = result_from_bytes(buf.getvalue(), sc)
    assert (old.inevitable, old.kinematic_violations, old.holds) == (0, 0, res.holds)
