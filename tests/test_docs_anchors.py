"""Every ``docs/<file>.md#anchor`` cited in the code, the README or the docs exists.

Comments and generated report sentences point readers to decisions by anchor; a renamed or
removed decision would otherwise leave a dead link that nobody notices.
"""

from __future__ import annotations

import re
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
DOCS = "deviations|functions|planning|bbob|algorithms"
CITE = re.compile(rf"(?:docs/)?({DOCS})\.md#([A-Za-z0-9_-]+[A-Za-z0-9])")
ANCHOR = re.compile(r'<a id="([^"]+)"></a>')


def _anchors(name: str) -> set[str]:
    text = (ROOT / "docs" / f"{name}.md").read_text(encoding="utf-8")
    return set(ANCHOR.findall(text))


def _citing_files() -> list[Path]:
    files = [ROOT / "README.md", ROOT / "CHANGELOG.md", *sorted((ROOT / "docs").rglob("*.md"))]
    files += sorted((ROOT / "src").rglob("*.py")) + sorted((ROOT / "tests").rglob("*.py"))
    return [f for f in files if f.name != Path(__file__).name]


def _citations() -> list[tuple[str, str, str]]:
    out = []
    for f in _citing_files():
        for doc, anchor in CITE.findall(f.read_text(encoding="utf-8")):
            out.append((str(f.relative_to(ROOT)), doc, anchor))
    return out


def test_the_code_cites_docs_anchors():
    assert len(_citations()) > 40  # the SPEC references became anchors: the scan must see them


@pytest.mark.parametrize("doc", ["deviations", "functions", "planning", "bbob", "algorithms"])
def test_every_cited_anchor_exists(doc):
    known = _anchors(doc)
    dead = sorted({(f, a) for f, d, a in _citations() if d == doc and a not in known})
    assert not dead, f"dead links to docs/{doc}.md: {dead}"
