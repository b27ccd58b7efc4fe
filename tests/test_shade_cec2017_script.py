"""``benchmarks/shade_cec2017.py``: its function numbers, refusals and table (no optimisation
runs here; the script itself is the long check)."""

from __future__ import annotations

import pytest
from benchmarks.shade_cec2017 import JSO_PUBLISHED, OFFICIAL, check_function, main, table


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
