"""IOHanalyzer logs exported from a suite store parse with the format's reader (the one
checked against ioh's own Analyzer files in tests/suites) and hold the store's best-so-far."""

from __future__ import annotations

import json

import numpy as np

from mawdo.experiments import Store
from mawdo.experiments.kinds.suite import export_ioh
from mawdo.experiments.kinds.suite.ioh_logs import read_analyzer_logs

from .conftest import TINY


def test_exported_logs_read_back_to_the_stores_best_so_far(tiny_store, tmp_path):
    export_ioh(tiny_store, tmp_path)
    with Store.read(tiny_store) as store:
        stored = {}
        for algo, _, r in store.rows():
            stored.setdefault((algo, r.function_id, r.dim, r.instance), []).append(r)
    n = 0
    for algo in TINY["algorithms"]:
        logs = read_analyzer_logs(tmp_path / algo)
        assert len(logs) == len(stored) // len(TINY["algorithms"]) * TINY["runs"]
        pos: dict = {}
        for log in logs:
            assert log["algorithm"] == algo
            key = (algo, log["function_id"], log["dim"], log["instance"])
            row = stored[key][pos.setdefault(key, 0)]  # runs are written in run order
            pos[key] += 1
            np.testing.assert_array_equal(log["evals"], row.evals)
            np.testing.assert_array_equal(log["precision"], row.best_so_far - row.f_star)
            assert log["total_evals"] == log["last_eval"] == row.nfev
            assert log["best"]["y"] == row.precision
            assert log["best"]["x"] == row.best_x.tolist()
            n += 1
    assert n == len(TINY["algorithms"]) * len(TINY["functions"]) * 2 * 2 * TINY["runs"]
    meta = json.loads(next((tmp_path / "cmaes").glob("IOHprofiler_f12_*.json")).read_text())
    assert meta["suite"] == "BBOB" and meta["function_name"] == "BentCigar"
    assert [s["dimension"] for s in meta["scenarios"]] == TINY["dims"]


def test_a_study_export_loads_whole_in_iohinspector(tiny_store, tmp_path):
    import polars as pl
    from iohinspector import DataManager  # a second reader of the format (the dev extra)

    export_ioh(tiny_store, tmp_path)
    with Store.read(tiny_store) as store:
        precision = {}
        for algo, _, r in store.rows():
            precision.setdefault((algo, r.function_id, r.dim, r.instance), []).append(r.precision)
    dm = DataManager()
    dm.add_folder(str(tmp_path))
    over = dm.overview.sort(["algorithm_name", "function_id", "dimension", "run_id"])
    assert over.height == sum(map(len, precision.values()))
    seen: dict = {}
    for row in over.iter_rows(named=True):
        key = (row["algorithm_name"], row["function_id"], row["dimension"], row["instance"])
        k = seen[key] = seen.get(key, -1) + 1  # runs are written in run order
        assert row["best_y"] == precision[key][k]
    data = dm.load(monotonic=True, include_meta_data=True)
    assert data["data_id"].n_unique() == over.height
    last = data.group_by("data_id").agg(y=pl.col("raw_y").min(), b=pl.col("best_y").first())
    assert (last["y"] == last["b"]).all()  # each run's data is paired with its own entry
