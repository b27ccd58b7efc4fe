"""``benchmarks/shade_cec2017.py``: the official-to-opfunu numbering, its refusals and its table
(no optimisation runs here; the script itself is the lead's long check)."""

from __future__ import annotations

import pytest
from benchmarks.shade_cec2017 import JSO_PUBLISHED, OFFICIAL, main, opfunu_id, table


def test_official_numbers_map_to_opfunu_without_f2():
    assert [opfunu_id(f) for f in (1, 3, 4, 30)] == [1, 2, 3, 29]
    assert len(OFFICIAL) == 29 and 2 not in OFFICIAL
    for bad in (2, 0, 31):
        with pytest.raises(ValueError, match="opfunu has F1 and F3..F30"):
            opfunu_id(bad)
    assert sorted(JSO_PUBLISHED) == list(range(1, 31))


def test_refuses_f2_before_running_anything(tmp_path):
    out = tmp_path / "rows.jsonl"
    with pytest.raises(ValueError, match="official F2"):
        main(["--functions", "1,2", "--out", str(out)])
    assert not out.exists()


def test_table_puts_the_published_mean_beside_the_measured_one():
    rows = [
        {"algorithm": "jso", "official": 5, "runs": 5, "mean": 1.99, "std": 0.63},
        {"algorithm": "lshade", "official": 5, "runs": 5, "mean": 2.5, "std": 0.7},
    ]
    text = table(rows)
    assert "| F | jso mean (std), runs | jso published | lshade mean (std), runs |" in text
    assert "| F5 | 1.99 (0.63), 5 | 1.76 | 2.5 (0.7), 5 |" in text
