"""Low-level pieces of the results store: the SQLite file, its tables and its meta row.

Schema (``SCHEMA_VERSION`` 3)
-----------------------------
``meta``  one row: ``schema_version, study_kind, plan_hash, plan_json, library_version,
          created``.
``runs``  one row per finished run, primary key ``(algorithm, problem, run)``: ``plan_hash,
          algorithm, problem``, then one column per field of the study kind's row type
          (:mod:`mawdo.experiments.rows`; ``run, wall_time, error_text`` first), then
          ``library_version, task_id``.
``tasks`` one row per executed task (the log of what was computed, and where).

Version 3 (mawdo 0.2.0, the study-kind redesign) replaced the one wide ``runs`` table,
whose planning rows reused the benchmark's ``function``/``fun``/``nit`` columns, by one typed
table per kind; older stores are refused with a message that says how to re-run them.
"""

from __future__ import annotations

import os
import sqlite3
import stat
from datetime import UTC, datetime
from pathlib import Path
from typing import Any

from mawdo.experiments.rows import STORAGE_SQL, RunRow, schema

SCHEMA_VERSION = 3
"""Layout of the store's tables. Bumped from 2: typed per-kind ``runs`` columns (see above)."""


class StoreError(RuntimeError):
    """The results store cannot be used as asked (wrong plan, corrupt, read-only ...)."""


class StoreWriteError(StoreError):
    """Writing a computed task into the store failed (a full disk, a lost file, a store changed
    under the sweep): a failure during the work, not a bad store given."""


def library_version() -> str:
    from mawdo import __version__

    return __version__


_META = """
CREATE TABLE meta (
    id INTEGER PRIMARY KEY CHECK (id = 1),
    schema_version INTEGER NOT NULL,
    study_kind TEXT NOT NULL,
    plan_hash TEXT NOT NULL,
    plan_json TEXT NOT NULL,
    library_version TEXT NOT NULL,
    created TEXT NOT NULL
)"""

_TASKS = """
CREATE TABLE tasks (
    id INTEGER PRIMARY KEY AUTOINCREMENT,
    algorithm TEXT NOT NULL,
    problem TEXT NOT NULL,
    first_run INTEGER NOT NULL,
    n_runs INTEGER NOT NULL,
    wall_time REAL,
    worker TEXT,
    finished TEXT NOT NULL,
    platform TEXT
)"""

TASK_COLUMNS = (
    "id",
    "algorithm",
    "problem",
    "first_run",
    "n_runs",
    "wall_time",
    "worker",
    "finished",
    "platform",
)
META_COLUMNS = (
    "schema_version",
    "study_kind",
    "plan_hash",
    "plan_json",
    "library_version",
    "created",
)


def runs_columns(row_type: type[RunRow]) -> tuple[str, ...]:
    """Every column of the ``runs`` table of a kind, in table order."""
    return (
        "plan_hash",
        "algorithm",
        "problem",
        *(n for n, _ in schema(row_type)),
        "library_version",
        "task_id",
    )


def create_tables(conn: sqlite3.Connection, row_type: type[RunRow]) -> None:
    """The three tables of a fresh store, ``runs`` typed by ``row_type`` (in one transaction)."""
    cols = ",\n    ".join(
        f"{name} {STORAGE_SQL[storage]}{' NOT NULL' if name == 'run' else ''}"
        for name, storage in schema(row_type)
    )
    runs = (
        "CREATE TABLE runs (\n    plan_hash TEXT NOT NULL,\n    algorithm TEXT NOT NULL,\n"
        f"    problem TEXT NOT NULL,\n    {cols},\n    library_version TEXT NOT NULL,\n"
        "    task_id INTEGER,\n    PRIMARY KEY (algorithm, problem, run)\n)"
    )
    with conn:
        for stmt in (_META, runs, _TASKS):
            conn.execute(stmt)


