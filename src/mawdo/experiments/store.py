"""The results store: one SQLite file per study, one typed row per finished run.

SQLite (stdlib) in WAL mode, written by one process (the runner's parent) one task at a time in
a single transaction, so a crash or ``kill -9`` leaves only whole tasks behind and a re-run skips
exactly what is stored. Reports and plots read this file and nothing else.

The store knows study kinds only through :data:`mawdo.experiments.protocol.STUDY_KINDS`: the
plan's kind gives the row type, and the row type gives the ``runs`` columns
(:mod:`mawdo.experiments.sqlitefile` has the layout).
"""

from __future__ import annotations

import sqlite3
from pathlib import Path
from typing import Any

from mawdo.experiments.lock import StoreLockedError, WriterLock
from mawdo.experiments.plans import PlanError
from mawdo.experiments.protocol import StudyKind, kind_of, plan_from_json
from mawdo.experiments.rows import (
    RowError,
    RunRow,
    check_row,
    from_sql,
    required_fields,
    schema,
    stored_value_problem,
    to_sql,
)
from mawdo.experiments.sqlitefile import (
    CORRUPT_ADVICE,
    SCHEMA_VERSION,
    TASK_COLUMNS,
    StoreError,
    StoreWriteError,
    check_foreign,
    connect,
    leave_clean,
    library_version,
    now,
    old_schema_message,
    quick_check,
    read_meta,
    runs_columns,
    table_columns,
    translate,
)
from mawdo.experiments.store_open import check_row_hashes, check_writable_path, open_meta

__all__ = ["SCHEMA_VERSION", "Store", "StoreError", "library_version"]


