"""Every generated headline sentence of a committed report is quoted verbatim in the README.

The reports write their claims as sentences computed from the store (``summary.md``); the README
quotes them, so a regenerated report that changes a number fails here until the README follows.
"""

import lzma
import shutil
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
SUMMARIES = sorted((ROOT / "docs" / "results").glob("**/summary.md"))


def unpack(packed: Path, folder: Path) -> Path:
    """A committed xz-compressed store, decompressed into ``folder``."""
    db = folder / packed.name.removesuffix(".xz")
    with lzma.open(packed) as src, open(db, "wb") as dst:
        shutil.copyfileobj(src, dst)
    return db


@pytest.mark.parametrize("summary", SUMMARIES, ids=lambda p: str(p.relative_to(ROOT)))
def test_readme_quotes_the_generated_sentences(summary):
    readme = (ROOT / "README.md").read_text(encoding="utf-8")
    lines = [s for s in summary.read_text(encoding="utf-8").splitlines() if s.strip()]
    assert lines, f"{summary} is empty"
    missing = [s for s in lines if s not in readme]
    assert not missing, f"README does not quote {summary}: {missing}"


def test_bbob_sentences_are_those_of_the_committed_store(tmp_path):
    """The committed BBOB stores (xz, one per dimension) give exactly the committed sentences."""
    from mawdo.experiments.bbob.data import load_runs
    from mawdo.experiments.bbob.summary import headline

    folder = ROOT / "docs" / "results" / "bbob"
    dbs = [unpack(folder / f"store-d{d}.db.xz", tmp_path) for d in (5, 20)]
    summary = (folder / "summary.md").read_text(encoding="utf-8")
    assert headline(load_runs(dbs)) == summary.splitlines()


def test_arena_sentences_are_those_of_the_committed_store(tmp_path):
    """The committed arena store (xz) gives exactly the committed headline sentences."""
    from mawdo.experiments import Store
    from mawdo.experiments.arena.summary import headline

    db = unpack(ROOT / "docs" / "results" / "arena-default" / "store.db.xz", tmp_path)
    with Store.read(db) as store:
        lines = headline(store)
    summary = (ROOT / "docs" / "results" / "arena-default" / "summary.md").read_text("utf-8")
    assert lines == summary.splitlines()
