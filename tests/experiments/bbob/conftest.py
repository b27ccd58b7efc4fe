"""A tiny suite study computed once (in process) as the reference of the bbob-kind tests."""

from __future__ import annotations

import pytest

from mawdo.experiments import run_plan
from mawdo.experiments.kinds.suite import SuitePlan

from ..conftest import stored_values as stored_columns

# Three groups of BBOB (separable, high conditioning, weak structure), two instances, two
# dimensions; batch_size 2 cuts 3 runs into 2 + 1, so batches are not the runs' unit. CMA-ES
# solves f1 in D=2 within the budget: runs that stop at the final target are covered.
TINY = {
    "name": "tiny",
    "suite": "bbob",
    "algorithms": ["mawdo", "cmaes", "random"],
    "functions": [1, 12, 21],
    "instances": [1, 2],
    "dims": [2, 3],
    "budget": 300,
    "runs": 3,
    "batch_size": 2,
    "seed": 7,
}


def tiny_plan(**changes) -> SuitePlan:
    return SuitePlan.from_dict({**TINY, **changes})


VALUE_COLUMNS = (
    "plan_hash, algorithm, problem, run, suite, function_id, instance, dim, function_name, "
    "seed_entropy, params, f_star, fun, precision, nfev, max_evals, status, evals, best_so_far, "
    "best_x, library_version, error_text"
)


def stored_values(path) -> list[tuple]:
    """Every run's value columns (not wall times or task ids), in key order."""
    return stored_columns(path, VALUE_COLUMNS)


@pytest.fixture(scope="session")
def tiny_store(tmp_path_factory):
    path = tmp_path_factory.mktemp("bbob") / "tiny.db"
    summary = run_plan(tiny_plan(), path, workers=1, progress=False)
    assert summary.complete and summary.failed == 0
    return path