class Store:
    """A results store on disk. Use :meth:`open` to write a study, :meth:`read` for reports.

    Parameters
    ----------
    path : pathlib.Path
        The SQLite file.
    conn : sqlite3.Connection
        An open connection.
    plan : Study
        The plan the store belongs to (from its meta row).
    meta : dict
        The meta row.
    writable : bool
        Whether this handle may write.
    """

    def __init__(
        self, path: Path, conn: sqlite3.Connection, plan: Any, meta: dict, writable: bool
    ) -> None:
        self.path = path
        self.conn = conn
        self.plan = plan
        self.meta = meta
        self.writable = writable
        self.kind: StudyKind = kind_of(plan)
        self.row_type: type[RunRow] = self.kind.row
        self._schema = schema(self.row_type)

    # ------------------------------------------------------------------ opening
    @classmethod
    def open(cls, path: str | Path, plan: Any, force: bool = False) -> Store:
        """Open (or create) the store at ``path`` for ``plan``, for writing.

        Parameters
        ----------
        path : str or Path
            SQLite file; created with its parent directories when absent.
        plan : Study
            The study to store (a plan of a registered kind).
        force : bool
            Accept a store created by another plan, kind, library version or store schema by
            discarding its runs and starting over. Without it such a store is refused.

        Raises
        ------
        StoreError
            A read-only file or directory, a file that is not SQLite (corrupt), a SQLite file
            that is not a mawdo store, or a store of another plan / library version / schema.
        """
        path = Path(path)
        kind = kind_of(plan)
        check_writable_path(path)
        try:
            lock = WriterLock(path)
        except StoreLockedError as exc:
            raise StoreError(str(exc)) from None
        except OSError as exc:
            raise StoreError(f"cannot lock results store {path}: {exc}") from None
        conn = None
        try:
            conn = connect(path, readonly=False)
            check_foreign(conn, path)
            quick_check(conn, path)
            meta = open_meta(conn, path, plan, kind, force)
            with translate(path, "initialise"):
                # WAL only once the store is accepted: a refused run leaves the file as it was.
                conn.execute("PRAGMA journal_mode=WAL")
                # NORMAL is durable against process crashes in WAL mode, which is what a sweep
                # needs; FULL would also survive power loss at the price of an fsync per task.
                conn.execute("PRAGMA synchronous=NORMAL")
        except BaseException:
            if conn is not None:
                leave_clean(conn)
                conn.close()
            lock.release()
            raise
        store = cls(path, conn, plan, meta, writable=True)
        store._lock = lock
        return store

    @classmethod
    def read(cls, path: str | Path) -> Store:
        """Open an existing store read-only (reports, plots); its plan comes from the file."""
        path = Path(path)
        if not path.is_file():
            raise StoreError(f"no results store at {path}")
        conn = connect(path, readonly=True)
        try:
            check_foreign(conn, path)
            meta = read_meta(conn, path)
            if meta is None:
                raise StoreError(
                    f"{path} is a SQLite file but not a mawdo results store (no meta row)"
                )
            if meta.get("schema_version") != SCHEMA_VERSION:
                raise StoreError(old_schema_message(path, meta))
            quick_check(conn, path)
            check_row_hashes(conn, path, meta["plan_hash"], force_hint=False)
            try:
                plan = plan_from_json(meta["plan_json"], stored=True)
            except PlanError as exc:
                raise StoreError(f"{path}: its stored plan is no longer valid: {exc}") from None
            if plan.plan_hash != meta["plan_hash"]:
                raise StoreError(
                    f"results store {path} is inconsistent: its meta row says plan "
                    f"{meta['plan_hash'][:12]} but its stored plan hashes to "
                    f"{plan.plan_hash[:12]} (edited by hand?). {CORRUPT_ADVICE}"
                )
        except BaseException:
            conn.close()
            raise
        return cls(path, conn, plan, meta, writable=False)

    def close(self) -> None:
        """Close the connection. A writer folds the WAL back into the file first (so a closed
        store is one self-contained file: copy it anywhere, read it on read-only media), then
        releases its writer lock."""
        if self.writable:
            leave_clean(self.conn)
        self.conn.close()
        lock = getattr(self, "_lock", None)
        if lock is not None:
            lock.release()

    def __enter__(self) -> Store:
        return self

    def __exit__(self, *exc) -> None:
        self.close()

    # ------------------------------------------------------------------ writing
    def write_task(self, outcome: dict[str, Any]) -> int:
        """Store one executed task's runs and its log entry in one transaction.

        Parameters
        ----------
        outcome : dict
            As returned by :func:`mawdo.experiments.runner.execute_task`: ``task`` (a dict with
            algorithm, problem, first_run, n_runs), ``rows`` (the kind's row objects),
            ``wall``, ``worker``.

        Returns
        -------
        int
            The task's id in the ``tasks`` table.
        """
        if not self.writable:
            raise StoreWriteError(f"results store {self.path} was opened read-only")
        t = outcome["task"]
        for r in outcome["rows"]:
            try:
                check_row(r, self.row_type)
            except RowError as exc:
                raise StoreWriteError(f"cannot write to results store {self.path}: {exc}") from None
        computed_for = outcome.get("plan_hash", self.plan.plan_hash)
        if computed_for != self.plan.plan_hash:
            raise StoreWriteError(
                f"cannot write to results store {self.path}: task {t['algorithm']} on "
                f"{t['problem']} was computed for plan {str(computed_for)[:12]}, the store "
                f"holds plan {self.plan.plan_hash[:12]}"
            )
        version = library_version()
        with translate(self.path, "write to"), self.conn:
            stored = self.conn.execute("SELECT plan_hash FROM meta").fetchone()
            if stored is None or stored[0] != self.plan.plan_hash:
                # Only reachable if something bypassed the writer lock (another library, a
                # hand edit): never add rows to a store that now belongs to another plan.
                raise StoreWriteError(
                    f"results store {self.path} was reset to another plan while this sweep "
                    f"was writing to it; nothing more is written. Re-run the sweep."
                )
            cur = self.conn.execute(
                "INSERT INTO tasks (algorithm, problem, first_run, n_runs, wall_time, worker, "
                "finished, platform) VALUES (?, ?, ?, ?, ?, ?, ?, ?)",
                (
                    t["algorithm"],
                    t["problem"],
                    t["first_run"],
                    t["n_runs"],
                    outcome["wall"],
                    outcome.get("worker"),
                    now(),
                    outcome.get("platform"),
                ),
            )
            task_id = cur.lastrowid
            self._drop_errors(t)
            head = (self.plan.plan_hash, t["algorithm"], t["problem"])
            values = [
                (
                    *head,
                    *(to_sql(getattr(r, n), s) for n, s in self._schema),
                    version,
                    task_id,
                )
                for r in outcome["rows"]
            ]
            cols = runs_columns(self.row_type)
            self.conn.executemany(
                f"INSERT INTO runs ({', '.join(cols)}) VALUES ({', '.join('?' * len(cols))})",
                values,
            )
        return int(task_id)

    def _drop_errors(self, t: dict[str, Any]) -> None:
        # A recomputed failure (run_plan's retry_failed) replaces its error row here, in the
        # transaction of its new row: a crash in between loses neither. Rows without an error
        # are results and are never replaced (their insert would be refused).
        self.conn.execute(
            "DELETE FROM runs WHERE algorithm = ? AND problem = ? AND run >= ? AND run < ? "
            "AND error_text IS NOT NULL",
            (t["algorithm"], t["problem"], t["first_run"], t["first_run"] + t["n_runs"]),
        )

    # ------------------------------------------------------------------ reading
    def done_keys(self, failed: bool = True) -> set[tuple[str, str, int]]:
        """``(algorithm, problem, run)`` of every stored run; runs that failed with an error
        (``error_text`` set) only if ``failed``."""
        where = "" if failed else " WHERE error_text IS NULL"
        rows = self.conn.execute(f"SELECT algorithm, problem, run FROM runs{where}").fetchall()
        return {(a, f, int(k)) for a, f, k in rows}

    def count(self, failed: bool | None = None) -> int:
        """Number of stored runs (all, only failed, or only successful)."""
        where = {
            None: "",
            True: " WHERE error_text IS NOT NULL",
            False: " WHERE error_text IS NULL",
        }[failed]
        return int(self.conn.execute(f"SELECT COUNT(*) FROM runs{where}").fetchone()[0])

    def rows(
        self,
        algorithm: str | None = None,
        problem: str | None = None,
        skip: tuple[str, ...] = (),
    ) -> list[tuple[str, str, RunRow]]:
        """Stored runs as ``(algorithm, problem, row)``, ordered by algorithm, problem and run.

        Parameters
        ----------
        algorithm, problem : str, optional
            Filters.
        skip : tuple of str
            Row fields not to read (large blobs a caller does not need); they come back as
            their default (None), as do fields the store's ``runs`` table lacks (columns added
            to the row type after the store was made).
        """
        unknown = set(skip) - {n for n, _ in self._schema}
        if unknown:
            raise ValueError(f"skip: {sorted(unknown)} are not fields of {self.row_type.__name__}")
        # a column added to the row type after the store was made reads as its default (None)
        present = {c[1] for c in self.conn.execute("PRAGMA table_info(runs)").fetchall()}
        read = [(n, s) for n, s in self._schema if n not in skip and n in present]
        cond, args = [], []
        for col, val in (("algorithm", algorithm), ("problem", problem)):
            if val is not None:
                cond.append(f"{col} = ?")
                args.append(val)
        where = f" WHERE {' AND '.join(cond)}" if cond else ""
        cols = ", ".join(["algorithm", "problem", *(n for n, _ in read)])
        out = []
        check_row_hashes(self.conn, self.path, self.meta["plan_hash"], force_hint=False)
        with translate(self.path, "read"):
            fetched = self.conn.execute(
                f"SELECT {cols} FROM runs{where} ORDER BY algorithm, problem, run", args
            ).fetchall()
        damaged = self._damaged(fetched, read)
        if damaged:
            more = f" and {len(damaged) - 5} more" if len(damaged) > 5 else ""
            raise StoreError(
                f"results store {self.path} is damaged: {len(damaged)} stored runs hold values "
                f"no run writes: {'; '.join(damaged[:5])}{more}. The store was changed outside "
                "mawdo: run the study again into a new store (or delete these rows from its "
                "runs table and run the same command again to recompute them)"
            )
        for a, p, *vals in fetched:
            try:
                fields = {n: from_sql(v, s) for (n, s), v in zip(read, vals, strict=True)}
            except RowError as exc:
                raise StoreError(
                    f"results store {self.path} is damaged: {a} on {p}: {exc}"
                ) from None
            out.append((a, p, self.row_type(**fields)))
        return out

    def _damaged(self, fetched: list[tuple], read: list[tuple[str, str]]) -> list[str]:
        """One line per stored run whose values no run writes: a value of the wrong type
        (text in a number's column), or NULL in a column every finished run fills."""
        required = required_fields(self.row_type)
        names = [n for n, _ in read]
        out = []
        for a, p, *vals in fetched:
            row = dict(zip(names, vals, strict=True))
            problems = [
                f"{n} {why}"
                for (n, s), v in zip(read, vals, strict=True)
                if (why := stored_value_problem(v, s))
            ]
            if row.get("error_text") is None:
                problems += [f"{n} is NULL" for n in names if n in required and row[n] is None]
            if problems:
                out.append(f"{a} on {p} run {row.get('run')}: {', '.join(problems)}")
        return out

    def task_log(self) -> list[dict[str, Any]]:
        """Every executed task, in execution order; ``platform`` (what computed it, see
        :func:`mawdo.experiments.machine.platform_summary`) is None in stores made before it was
        recorded."""
        cols = [c for c in TASK_COLUMNS if c in table_columns(self.conn, "tasks")]
        rows = self.conn.execute(f"SELECT {', '.join(cols)} FROM tasks ORDER BY id").fetchall()
        return [{**dict.fromkeys(TASK_COLUMNS), **dict(zip(cols, r, strict=True))} for r in rows]
