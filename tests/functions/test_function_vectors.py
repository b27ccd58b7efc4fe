"""Every record of ``tests/data/function_vectors.json`` is reproduced.

See docs/functions.md#f-exactness.

The vectors are the project's independent reference values for F1-F16 and the alternates; they
ship with the repository so a clone can run the test on its own.
"""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

from mawdo.functions import ALTERNATES, FUNCTIONS, PAPER_SUITE

REL, ABS = 1e-12, 1e-30
# Textbook Ackley gives 4.4e-16 at the origin in float64; ours is exactly 0 (see ackley's
# docstring) but the allowance the json's note asks for is kept for that one record.
ABS_OVERRIDES = {("ackley", "optimum"): 1e-15}

VECTORS_PATH = Path(__file__).resolve().parents[1] / "data" / "function_vectors.json"
# Read at import: a missing or broken file is a collection error (a failure), never a skip.
RECORDS: list[dict] = json.loads(VECTORS_PATH.read_text())
RECORD_IDS = [f"{i:02d}-{r.get('name')}-{r.get('point')}" for i, r in enumerate(RECORDS)]


@pytest.fixture(scope="module")
def vectors() -> list[dict]:
    """All json records (a list of dicts)."""
    return RECORDS


@pytest.fixture(params=RECORDS, ids=RECORD_IDS)
def record(request) -> dict:
    """One json record."""
    return request.param


def _expected_function(record: dict):
    return FUNCTIONS[record["name"]]


def test_vectors_file_is_complete(vectors):
    names = {r["name"] for r in vectors}
    assert len(vectors) >= 89
    assert set(PAPER_SUITE) - {"quartic"} <= names  # F6 is stored as its noiseless part
    assert "quartic_noiseless" in names
    assert names <= set(PAPER_SUITE) | set(ALTERNATES)


def test_record_reproduced(record):
    f = _expected_function(record)
    x = np.array(record["x"], dtype=float)
    assert record["dim"] == f.dim == x.size
    value = f.func(x[None, :])[0]  # the noiseless formula
    tol = ABS_OVERRIDES.get((record["name"], record["point"]), ABS)
    assert value == pytest.approx(record["f"], rel=REL, abs=tol), (
        f"{record['name']} at {record['point']}: got {value!r}, json says {record['f']!r}"
    )
    if not f.noise:  # the public call gives the same value (noisy F6 is tested elsewhere)
        assert f(x) == value


def test_record_paper_id_matches_registry(record):
    f = _expected_function(record)
    if record["paper_id"] == "ALT" or f.paper_id is None:
        assert record["name"] in ALTERNATES
    else:
        assert f.paper_id == record["paper_id"]
        assert FUNCTIONS[record["paper_id"]] is f


def test_optimum_records_agree_with_f_star(vectors):
    """The json's ``optimum`` rows give the registered ``f_star`` (noiseless F6 included)."""
    checked = 0
    for r in vectors:
        if r["point"] != "optimum":
            continue
        f = FUNCTIONS[r["name"]]
        assert r["f"] == pytest.approx(f.f_star, rel=REL, abs=1e-15), r["name"]
        checked += 1
    assert checked >= 20


def test_records_batched_equal_single(vectors):
    """All records of one function evaluated in one batch equal the single-point values."""
    by_name: dict[str, list[dict]] = {}
    for r in vectors:
        by_name.setdefault(r["name"], []).append(r)
    for name, rows in by_name.items():
        f = FUNCTIONS[name]
        X = np.array([r["x"] for r in rows])
        batch = f.func(X)
        assert batch.shape == (len(rows),)
        singles = np.array([f.func(X[i : i + 1])[0] for i in range(len(rows))])
        np.testing.assert_array_equal(batch, singles, err_msg=name)
