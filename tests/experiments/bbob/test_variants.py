"""Named variants of one algorithm in a suite study (issue 31): each option set is stored and
reported under its label, computes what a plan of that algorithm with those options computes,
is checked before anything runs, and the same command resumes with nothing recomputed."""

from __future__ import annotations

import json

import pytest

from mawdo.experiments import PlanError, Store, run_plan
from mawdo.experiments.kinds.suite import SuitePlan
from mawdo.experiments.kinds.suite.variants import parse_option, parse_variant

from .conftest import stored_values
from .test_cli import mawdo

# pop 10 and 300 x D evaluations: 60 iterations at D = 2, so restarts every 3 iterations act
SMALL = {"suite": "bbob", "functions": [8], "instances": [1], "dims": [2], "budget": 300,
         "runs": 2, "pop_size": 10, "seed": 5}  # fmt: skip
FLAGS = ("bench", "run", "--suite", "bbob", "--functions", "8", "--instances", "1", "--dims",
         "2", "--budget", "300", "--runs", "2", "--pop-size", "10", "--seed", "5",
         "--algorithms", "mawdo", "--no-progress")  # fmt: skip
X = {"x": "mawdo"}
VARIANT = ("--variant", "mawdo-r3=mawdo:restart_every=3,restart_frac=0.5")


def runs_of(path, algorithm):
    with Store.read(path) as store:
        return [r for a, _, r in store.rows() if a == algorithm]


def test_parsing_of_the_flags():
    assert parse_variant("Mawdo-R3=mawdo:restart_every=3,weights=[0.5, 0.5],boundary=clip") == (
        "mawdo-r3", "mawdo", {"restart_every": 3, "weights": [0.5, 0.5], "boundary": "clip"},
    )  # fmt: skip
    assert parse_variant("m2=wdo") == ("m2", "wdo", {})
    assert parse_option("mawdo-r3.restart_frac=0.25") == ("mawdo-r3", "restart_frac", 0.25)
    for bad in ("mawdo-r3:restart_every=3", "=mawdo", "m=mawdo:restart_every"):
        with pytest.raises(ValueError, match="LABEL=ALGORITHM"):
            parse_variant(bad)
    with pytest.raises(ValueError, match="NAME.OPTION=VALUE"):
        parse_option("groups=4")


@pytest.mark.parametrize(
    "changes, words",
    [
        ({"variants": {"wdo": "mawdo"}}, ["variants.wdo", "registered algorithm"]),
        ({"variants": {"m r": "mawdo"}}, ["variants.m r", "letters, digits"]),
        ({"variants": {"x": "mawdoo"}}, ["variants.x", "Did you mean 'mawdo'"]),
        ({"variants": {"x": "mawdo"}}, ["variants.x: not one of the plan's algorithms"]),
        ({"algorithms": ["mawdo", "x"]}, ["algorithms[1]", "--variant x=ALGORITHM"]),
        (
            {"algorithms": ["x"], "variants": X, "options": {"x": {"restart_every": 0}}},
            ["options.x: restart_every=0 must be an integer >= 1"],
        ),
        (
            {"algorithms": ["x"], "variants": X, "options": {"x": {"restart_evry": 3}}},
            ["options.x", "Did you mean 'restart_every'"],
        ),
    ],
)
def test_bad_variants_are_named(changes, words):
    with pytest.raises(PlanError) as err:
        SuitePlan.from_dict({"algorithms": ["mawdo"], **SMALL, **changes})
    for w in words:
        assert w in str(err.value), (w, str(err.value))


