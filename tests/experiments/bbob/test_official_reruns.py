"""The committed official CEC studies are what the code computes: a stored run, computed again
from the plan beside it, gives the stored final value and evaluation count bit for bit. A change
to an optimizer, the driver or the CEC functions that moves a stored number fails here, where
the store would otherwise mix its old rows with new ones on a resume; so would a run whose
numbers depend on the CPU (docs/deviations.md#d-cpu)."""

import lzma
import shutil
import sqlite3
from pathlib import Path

import pytest

from mawdo.experiments.kinds.suite.execute import execute_suite_task
from mawdo.experiments.protocol import Task, load_plan_file

RESULTS = Path(__file__).resolve().parents[3] / "docs" / "results"
# one simple multimodal function per store (shifted, rotated Rastrigin; CEC 2022's F4 is the
# non-continuous Rastrigin, which the official code computes as the Rastrigin): runs end in
# different local minima, so a changed step shows in the final value, unlike a function
# solved to 1e-8
STORES = {
    "cec2017-official-d10": "f05_i01_d10",
    "cec2022-official-d10": "f04_i01_d10",
    "cec2022-official-d20": "f04_i01_d20",
    "cec2017-official-d30": "f05_i01_d30",
}
# a further store of a study's protocol (one more algorithm, run later): NAME.db.xz beside
# NAME.plan.json in the study's folder
EXTRA = {
    "cec2017-official-d10": ("ea4eig",),
    "cec2017-official-d30": (
        "lshade",
        "jso",
        "nlshade_rsp",
        "ea4eig",
        "cmaes",
        "random",
        "scipy_de",
    ),
    "cec2022-official-d10": ("ea4eig",),
    "cec2022-official-d20": ("ea4eig",),
}
LIBRARIES = ("cmaes", "scipy_de")  # computed by other libraries (cmaes, SciPy)
# run 7 is the third of its task (tasks of five runs), so a dependence on the batch shows too
RUN = 7


@pytest.fixture(scope="module")
def stores(tmp_path_factory):
    cons = {}
    for name in STORES:
        for stem in ("store", *EXTRA.get(name, ())):
            db = tmp_path_factory.mktemp(name) / f"{stem}.db"
            with lzma.open(RESULTS / name / f"{stem}.db.xz") as src, open(db, "wb") as dst:
                shutil.copyfileobj(src, dst)
            cons[name, stem] = sqlite3.connect(db)
    yield cons
    for con in cons.values():
        con.close()


def _rerun(stores, name: str, algorithm: str, stem: str = "store") -> None:
    plan_file = "plan.json" if stem == "store" else f"{stem}.plan.json"
    plan = load_plan_file(RESULTS / name / plan_file)
    problem = STORES[name]
    stored = (
        stores[name, stem]
        .execute(
            "select fun, nfev from runs where algorithm = ? and problem = ? and run = ?",
            (algorithm, problem, RUN),
        )
        .fetchone()
    )
    assert stored is not None, (name, algorithm)
    (row,) = execute_suite_task(plan.task_spec(Task(algorithm, problem, RUN, 1)))
    assert (row.fun, row.nfev) == tuple(stored), (name, algorithm)


def _own(name: str) -> list[str]:
    return [
        a for a in load_plan_file(RESULTS / name / "plan.json").algorithms if a not in LIBRARIES
    ]


@pytest.mark.parametrize(
    ("name", "algorithm"),
    [(n, a) for n in STORES for a in _own(n)],
)
def test_a_stored_run_is_computed_again_bit_for_bit(stores, name, algorithm):
    _rerun(stores, name, algorithm)


@pytest.mark.slow
@pytest.mark.parametrize(
    ("name", "algorithm"),
    [
        ("cec2017-official-d10", "cmaes"),
        ("cec2017-official-d10", "scipy_de"),
        ("cec2022-official-d10", "cmaes"),
    ],
)
def test_a_stored_run_of_a_library_reference_is_computed_again_bit_for_bit(stores, name, algorithm):
    # the cmaes library's eigendecomposition runs in OpenBLAS, whose kernels depend on the CPU
    # (docs/deviations.md#d-cpu): these hold with OpenBLAS's Haswell or Zen kernels, which
    # `make test-all` asks for on any x86-64 CPU with AVX2
    _rerun(stores, name, algorithm)


@pytest.mark.slow
@pytest.mark.parametrize(
    ("name", "stem"), [(n, stem) for n, stems in EXTRA.items() for stem in stems]
)
def test_a_stored_run_of_a_further_store_is_computed_again_bit_for_bit(stores, name, stem):
    # the plan names the one algorithm of its store; EA4eig's eigendecompositions (LAPACK, in
    # OpenBLAS) hold to the same CPUs as the cmaes library's above
    (algorithm,) = load_plan_file(RESULTS / name / f"{stem}.plan.json").algorithms
    _rerun(stores, name, algorithm, stem)
