"""Every generated headline sentence of a committed report is quoted verbatim in the README.

The reports write their claims as sentences computed from the store (``summary.md``); the README
quotes them, so a regenerated report that changes a number fails here until the README follows.
"""

from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
SUMMARIES = sorted((ROOT / "docs" / "results").glob("**/summary.md"))


@pytest.mark.parametrize("summary", SUMMARIES, ids=lambda p: str(p.relative_to(ROOT)))
def test_readme_quotes_the_generated_sentences(summary):
    readme = (ROOT / "README.md").read_text(encoding="utf-8")
    lines = [s for s in summary.read_text(encoding="utf-8").splitlines() if s.strip()]
    assert lines, f"{summary} is empty"
    missing = [s for s in lines if s not in readme]
    assert not missing, f"README does not quote {summary}: {missing}"
