"""What a results store checks when it is opened: that its path can be written, that its meta
row belongs to the plan and this library (or why not, with the fix), and that every stored run
belongs to the plan of its meta row. Used by :class:`mawdo.experiments.store.Store` alone."""

from __future__ import annotations

import json
import sqlite3
from pathlib import Path
from typing import Any

from mawdo.experiments.plans import PlanError
from mawdo.experiments.protocol import STUDY_KINDS, StudyKind, plan_from_json
from mawdo.experiments.sqlitefile import (
    SCHEMA_VERSION,
    StoreError,
    add_missing_columns,
    create_tables,
    drop_tables,
    library_version,
    old_schema_message,
    read_meta,
    translate,
    writable,
    write_meta,
)

__all__ = ["check_row_hashes", "check_writable_path", "open_meta"]


def open_meta(conn, path: Path, plan: Any, kind: StudyKind, force: bool) -> dict[str, Any]:
    """The meta row of a store opened for ``plan``: created, accepted, or reset with force."""
    meta = read_meta(conn, path)
    if meta is None:
        with translate(path, "initialise"):
            drop_tables(conn)  # half-made files (tables without a meta row)
            create_tables(conn, kind.row)
        return write_meta(conn, path, plan)
    problem = _mismatch(meta, plan)
    mixed = None if problem else _foreign_rows(conn, path, meta["plan_hash"], force_hint=True)
    if mixed and not force:
        raise StoreError(mixed)
    if problem or mixed:
        if problem and not force:
            raise StoreError(_refusal(conn, path, meta, problem))
        with translate(path, "reset"):
            drop_tables(conn)
            create_tables(conn, kind.row)
        meta = write_meta(conn, path, plan)
    else:  # the same plan and version: columns added to the row type since are added here
        with translate(path, "update"):
            add_missing_columns(conn, kind.row)
    return meta


def check_row_hashes(conn, path: Path, plan_hash: str, force_hint: bool) -> None:
    """Refuse a store holding runs computed for another plan than its meta row's."""
    msg = _foreign_rows(conn, path, plan_hash, force_hint)
    if msg:
        raise StoreError(msg)


def _foreign_rows(conn, path: Path, plan_hash: str, force_hint: bool) -> str | None:
    """Why a store holds runs of another plan than its meta row's, or None."""
    with translate(path, "read"):
        bad = conn.execute(
            "SELECT plan_hash, COUNT(*) FROM runs WHERE plan_hash != ? GROUP BY plan_hash",
            (plan_hash,),
        ).fetchall()
    if bad:
        others = ", ".join(f"{n} of plan {h[:12]}" for h, n in bad)
        fix = (
            "add --force (force=True) to discard its runs and start over"
            if force_hint
            else "re-run the study into a new file"
        )
        return (
            f"results store {path} mixes plans: it belongs to plan {plan_hash[:12]} but holds "
            f"runs {others}. Its results cannot be reported; {fix}."
        )
    return None


def check_writable_path(path: Path) -> None:
    """Refuse a store path that cannot be written (a folder, read-only, no room for WAL files)."""
    if path.is_dir():
        raise StoreError(
            f"results store {path} is a directory; give a file name like {path / 'results.db'}"
        )
    if path.exists() and not writable(path):
        raise StoreError(
            f"results store {path} is read-only; cannot write results to it "
            f"(make it writable or choose another --out file)"
        )
    try:
        path.parent.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise StoreError(
            f"cannot create directory {path.parent} for results store {path}: {exc.strerror or exc}"
        ) from None
    if not writable(path.parent):
        # WAL mode creates PATH-wal and PATH-shm next to the file.
        raise StoreError(
            f"directory {path.parent} is read-only; cannot write results store "
            f"{path} (SQLite needs to create {path.name}-wal there)"
        )


def _refusal(conn: sqlite3.Connection, path: Path, meta: dict, problem: str) -> str:
    if meta.get("schema_version") != SCHEMA_VERSION:
        return old_schema_message(path, meta)
    n = conn.execute("SELECT COUNT(*) FROM runs").fetchone()[0]
    return (
        f"results store {path} belongs to {problem}. Refusing to mix results: use another "
        f"--out file, or --force (force=True) to discard its {n} stored runs and start over. "
        f"Reports and exports read it as it is (read-only)."
    )


def _mismatch(meta: dict[str, Any], plan: Any) -> str | None:
    """Why a stored meta row does not match ``plan`` and this library, or None."""
    if meta.get("schema_version") != SCHEMA_VERSION:
        return f"store schema {meta.get('schema_version')} (this library writes {SCHEMA_VERSION})"
    if STUDY_KINDS.resolve(meta["study_kind"]) != plan.kind:  # a kind's former name is it
        return f"another study kind ({meta['study_kind']!r}, this plan is {plan.kind!r})"
    if meta["library_version"] != library_version():
        return (
            f"mawdo {meta['library_version']} (this is mawdo {library_version()}; results "
            f"of different versions may differ)"
        )
    if meta["plan_hash"] != plan.plan_hash:
        try:
            old = plan_from_json(meta["plan_json"], stored=True).numbers_spec()
            new = plan.numbers_spec()
            diff = [
                f"{k} ({_short(old.get(k))} -> {_short(new.get(k))})"
                for k in new
                if old.get(k) != new.get(k)
            ]
            what = "; differs in " + ", ".join(diff) if diff else ""
        except PlanError:
            what = ""
        return (
            f"another plan (hash {meta['plan_hash'][:12]}, this plan {plan.plan_hash[:12]}{what})"
        )
    return None


def _short(v: Any) -> str:
    s = json.dumps(v)
    return s if len(s) <= 40 else s[:37] + "..."
