"""Several stores of one suite study (one per dimension) report as the study run in one store."""

from __future__ import annotations

import shutil
import sqlite3
from pathlib import Path

import numpy as np
import pytest

import mawdo
from mawdo.experiments import StoreError, run_plan
from mawdo.experiments.kinds.suite import write_suite_report
from mawdo.experiments.kinds.suite.data import load_runs

from .conftest import tiny_plan


def _key(r):
    return (r.algorithm, r.function_id, r.instance, r.dim, r.run)


@pytest.fixture(scope="module")
def per_dim(tmp_path_factory):
    folder = tmp_path_factory.mktemp("per-dim")
    paths = []
    for dim in (3, 2):  # the later dimension first: the merge must not depend on file order
        path = folder / f"d{dim}.db"
        assert run_plan(tiny_plan(dims=[dim]), path, workers=1, progress=False).complete
        paths.append(path)
    return paths


def test_merged_stores_hold_the_runs_of_the_single_store(tiny_store, per_dim):
    whole, merged = load_runs(tiny_store), load_runs(per_dim)
    assert merged.dims == (2, 3) and merged.suite == whole.suite
    assert set(merged.algorithms) == set(whole.algorithms)
    assert set(merged.functions) == set(whole.functions)
    a = {_key(r): r for r in whole.runs}
    b = {_key(r): r for r in merged.runs}
    assert a.keys() == b.keys()
    for k, r in a.items():  # a run's seed does not depend on the plan's other dimensions
        np.testing.assert_array_equal(r.evals, b[k].evals)
        np.testing.assert_array_equal(r.best_y, b[k].best_y)


def test_merged_report_tables_equal_the_single_store_report(tiny_store, per_dim, tmp_path):
    write_suite_report(tiny_store, tmp_path / "one", plots=False)
    write_suite_report(per_dim, tmp_path / "two", plots=False)
    for name in ("art_d2.csv", "art_d3.csv", "fixed_budget_d3.csv", "friedman.csv"):
        assert (tmp_path / "one" / name).read_text() == (tmp_path / "two" / name).read_text()
    made = f"(from d3.db + d2.db, made by mawdo {mawdo.__version__})"
    assert made in (tmp_path / "two" / "report.md").read_text()


def test_a_report_names_every_version_that_made_its_stores(per_dim, tmp_path):
    """A report reads stores of older versions (read-only) and says which made them."""
    old = Path(shutil.copy(per_dim[1], tmp_path / "d2-old.db"))
    conn = sqlite3.connect(old)
    with conn:
        conn.execute("UPDATE meta SET library_version = '0.2.0'")
    conn.close()
    write_suite_report([per_dim[0], old], tmp_path / "mixed", plots=False)
    made = f"(from d3.db + d2-old.db, made by mawdo {mawdo.__version__} and 0.2.0)"
    assert made in (tmp_path / "mixed" / "report.md").read_text()


def test_a_store_given_twice_is_refused(per_dim):
    with pytest.raises(StoreError, match="both hold run 0 of .*report them separately"):
        load_runs([per_dim[0], per_dim[0]])


def test_stores_of_other_budgets_are_refused(per_dim, tmp_path):
    other = tmp_path / "b.db"
    assert run_plan(
        tiny_plan(dims=[5], budget=100, algorithms=["random"]), other, workers=1, progress=False
    ).complete
    with pytest.raises(StoreError, match="at 100 x D evaluations.*report them separately"):
        load_runs([per_dim[0], other])


def test_no_store_is_a_clear_error():
    with pytest.raises(ValueError, match="no results store given"):
        load_runs([])
