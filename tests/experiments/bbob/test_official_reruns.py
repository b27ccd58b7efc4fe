"""The committed official CEC 2017 study (D = 10) is what the code computes: a stored run,
computed again from the plan beside it, gives the stored final value and evaluation count bit
for bit. A change to an optimizer, the driver or the CEC functions that moves a stored number
fails here, where the store would otherwise mix its old rows with new ones on a resume."""

import lzma
import shutil
import sqlite3
from pathlib import Path

import pytest

from mawdo.experiments.kinds.suite.execute import execute_suite_task
from mawdo.experiments.protocol import Task, load_plan_file

FOLDER = Path(__file__).resolve().parents[3] / "docs" / "results" / "cec2017-official-d10"
# a simple multimodal function (shifted, rotated Rastrigin): runs end in different local
# minima, so a changed step shows in the final value, unlike a function solved to 1e-8
PROBLEM = "f05_i01_d10"
FAST = ["wdo_plus", "mawdo", "wdo", "gwo", "lshade", "jso", "nlshade_rsp", "random"]


@pytest.fixture(scope="module")
def store(tmp_path_factory):
    db = tmp_path_factory.mktemp("cec2017") / "store.db"
    with lzma.open(FOLDER / "store.db.xz") as src, open(db, "wb") as dst:
        shutil.copyfileobj(src, dst)
    con = sqlite3.connect(db)
    yield con
    con.close()


def _rerun(store, algorithm: str, run: int) -> None:
    plan = load_plan_file(FOLDER / "plan.json")
    stored = store.execute(
        "select fun, nfev from runs where algorithm = ? and problem = ? and run = ?",
        (algorithm, PROBLEM, run),
    ).fetchone()
    assert stored is not None, (algorithm, run)
    (row,) = execute_suite_task(plan.task_spec(Task(algorithm, PROBLEM, run, 1)))
    assert (row.fun, row.nfev) == tuple(stored), algorithm


@pytest.mark.parametrize("algorithm", FAST)
def test_a_stored_run_is_computed_again_bit_for_bit(store, algorithm):
    _rerun(store, algorithm, 7)


@pytest.mark.slow
@pytest.mark.parametrize("algorithm", ["cmaes", "scipy_de"])
def test_a_stored_run_of_a_library_reference_is_computed_again_bit_for_bit(store, algorithm):
    _rerun(store, algorithm, 7)
