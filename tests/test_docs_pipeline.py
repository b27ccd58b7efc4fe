"""The pipeline section of docs/planning.md names real tests and links to real anchors.

The section's table says which test checks each stage's guarantee; a renamed or removed test
would leave a claim that nothing checks. Nothing is imported: the test files are read as text.
"""

from __future__ import annotations

import re
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
DOC = ROOT / "docs" / "planning.md"
CITED = re.compile(r"`(tests/[\w/]+\.py)::(test_\w+)`")
LINK = re.compile(r"\]\(#([A-Za-z0-9_-]+)\)")
ANCHOR = re.compile(r'<a id="([^"]+)"></a>')


def _defines(path: Path, name: str) -> bool:
    """True when ``path`` defines a test function ``name`` (at module level or in a class)."""
    text = path.read_text(encoding="utf-8")
    return re.search(rf"^[ \t]*(?:async[ \t]+)?def[ \t]+{name}[ \t]*\(", text, re.M) is not None


def test_the_pipeline_section_cites_tests():
    text = DOC.read_text(encoding="utf-8")
    assert "## The pipeline" in text and "```mermaid" in text
    # one or more tests per stage of the table (ten rows): the scan must see them
    assert len(set(CITED.findall(text))) >= 30


def test_every_cited_test_exists():
    missing = []
    for rel, name in sorted(set(CITED.findall(DOC.read_text(encoding="utf-8")))):
        path = ROOT / rel
        if not (path.is_file() and _defines(path, name)):
            missing.append(f"{rel}::{name}")
    assert not missing, f"docs/planning.md cites tests that do not exist: {missing}"


def test_every_local_link_has_its_anchor():
    text = DOC.read_text(encoding="utf-8")
    anchors = set(ANCHOR.findall(text))
    dead = sorted(set(LINK.findall(text)) - anchors)
    assert not dead, f'docs/planning.md links to #anchors without <a id="...">: {dead}'


def test_the_check_catches_a_missing_name(tmp_path):
    """The regex accepts a real definition and refuses a name that is only mentioned."""
    f = tmp_path / "test_x.py"
    f.write_text("def test_real():\n    test_mentioned()\n\nclass T:\n    def test_m(self): ...\n")
    assert _defines(f, "test_real") and _defines(f, "test_m")
    assert not _defines(f, "test_mentioned") and not _defines(f, "test_rea")
