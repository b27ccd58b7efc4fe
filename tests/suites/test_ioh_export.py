"""Exported logs match the files ioh's own Analyzer writes, and read back to the input."""

import json
import warnings
from importlib import metadata
from types import SimpleNamespace

import ioh
import numpy as np
import pytest

from mawdo import minimize
from mawdo.experiments.kinds.suite.ioh_logs import (
    IOHRun,
    read_analyzer_logs,
    runs_from_result,
    write_analyzer_logs,
)
from mawdo.minimize import NoFiniteValueWarning
from mawdo.suites import get_problem, run_problem


def ioh_and_ours(tmp_path, fid, iid, dims, runs=2, batches=25, n=6):
    """The same evaluations logged by ioh.logger.Analyzer and traced by our driver: its
    objective is the ioh problem with the logger attached (the last batch cut by max_evals)."""
    lg = ioh.logger.Analyzer(
        root=str(tmp_path), folder_name="ioh", algorithm_name="rs", algorithm_info="uniform"
    )
    ours = []
    for dim in dims:
        f = get_problem("bbob", fid, instance=iid, dim=dim)
        p = ioh.get_problem(fid, iid, dim, ioh.ProblemClass.REAL)
        p.attach_logger(lg)
        for k in range(runs):
            res = minimize(lambda X, p=p: np.asarray(p(X), dtype=float), lb=f.lb, ub=f.ub,
                           algorithm="random", pop_size=n, max_evals=batches * n - 2,
                           seed=fid, first_run=k, trace_evaluations=True)  # fmt: skip
            p.reset()
            ours += runs_from_result(f, res)
    lg.close()
    write_analyzer_logs(tmp_path / "ours", ours, "rs", "uniform")
    return tmp_path / "ioh", tmp_path / "ours", ours


@pytest.mark.parametrize(("fid", "iid"), [(3, 2), (8, 1), (21, 4)])
def test_files_match_ioh_analyzer(tmp_path, fid, iid):
    ioh_dir, our_dir, _ = ioh_and_ours(tmp_path, fid, iid, dims=(2, 5))
    theirs, mine = read_analyzer_logs(ioh_dir), read_analyzer_logs(our_dir)
    assert len(theirs) == len(mine) == 4
    for a, b in zip(theirs, mine, strict=True):
        for key in ("function_id", "function_name", "dim", "instance", "total_evals", "last_eval"):
            assert a[key] == b[key], key
        np.testing.assert_array_equal(a["evals"], b["evals"])
        np.testing.assert_allclose(a["precision"], b["precision"], rtol=0, atol=2e-10)  # 10 dp
        assert a["best"]["evals"] == b["best"]["evals"]
        assert b["best"]["y"] == pytest.approx(a["best"]["y"], abs=1e-12)
    # same file names and meta-data keys as ioh's
    names = sorted(p.relative_to(ioh_dir).as_posix() for p in ioh_dir.rglob("*") if p.is_file())
    assert names == sorted(p.relative_to(our_dir).as_posix() for p in our_dir.rglob("*.*"))
    mj = json.loads(next(our_dir.glob("*.json")).read_text())
    ij = json.loads(next(ioh_dir.glob("*.json")).read_text())
    assert set(mj) == set(ij)
    assert mj["attributes"] == ij["attributes"] and mj["maximization"] is False


def test_round_trip_of_a_batched_run_is_exact(tmp_path):
    written = []
    for fid, dim in ((1, 3), (1, 5), (17, 3)):
        f = get_problem("bbob", fid, instance=3, dim=dim)
        res = run_problem(f, "mawdo", runs=3, budget=80, seed=fid, final_target=None)
        written += runs_from_result(f, res)
    files = write_analyzer_logs(tmp_path, written, "mawdo", "test")
    assert sorted(p.name for p in files) == [
        "IOHprofiler_f17_Schaffers10.json",
        "IOHprofiler_f1_Sphere.json",
    ]
    back = read_analyzer_logs(tmp_path)
    assert len(back) == len(written) == 9
    for fid, dim in ((1, 3), (1, 5), (17, 3)):
        mine = [w for w in written if (w.function_id, w.dim) == (fid, dim)]
        read = [r for r in back if (r["function_id"], r["dim"]) == (fid, dim)]
        for w, r in zip(mine, read, strict=True):  # runs keep their order
            np.testing.assert_array_equal(r["evals"], w.evals)
            np.testing.assert_array_equal(r["precision"], w.best_y - w.f_opt)  # exact floats
            assert r["total_evals"] == r["last_eval"] == w.total_evals == 80 * dim
            assert r["best"]["y"] == w.best_y[-1] - w.f_opt
            np.testing.assert_array_equal(r["best"]["x"], w.best_x)


def test_bad_runs_are_refused(tmp_path):
    run = IOHRun(1, "Sphere", 2, 1, np.array([1, 3]), np.array([2.0, 3.0]), 5)
    with pytest.raises(ValueError, match="best_y strictly decrease"):
        write_analyzer_logs(tmp_path, [run], "x")
    run = IOHRun(1, "Sphere", 2, 1, np.array([1, 3]), np.array([2.0, 1.0]), 2)
    with pytest.raises(ValueError, match="total_evals 2 < last eval"):
        write_analyzer_logs(tmp_path, [run], "x")