def add_missing_columns(conn: sqlite3.Connection, row_type: type[RunRow]) -> list[str]:
    """Add to ``runs`` the columns of ``row_type`` that a store made before they existed lacks
    (NULL in its rows, read as None), so that resuming it can write rows of today's type;
    returns their names."""
    present = table_columns(conn, "runs")
    missing = [(n, s) for n, s in schema(row_type) if n not in present]
    with conn:
        for name, storage in missing:
            conn.execute(f"ALTER TABLE runs ADD COLUMN {name} {STORAGE_SQL[storage]}")
        if "platform" not in table_columns(conn, "tasks"):  # stores made before it existed
            conn.execute("ALTER TABLE tasks ADD COLUMN platform TEXT")
    return [n for n, _ in missing]


def table_columns(conn: sqlite3.Connection, table: str) -> set[str]:
    """The names of a table's columns."""
    return {r[1] for r in conn.execute(f"PRAGMA table_info({table})").fetchall()}


def drop_tables(conn: sqlite3.Connection) -> None:
    with conn:
        for t in ("runs", "tasks", "meta"):
            conn.execute(f"DROP TABLE IF EXISTS {t}")


def read_meta(conn: sqlite3.Connection, path: Path) -> dict[str, Any] | None:
    """The meta row as a dict; None for a file without one. A store of an older layout gives
    its ``schema_version`` (and whatever else it has) so the caller can say what to do."""
    try:
        have = [r[1] for r in conn.execute("PRAGMA table_info(meta)").fetchall()]
        if not have:
            return None
        cols = [c for c in META_COLUMNS if c in have]
        row = conn.execute(f"SELECT {', '.join(cols)} FROM meta").fetchone()
    except sqlite3.DatabaseError as exc:
        raise StoreError(f"{path} is not a mawdo results store ({exc})") from None
    if row is None:
        return None
    return dict(zip(cols, row, strict=True))


def write_meta(conn: sqlite3.Connection, path: Path, plan: Any) -> dict[str, Any]:
    meta = {
        "schema_version": SCHEMA_VERSION,
        "study_kind": plan.kind,
        "plan_hash": plan.plan_hash,
        "plan_json": plan.to_json(),
        "library_version": library_version(),
        "created": now(),
    }
    with translate(path, "initialise"), conn:
        conn.execute(
            f"INSERT INTO meta (id, {', '.join(META_COLUMNS)}) VALUES (1, ?, ?, ?, ?, ?, ?)",
            tuple(meta[c] for c in META_COLUMNS),
        )
    return meta


def old_schema_message(path: Path, meta: dict[str, Any]) -> str:
    """What to do with a store written by an older layout."""
    return (
        f"results store {path} has store schema {meta.get('schema_version')} (this mawdo reads "
        f"and writes schema {SCHEMA_VERSION}: typed rows per study kind). Its runs cannot be "
        f"read by this version. Re-run the sweep into a new file (the same command with another "
        f"--out), or add --force (force=True) to discard its runs and recompute them in place; "
        f"to report from it, use the mawdo version that wrote it "
        f"({meta.get('library_version', 'unknown')})."
    )


def writable(p: Path) -> bool:
    # Root passes os.access on any file, so the permission bits are checked as well: a store
    # someone marked read-only is treated as read-only whoever runs the sweep.
    try:
        mode = p.stat().st_mode
    except OSError:
        return False
    return os.access(p, os.W_OK) and bool(mode & (stat.S_IWUSR | stat.S_IWGRP | stat.S_IWOTH))


def now() -> str:
    return datetime.now(UTC).isoformat(timespec="seconds")


def connect(path: Path, readonly: bool) -> sqlite3.Connection:
    try:
        if readonly:
            return _connect_readonly(path)
        return sqlite3.connect(path, timeout=30)
    except sqlite3.Error as exc:
        raise StoreError(f"cannot open results store {path}: {exc}") from None


