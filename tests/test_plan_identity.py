"""``benchmarks/plan_identity.py``, the before/after check of speed changes: it must see any
change of a run's fields (else a "0 differ" proves nothing) and ignore only wall times."""

import pickle
import subprocess
import sys
from pathlib import Path

import numpy as np
from benchmarks.plan_identity import _plain, cases, diff, run_case

SCRIPT = Path(__file__).resolve().parents[1] / "benchmarks" / "plan_identity.py"


def test_diff_sees_every_kind_of_change():
    a = {"x": np.array([1.0, np.nan]), "r": [{"n": 3, "latency": 0.1}], "s": "goal reached"}
    assert diff(a, _plain(a)) == []  # NaN equals NaN, copies are equal
    b = _plain(a) | {"x": np.array([1.0 + 2**-52, np.nan])}  # one ulp
    assert diff(a, b) == [".x"]
    assert diff(a, _plain(a) | {"x": np.array([1.0, np.nan], np.float32)}) == [".x"]  # dtype
    assert diff(a, _plain(a) | {"r": [{"n": 4, "latency": 0.1}]}) == [".r[0].n"]
    assert diff(a, _plain(a) | {"r": []}) == [".r length 1 != 0"]
    assert diff(a, _plain(a) | {"s": "step limit"}) == [".s"]
    assert diff(a, _plain(a) | {"r": [{"n": 3, "latency": 9.0}]}) == []  # wall time only


def test_a_field_added_at_its_default_is_no_difference_and_at_another_value_is():
    a = {"spec": {"width": 10.0}, "success": True}
    assert (
        diff(a, {"spec": {"width": 10.0, "units": "px"}, "success": True, "robot_caused": None})
        == []
    )
    assert diff(a, {"spec": {"width": 10.0, "units": "m"}, "success": True}) == [
        ".spec keys ['units']"
    ]
    assert diff(a, {"spec": {"width": 10.0}, "success": True, "robot_caused": 0}) != []
    assert diff(a, {"spec": {}, "success": True}) != []  # a field that went missing


def test_seed_sequences_compare_by_state():
    a = _plain({"seed": np.random.SeedSequence(5, spawn_key=(1,))})
    assert diff(a, _plain({"seed": np.random.SeedSequence(5, spawn_key=(1,))})) == []
    assert diff(a, _plain({"seed": np.random.SeedSequence(5, spawn_key=(2,))})) != []


def test_cases_cover_every_family_both_ways_and_the_limits():
    from mawdo.experiments.kinds.arena.plan import LARGE_FAMILIES
    from mawdo.planning.run.config import PRESETS
    from mawdo.planning.scenes import FAMILIES

    full, quick = cases(), cases(quick=True)
    assert len({c[0] for c in full}) == len(full)  # labels are unique keys
    for fam in FAMILIES:
        assert f"{fam}-0" in {c[0] for c in quick}
        if fam in LARGE_FAMILIES:  # one scene, under the lookahead of the preset 'large'
            ahead = {"lookahead": PRESETS["large"].lookahead}
            assert [c[3] for c in full if c[0] == f"{fam}-0"] == [ahead]
            continue
        assert {f"{fam}-{i}{t}" for i in range(3) for t in ("", "-noguide")} <= {c[0] for c in full}
    assert sum("max_accel" in c[3] for c in full) == 3


def test_a_run_dumped_twice_is_identical_and_another_seed_is_not(tmp_path):
    one = run_case("open:0", 0, {})
    assert diff(one, run_case("open:0", 0, {})) == []
    assert diff(one, run_case("open:0", 1, {})) != []
    base, new = tmp_path / "a.pkl", tmp_path / "b.pkl"
    base.write_bytes(pickle.dumps({"open-0": one}))
    new.write_bytes(pickle.dumps({"open-0": run_case("open:0", 1, {})}))
    cmd = [sys.executable, str(SCRIPT), "compare"]
    same = subprocess.run([*cmd, str(base), str(base)], capture_output=True, text=True)
    assert same.returncode == 0 and "1 runs compared" in same.stdout and ": 0 differ" in same.stdout
    other = subprocess.run([*cmd, str(base), str(new)], capture_output=True, text=True)
    assert other.returncode == 1 and ": 1 differ" in other.stdout