# Scripted values per run (precision = value: the wrapped problem has no known optimum). Run 0
# starts with two infinite values, run 1 never has a finite one (what CEC or a user's function
# can give), run 2 is finite; every run's last value improves, where ioh's last line (the last
# *evaluated* value) and ours (the best-so-far) agree.
SCRIPTS = ([np.inf, np.inf, 5.0, 6.0, 0.25], [np.inf] * 4, [3.0, 1.5, 2.0, 0.5])


def scripted_logs(tmp_path):
    """The scripted runs logged by ioh's own Analyzer and written by us from our driver's
    trace (one iteration of ``len(script)`` points: the objective is the logged problem)."""
    state = {"values": iter(())}
    name = f"Scripted{tmp_path.name[-6:]}"  # ioh keeps wrapped problems for the process
    ioh.wrap_problem(
        lambda x: float(next(state["values"])), name, ioh.ProblemClass.REAL,
        dimension=2, instance=1, lb=-5, ub=5,
    )  # fmt: skip
    problem = ioh.get_problem(name, 1, 2)
    lg = ioh.logger.Analyzer(root=str(tmp_path), folder_name="ioh", algorithm_name="s")
    problem.attach_logger(lg)
    meta = SimpleNamespace(
        function_id=problem.meta_data.problem_id, function_name=name, dim=2, instance=1,
        f_star=0.0,
    )  # fmt: skip
    ours = []
    for script in SCRIPTS:
        state["values"] = iter(script)
        with warnings.catch_warnings(record=True) as seen:
            warnings.simplefilter("always", NoFiniteValueWarning)
            res = minimize(lambda X: np.array([problem(x) for x in X]), [(-5, 5)] * 2,
                           algorithm="random", pop_size=len(script), max_iter=1, seed=0,
                           trace_evaluations=True)  # fmt: skip
        # a run without a finite value says so (its x was never evaluated)
        warned = any(issubclass(w.category, NoFiniteValueWarning) for w in seen)
        assert warned == (not np.isfinite(script).any())
        problem.reset()
        ours += runs_from_result(meta, res)
    lg.close()
    write_analyzer_logs(tmp_path / "ours", ours, "s")
    return tmp_path / "ioh", tmp_path / "ours", meta


def dat_lines(folder) -> list[tuple[int, float | None]]:
    (dat,) = folder.rglob("*.dat")
    out = []
    for line in dat.read_text().splitlines():
        if line and not line.startswith("evaluations"):
            ev, val = line.split()
            out.append((int(ev), None if val == "None" else float(val)))
        elif line:
            out.append((0, None))  # a run's header
    return out


def test_runs_without_a_finite_value_are_written_as_ioh_writes_them(tmp_path):
    ioh_dir, our_dir, meta = scripted_logs(tmp_path)
    theirs, mine = dat_lines(ioh_dir), dat_lines(our_dir)
    assert [e for e, _ in mine] == [e for e, _ in theirs] == [0, 1, 3, 5, 0, 1, 0, 1, 2, 4]
    for (_, a), (_, b) in zip(theirs, mine, strict=True):
        assert (a is None) == (b is None)
        assert b is None or b == pytest.approx(a, abs=1e-10)  # ioh prints 10 decimals
    # ioh 0.4.2 leaves the run without a best point out of its meta data (so its file has 3
    # blocks and 2 entries); we list it with every key of an entry
    (ij,) = [json.loads(p.read_text()) for p in ioh_dir.glob("*.json")]
    (mj,) = [json.loads(p.read_text()) for p in our_dir.glob("*.json")]
    ir, mr = ij["scenarios"][0]["runs"], mj["scenarios"][0]["runs"]
    assert len(ir) == 2 and len(mr) == 3
    for a, b in zip(ir, [mr[0], mr[2]], strict=True):
        assert (a["instance"], a["evals"], a["best"]["evals"]) == (
            b["instance"], b["evals"], b["best"]["evals"],
        )  # fmt: skip
        assert b["best"]["y"] == a["best"]["y"]
        np.testing.assert_array_equal(b["best"]["x"], a["best"]["x"])
    assert mr[1] == {"instance": 1, "evals": 4, "best": {"evals": 0, "y": None, "x": [None] * 2}}
    back = read_analyzer_logs(our_dir)  # our reader takes None as "no value yet"
    assert [r["evals"].tolist() for r in back] == [[3, 5], [], [1, 2, 4]]
    assert [r["precision"].tolist() for r in back] == [[5.0, 0.25], [], [3.0, 1.5, 0.5]]
    assert [r["last_eval"] for r in back] == [5, 1, 4]
    assert mj["function_id"] == ij["function_id"] == meta.function_id


def test_version_is_the_installed_iohs(tmp_path):
    ioh_dir, our_dir, _ = ioh_and_ours(tmp_path, 1, 1, dims=(2,), runs=1, batches=2)
    (ij,) = [json.loads(p.read_text()) for p in ioh_dir.glob("*.json")]
    (mj,) = [json.loads(p.read_text()) for p in our_dir.glob("*.json")]
    assert mj["version"] == ij["version"] == metadata.version("ioh")
