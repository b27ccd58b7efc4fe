"""``benchmarks/shade_cec2017.py``: its function numbers, refusals and table (no optimisation
runs here; the script itself is the long check)."""

from __future__ import annotations

import pytest
from benchmarks.shade_cec2017 import (
    JSO_PUBLISHED,
    OFFICIAL,
    check_function,
    friedman_ranks,
    main,
    table,
)


def test_the_official_numbers_are_checked():
    assert [check_function(f) for f in (1, 2, 30)] == [1, 2, 30]
    assert OFFICIAL == tuple(range(1, 31))
    for bad in (0, 31):
        with pytest.raises(ValueError, match="CEC 2017 has F1..F30"):
            check_function(bad)
    assert sorted(JSO_PUBLISHED) == list(range(1, 31))


def test_refuses_an_unknown_function_before_running_anything(tmp_path):
    out = tmp_path / "rows.jsonl"
    with pytest.raises(ValueError, match="official F31"):
        main(["--functions", "1,31", "--out", str(out)])
    assert not out.exists()


def test_table_puts_the_published_mean_beside_the_measured_one():
    rows = [
        {"algorithm": "jso", "official": 5, "runs": 5, "mean": 1.99, "std": 0.63},
        {"algorithm": "lshade", "official": 5, "runs": 5, "mean": 2.5, "std": 0.7},
    ]
    text = table(rows)
    assert "| F | jso mean (std), runs | jso published | lshade mean (std), runs |" in text
    assert "| F5 | 1.99 (0.63), 5 | 1.76 | 2.5 (0.7), 5 |" in text


def _stored_rows(others: bool = False):
    import json
    from pathlib import Path

    folder = Path(__file__).parents[1] / "docs/results/shade-cec2017"
    names = ["d10-runs51-seed2017.jsonl"]
    if others:
        names += ["d10-runs51-seed2017-others.jsonl", "d10-runs51-seed2017-more.jsonl",
                  "d10-runs51-seed2017-scipy_de.jsonl"]  # fmt: skip
    return [
        json.loads(line)
        for name in names
        for line in (folder / name).read_text().splitlines()
        if line.strip()
    ]


def test_the_docs_table_is_the_stored_runs_table():
    from pathlib import Path

    doc = (Path(__file__).parents[1] / "docs/algorithms.md").read_text(encoding="utf-8")
    assert table(_stored_rows()) in doc


def test_jso_agrees_with_its_published_means_as_the_docs_say():
    # the docs' claim: on all 30 functions the difference of the means is within two standard
    # errors of a difference of two 51-run means (published std taken equal to ours)
    import numpy as np

    rows = {r["official"]: r for r in _stored_rows() if r["algorithm"] == "jso"}
    assert sorted(rows) == list(range(1, 31))
    for f, r in rows.items():
        e = np.asarray(r["errors"])
        assert len(e) == 51 and r["mean"] == pytest.approx(e.mean())
        se = e.std(ddof=1) * np.sqrt(2 / len(e))
        assert abs(e.mean() - JSO_PUBLISHED[f]) <= max(2 * se, 1e-6 * max(1.0, JSO_PUBLISHED[f]))
    f30 = np.sort(rows[30]["errors"])
    assert np.median(f30) == pytest.approx(394.5, abs=0.05) and f30[-1] > 8e5


def test_friedman_ranks_by_hand():
    # F1: a 0, b 1, c 1 -> ranks 1, 2.5, 2.5; F2: a 3, b 2, c 1 -> 3, 2, 1; c alone on F3
    # is left out: means a 2.0, b 2.25, c 1.75
    rows = [
        {"algorithm": a, "official": f, "mean": m}
        for a, f, m in [("a", 1, 0.0), ("b", 1, 1.0), ("c", 1, 1.0), ("a", 2, 3.0),
                        ("b", 2, 2.0), ("c", 2, 1.0), ("c", 3, 9.0)]
    ]  # fmt: skip
    assert friedman_ranks(rows) == {"c": 1.75, "a": 2.0, "b": 2.25}


def test_wdo_plus_among_the_winners_as_the_docs_and_readme_say():
    from pathlib import Path

    from benchmarks.shade_cec2017 import rank_table

    rows = _stored_rows(others=True)
    root = Path(__file__).parents[1]
    doc = (root / "docs/algorithms.md").read_text(encoding="utf-8")
    assert rank_table(rows) in doc and table(rows) in doc
    order = list(friedman_ranks(rows))
    assert order.index("wdo_plus") == 5 and len(order) == 13
    assert order[:5] == ["nlshade_rsp", "jso", "lshade", "cmaes", "scipy_de"]
    readme = " ".join((root / "README.md").read_text(encoding="utf-8").split())
    assert "WDO+ ranks 6th of 13, behind NL-SHADE-RSP, jSO, L-SHADE, CMA-ES and scipy's DE" in (
        readme
    )
    text = " ".join(doc.split())
    assert "sixth of these thirteen, behind NL-SHADE-RSP, jSO, L-SHADE, CMA-ES and scipy's DE" in (
        text
    )
    assert order[6:] == ["mewdo", "gwo", "wdo", "woa", "mawdo", "random", "awdo"]
    assert "MEWDO seventh, WDO ninth, MAWDO eleventh and AWDO last, behind random search" in text
    by = {(r["algorithm"], r["official"]): r["mean"] for r in rows}

    def against(other):
        return [sum(cmp(by["wdo_plus", f], by[other, f]) for f in range(1, 31))
                for cmp in (float.__lt__, float.__gt__)]  # fmt: skip

    assert against("jso") == [7, 22]
    assert "better than jSO on 7 of the 30 functions and worse on 22" in text
    assert against("cmaes") == [7, 22] and "(against CMA-ES: 7 and 22 as well;" in text
    assert against("scipy_de") == [8, 22] and "against scipy's DE: 8 and 22)" in text

    def group(fs):
        return list(friedman_ranks([r for r in rows if r["official"] in fs]))

    assert group(range(21, 31))[:4] == ["nlshade_rsp", "scipy_de", "cmaes", "wdo_plus"]
    assert "(F21-F30) it is fourth, behind NL-SHADE-RSP, scipy's DE and CMA-ES" in text
    simple = group(range(4, 11))
    shade = {"jso", "lshade", "nlshade_rsp"}
    assert simple.index("wdo_plus") == 4 and set(simple[:4]) == shade | {"cmaes"}
    for fs in (range(1, 4), range(11, 21)):
        ranked = group(fs)
        assert ranked.index("wdo_plus") == 5
        assert set(ranked[:5]) == shade | {"cmaes", "scipy_de"}
