"""Our IOHanalyzer logs load whole in ``iohinspector`` (a second reader of the format), runs
without a finite value included: every run is listed and each run's data is its own."""

from __future__ import annotations

import warnings

import numpy as np
import pytest
from iohinspector import DataManager

from mawdo.experiments.kinds.suite.ioh_logs import IOHRun, write_analyzer_logs


def run(fid, dim, instance, evals, best_y, total, f_opt=0.0):
    x = None if not len(evals) else np.linspace(-1, 1, dim) * (instance + len(evals))
    return IOHRun(
        fid, "Thing", dim, instance, np.array(evals, dtype=np.int64), np.array(best_y, float),
        total, x, f_opt,
    )  # fmt: skip


def load(folder):
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # iohinspector warns, and skips the file, on a bad one
        dm = DataManager()
        dm.add_folder(str(folder))
        return dm, dm.load(monotonic=True, include_meta_data=True)


@pytest.mark.parametrize("no_value_at", [0, 1, 3])
def test_an_export_with_a_run_without_a_finite_value_loads_whole(tmp_path, no_value_at):
    runs = [
        run(7, 2, 1, [1, 4, 9], [30.0, 12.5, 10.25], 20, f_opt=10.0),
        run(7, 2, 2, [3, 5], [11.0, 10.5], 20, f_opt=10.0),  # no finite value before eval 3
        run(7, 5, 1, [1, 2], [40.0, 35.0], 50, f_opt=10.0),
        run(7, 5, 2, [6], [15.0], 50, f_opt=10.0),
    ]
    runs.insert(no_value_at, run(7, runs[no_value_at].dim, 3, [], [], 20))  # never finite
    write_analyzer_logs(tmp_path, runs, "algo")
    dm, data = load(tmp_path)
    over = dm.overview.sort(["dimension", "run_id"])
    assert over.height == len(runs)  # the whole file (the no-best run used to drop it)
    mine = sorted(runs, key=lambda r: r.dim)  # scenarios by dimension, runs in input order
    assert over["instance"].to_list() == [r.instance for r in mine]
    assert over["evals"].to_list() == [r.total_evals for r in mine]
    want_best = [float(r.best_y[-1] - r.f_opt) if len(r.evals) else None for r in mine]
    assert over["best_y"].to_list() == want_best
    # every run's data rows are its own: its improvements, paired with its own meta entry
    for (data_id,), rows in data.sort("evaluations").group_by(["data_id"]):
        r = mine[over["data_id"].to_list().index(data_id)]
        assert rows["instance"].unique().to_list() == [r.instance]
        assert rows["evaluations"].to_list() == r.evals.tolist()
        assert rows["raw_y"].to_list() == (r.best_y - r.f_opt).tolist()
        assert rows["best_y"].unique().to_list() == [float(r.best_y[-1] - r.f_opt)]
    # the run without a value has no data row (ioh writes its value as None), nothing else lost
    assert data["data_id"].n_unique() == len(runs) - 1