def _connect_readonly(path: Path) -> sqlite3.Connection:
    # mode=ro: a report never writes, and works on a store someone made read-only.
    uri = path.resolve().as_uri()
    conn = None
    try:
        conn = sqlite3.connect(f"{uri}?mode=ro", uri=True, timeout=30)
        conn.execute("SELECT COUNT(*) FROM sqlite_master").fetchone()
        return conn
    except sqlite3.OperationalError:
        if conn is not None:
            conn.close()
    except sqlite3.DatabaseError:
        return conn  # not a database at all: check_foreign says so
    # A store left in WAL mode (a writer killed with -9) on read-only media: SQLite cannot
    # create the -shm file. With no -wal file beside it nothing is pending, so the file alone
    # is the whole store and can be opened as immutable.
    wal = path.with_name(path.name + "-wal")
    if wal.exists() and wal.stat().st_size > 0:
        raise StoreError(
            f"cannot read results store {path}: it is on a read-only location and its "
            f"write-ahead log {wal.name} holds runs not yet folded into it. Copy both files "
            f"to a writable folder and report from the copy."
        )
    return sqlite3.connect(f"{uri}?immutable=1", uri=True, timeout=30)


CORRUPT_ADVICE = (
    "Its stored runs cannot be trusted. Recover: restore the file from a backup, or move it "
    "away and run the same command again into a new file (every run is recomputed "
    "identically from the plan); `sqlite3 BROKEN.db .recover | sqlite3 NEW.db` may salvage "
    "the intact rows for inspection."
)


def quick_check(conn: sqlite3.Connection, path: Path) -> None:
    """Refuse a damaged file: ``PRAGMA quick_check`` (pages, records, index order).

    Linear in the file size (0.2 s for a 200 MB file, warm cache); run when a store is opened for
    writing or reporting, so a damaged store is never resumed as "complete" nor reported from.
    """
    try:
        found = [r[0] for r in conn.execute("PRAGMA quick_check(5)").fetchall()]
    except sqlite3.DatabaseError as exc:
        found = [str(exc)]
    if found != ["ok"]:
        raise StoreError(
            f"results store {path} is corrupt ({'; '.join(found)[:300]}). {CORRUPT_ADVICE}"
        )


def leave_clean(conn: sqlite3.Connection) -> None:
    """Fold the write-ahead log back into the file and switch to the DELETE journal, so the
    store is one self-contained file that read-only media can serve. Best effort: a reader
    holding the file keeps WAL mode, which is still consistent."""
    try:
        conn.execute("PRAGMA wal_checkpoint(TRUNCATE)")
        conn.execute("PRAGMA journal_mode=DELETE")
    except sqlite3.Error:
        pass


def check_foreign(conn: sqlite3.Connection, path: Path) -> None:
    """Fail clearly on a file that is not SQLite, or SQLite that is not ours."""
    try:
        tables = {
            r[0]
            for r in conn.execute("SELECT name FROM sqlite_master WHERE type = 'table'").fetchall()
        }
    except sqlite3.DatabaseError as exc:
        raise StoreError(
            f"{path} is not a readable SQLite results store ({exc}); the file is corrupt or "
            f"of another kind. Move it away or choose another --out file. {CORRUPT_ADVICE}"
        ) from None
    ours = {"meta", "runs", "tasks"}
    if tables and not ours & tables:
        raise StoreError(
            f"{path} is a SQLite database of something else (tables: "
            f"{', '.join(sorted(tables))}), not a mawdo results store"
        )


class translate:
    """Turn sqlite3 errors into StoreError messages that name the file and the action."""

    def __init__(self, path: Path, action: str) -> None:
        self.path, self.action = path, action

    def __enter__(self) -> None:
        return None

    def __exit__(self, typ, exc, tb) -> bool:
        if exc is None or not isinstance(exc, sqlite3.Error):
            return False
        msg = str(exc)
        error = StoreWriteError if self.action.startswith("write") else StoreError
        if "readonly" in msg or "read-only" in msg:
            raise error(
                f"cannot {self.action} results store {self.path}: it is read-only ({msg})"
            ) from None
        if isinstance(exc, sqlite3.IntegrityError):
            raise error(
                f"cannot {self.action} results store {self.path}: {msg} (a run "
                f"was computed twice; is another sweep writing to this file?)"
            ) from None
        raise error(f"cannot {self.action} results store {self.path}: {msg}") from None