def test_a_variant_computes_what_its_options_compute(tmp_path):
    both = SuitePlan.from_dict({**SMALL, "algorithms": ["mawdo", "mawdo-r3"],
                                "variants": {"mawdo-r3": "mawdo"},
                                "options": {"mawdo-r3": {"restart_every": 3}}})  # fmt: skip
    plain = SuitePlan.from_dict({**SMALL, "algorithms": ["mawdo"]})
    direct = SuitePlan.from_dict({**SMALL, "algorithms": ["mawdo"],
                                  "options": {"mawdo": {"restart_every": 3}}})  # fmt: skip
    for plan, name in ((both, "both"), (plain, "plain"), (direct, "direct")):
        assert run_plan(plan, tmp_path / f"{name}.db", progress=False).failed == 0
    # the variant is the algorithm with its options, on the same seeds; the default is untouched
    for label, ref in (("mawdo-r3", "direct"), ("mawdo", "plain")):
        mine, want = runs_of(tmp_path / "both.db", label), runs_of(tmp_path / f"{ref}.db", "mawdo")
        assert [r.params for r in mine] == [r.params for r in want]
        assert [r.best_so_far.tolist() for r in mine] == [r.best_so_far.tolist() for r in want]
    assert {r.params["restart_every"] for r in runs_of(tmp_path / "both.db", "mawdo-r3")} == {3}
    differ = [a.best_so_far.tolist() != b.best_so_far.tolist()
              for a, b in zip(runs_of(tmp_path / "both.db", "mawdo"),
                              runs_of(tmp_path / "both.db", "mawdo-r3"), strict=True)]  # fmt: skip
    assert any(differ)  # the restarts act at this budget, so the test can tell them apart
    assert plain.plan_hash == SuitePlan.from_dict({**SMALL, "algorithms": ["mawdo"],
                                                   "variants": {}}).plan_hash  # fmt: skip


@pytest.mark.slow
def test_variants_from_the_command_store_report_and_resume(tmp_path):
    first = mawdo(*FLAGS, *VARIANT, "--out", "v.db", cwd=tmp_path)
    assert first.returncode == 0, first.stderr
    assert "complete: 4 runs computed" in first.stdout
    before = stored_values(tmp_path / "v.db")
    assert sorted({row[1] for row in before}) == ["mawdo", "mawdo-r3"]
    again = mawdo(*FLAGS, *VARIANT, "--out", "v.db", cwd=tmp_path)
    assert "0 runs computed" in again.stdout and "4 already stored" in again.stdout
    assert stored_values(tmp_path / "v.db") == before
    # the same study as a plan file (JSON) is the same plan: it resumes the store too
    plan = {**SMALL, "kind": "bbob", "algorithms": ["mawdo", "mawdo-r3"],
            "variants": {"mawdo-r3": "mawdo"},
            "options": {"mawdo-r3": {"restart_every": 3, "restart_frac": 0.5}}}  # fmt: skip
    (tmp_path / "p.json").write_text(json.dumps(plan))
    by_file = mawdo("bench", "run", "--plan", "p.json", "--out", "v.db", "--no-progress",
                    cwd=tmp_path)  # fmt: skip
    assert "0 runs computed" in by_file.stdout, by_file.stderr
    # "bbob" above is the kind's former name; its name now, with no suite field to go by
    named = {**{k: v for k, v in plan.items() if k != "suite"}, "kind": "suite"}
    (tmp_path / "q.json").write_text(json.dumps(named))
    by_name = mawdo("bench", "run", "--plan", "q.json", "--out", "v.db", "--no-progress",
                    cwd=tmp_path)  # fmt: skip
    assert "0 runs computed" in by_name.stdout, by_name.stderr
    rep = mawdo("bench", "report", "v.db", "--out", "rep", "--no-plots", cwd=tmp_path)
    assert rep.returncode == 0, rep.stderr
    text = (tmp_path / "rep" / "report.md").read_text()
    assert "- mawdo-r3: mawdo (restart_every=3, restart_frac=0.5)" in text
    header = (tmp_path / "rep" / "art_d2.csv").read_text().splitlines()[0]
    assert header.split(",")[-2:] == ["mawdo", "mawdo-r3"]


@pytest.mark.parametrize(
    "extra, words",
    [
        (("--variant", "mawdo-r3=mawdo:restart_every=0"), ["options.mawdo-r3", ">= 1"]),
        (("--variant", "mawdo-r3=mawdo:restart_evry=3"), ["Did you mean 'restart_every'"]),
        (("--variant", "mawdo-r3:restart_every=3"), ["--variant", "LABEL=ALGORITHM"]),
        (("--variant", "wdo=mawdo"), ["variants.wdo", "registered algorithm"]),
        (("--option", "mawdo.groups=0"), ["options.mawdo", "groups"]),
        (("--option", "cmaes.sigma0=1"), ["options.cmaes", "not one of the plan's algorithms"]),
    ],
)
def test_bad_variant_flags_exit_2_before_computing(tmp_path, extra, words):
    r = mawdo(*FLAGS, "--runs", "1000", "--budget", "1e7", *extra, "--out", "x.db", cwd=tmp_path)
    assert r.returncode == 2 and "Traceback" not in r.stderr, r.stderr
    for w in words:
        assert w in r.stderr, (w, r.stderr)
    assert not (tmp_path / "x.db").exists()
