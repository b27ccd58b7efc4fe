"""Fixtures for the benchmark-function tests: the shared test vectors (SPEC 2).

``shared/data/function_vectors.json`` lives outside the repository (``<repo>/../shared``) unless
``MAWDO_SHARED`` points at the shared folder. A missing or unreadable file FAILS the tests that
need it (with the path it looked at), it never skips them.
"""

from __future__ import annotations

import json
import os
from pathlib import Path

import pytest

REPO_ROOT = Path(__file__).resolve().parents[2]


def vectors_path() -> Path:
    """``$MAWDO_SHARED/data/function_vectors.json``, else ``<repo>/../shared/data/...``."""
    shared = os.environ.get("MAWDO_SHARED")
    base = Path(shared) if shared else REPO_ROOT.parent / "shared"
    return base / "data" / "function_vectors.json"


def load_vectors() -> tuple[list[dict], str | None]:
    """``(records, None)``, or ``([], reason)`` when the file cannot be read."""
    path = vectors_path()
    try:
        records = json.loads(path.read_text())
    except FileNotFoundError:
        return [], (
            f"function test vectors not found at {path}; set MAWDO_SHARED to the shared folder "
            "(the one holding data/function_vectors.json)"
        )
    except (OSError, ValueError) as exc:
        return [], f"cannot read function test vectors at {path}: {exc}"
    if not isinstance(records, list) or not records:
        return [], f"function test vectors at {path} are not a non-empty list"
    return records, None


class MissingVectors:
    """Stands in for the records when the file is missing: any use FAILS the test (not an error
    at setup, not a skip) with the reason, from inside the test body."""

    def __init__(self, reason: str) -> None:
        self.reason = reason

    def _fail(self, *args, **kwargs):
        pytest.fail(self.reason)

    __getitem__ = __iter__ = __len__ = __contains__ = get = keys = items = _fail


_RECORDS, _LOAD_ERROR = load_vectors()


def pytest_generate_tests(metafunc: pytest.Metafunc) -> None:
    """Parametrise ``record`` with every json record (or one placeholder that fails)."""
    if "record" not in metafunc.fixturenames:
        return
    if _LOAD_ERROR is not None:
        metafunc.parametrize("record", [MissingVectors(_LOAD_ERROR)], ids=["vectors-missing"])
        return
    ids = [f"{i:02d}-{r.get('name')}-{r.get('point')}" for i, r in enumerate(_RECORDS)]
    metafunc.parametrize("record", _RECORDS, ids=ids)


@pytest.fixture(scope="session")
def vectors():
    """All json records (a list of dicts), or a placeholder whose use fails the test."""
    return MissingVectors(_LOAD_ERROR) if _LOAD_ERROR is not None else _RECORDS
