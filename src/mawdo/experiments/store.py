"""The results store: one SQLite file per sweep, one row per finished run.

SQLite (stdlib) in WAL mode, written by one process (the runner's parent) one task at a time in
a single transaction, so a crash or ``kill -9`` leaves only whole tasks behind and a re-run skips
exactly what is stored. Reports and plots read this file and nothing else.

Schema (``SCHEMA_VERSION`` 1)
-----------------------------
``meta``  one row: ``schema_version, plan_hash, plan_json, library_version, created``.
``runs``  one row per finished run, primary key ``(algorithm, function, shifted, run)``:
          ``plan_hash, params_json, seed_entropy, shift_seed, fun, error (= fun - f_star),
          f_star, nfev, nit, status, wall_time, curve, curve_nfev, curve_len,
          library_version, error_text, task_id``. ``curve`` is the best-so-far value after each
          iteration as little-endian float64 bytes, ``curve_nfev`` the evaluations spent after
          each iteration as little-endian int64 bytes; ``curve_len`` entries each. A failed run
          has ``fun`` NULL and the exception in ``error_text``.
``tasks`` one row per executed task (the log of what was computed, and where).
"""

from __future__ import annotations

import json
import os
import sqlite3
import stat
from dataclasses import dataclass
from datetime import UTC, datetime
from pathlib import Path
from typing import Any

import numpy as np

from mawdo.experiments.plan import ExperimentPlan, PlanError

SCHEMA_VERSION = 2

_SCHEMA = """
CREATE TABLE IF NOT EXISTS meta (
    id INTEGER PRIMARY KEY CHECK (id = 1),
    schema_version INTEGER NOT NULL,
    plan_hash TEXT NOT NULL,
    plan_json TEXT NOT NULL,
    library_version TEXT NOT NULL,
    created TEXT NOT NULL
);
CREATE TABLE IF NOT EXISTS runs (
    plan_hash TEXT NOT NULL,
    algorithm TEXT NOT NULL,
    function TEXT NOT NULL,
    shifted INTEGER NOT NULL,
    run INTEGER NOT NULL,
    params_json TEXT NOT NULL,
    seed_entropy TEXT NOT NULL,
    shift_seed INTEGER,
    fun REAL,
    error REAL,
    f_star REAL,
    nfev INTEGER,
    nit INTEGER,
    status INTEGER,
    wall_time REAL,
    curve BLOB,
    curve_nfev BLOB,
    curve_len INTEGER,
    library_version TEXT NOT NULL,
    error_text TEXT,
    task_id INTEGER,
    metrics_json TEXT,
    payload BLOB,
    PRIMARY KEY (algorithm, function, shifted, run)
);
CREATE TABLE IF NOT EXISTS tasks (
    id INTEGER PRIMARY KEY AUTOINCREMENT,
    algorithm TEXT NOT NULL,
    function TEXT NOT NULL,
    first_run INTEGER NOT NULL,
    n_runs INTEGER NOT NULL,
    wall_time REAL,
    worker TEXT,
    finished TEXT NOT NULL
);
"""

_RUN_COLUMNS = (
    "plan_hash",
    "algorithm",
    "function",
    "shifted",
    "run",
    "params_json",
    "seed_entropy",
    "shift_seed",
    "fun",
    "error",
    "f_star",
    "nfev",
    "nit",
    "status",
    "wall_time",
    "curve",
    "curve_nfev",
    "curve_len",
    "library_version",
    "error_text",
    "task_id",
    "metrics_json",
    "payload",
)


class StoreError(RuntimeError):
    """The results store cannot be used as asked (wrong plan, corrupt, read-only ...)."""


def library_version() -> str:
    from mawdo import __version__

    return __version__


@dataclass(frozen=True)
class RunRecord:
    """One stored run, as read back from the ``runs`` table."""

    algorithm: str
    function: str
    shifted: bool
    run: int
    fun: float | None
    error: float | None
    f_star: float | None
    nfev: int | None
    nit: int | None
    status: int | None
    wall_time: float | None
    params: dict[str, Any]
    seed_entropy: list[int]
    shift_seed: int | None
    curve: np.ndarray
    curve_nfev: np.ndarray
    library_version: str
    error_text: str | None

    @property
    def failed(self) -> bool:
        return self.error_text is not None


def encode_f64(a: np.ndarray) -> bytes:
    """Array -> little-endian float64 bytes (explicit byte order: files move between hosts)."""
    return np.ascontiguousarray(a, dtype="<f8").tobytes()


def encode_i64(a: np.ndarray) -> bytes:
    return np.ascontiguousarray(a, dtype="<i8").tobytes()


def decode(blob: bytes | None, dtype: str, n: int | None) -> np.ndarray:
    if blob is None:
        return np.empty(0, dtype=dtype)
    arr = np.frombuffer(blob, dtype=dtype)
    if n is not None and arr.size != n:
        raise StoreError(f"stored curve has {arr.size} entries, expected {n}: the store is damaged")
    return arr.astype(dtype[1:])  # native byte order, writable copy


def _writable(p: Path) -> bool:
    # Root passes os.access on any file, so the permission bits are checked as well: a store
    # someone marked read-only is treated as read-only whoever runs the sweep.
    try:
        mode = p.stat().st_mode
    except OSError:
        return False
    return os.access(p, os.W_OK) and bool(mode & (stat.S_IWUSR | stat.S_IWGRP | stat.S_IWOTH))


class Store:
    """A results store on disk. Use :meth:`open` to write a sweep, :meth:`read` for reports.

    Parameters
    ----------
    path : pathlib.Path
        The SQLite file.
    conn : sqlite3.Connection
        An open connection.
    plan : ExperimentPlan
        The plan the store belongs to (from its meta row).
    writable : bool
        Whether this handle may write.
    """

    def __init__(
        self,
        path: Path,
        conn: sqlite3.Connection,
        plan: ExperimentPlan,
        meta: dict[str, Any],
        writable: bool,
    ) -> None:
        self.path = path
        self.conn = conn
        self.plan = plan
        self.meta = meta
        self.writable = writable

    # ------------------------------------------------------------------ opening
    @classmethod
    def open(cls, path: str | Path, plan: ExperimentPlan, force: bool = False) -> Store:
        """Open (or create) the store at ``path`` for ``plan``, for writing.

        Parameters
        ----------
        path : str or Path
            SQLite file; created with its parent directories when absent.
        plan : ExperimentPlan
            The sweep to store.
        force : bool
            Accept a store created by another plan or library version by discarding its runs
            and starting over (the meta row is rewritten). Without it such a store is refused.

        Raises
        ------
        StoreError
            A read-only file or directory, a file that is not SQLite (corrupt), a SQLite file
            that is not a mawdo store, or a store of another plan / library version.
        """
        path = Path(path)
        if path.is_dir():
            raise StoreError(
                f"results store {path} is a directory; give a file name like {path / 'results.db'}"
            )
        if path.exists() and not _writable(path):
            raise StoreError(
                f"results store {path} is read-only; cannot write results to it "
                f"(make it writable or choose another --out file)"
            )
        try:
            path.parent.mkdir(parents=True, exist_ok=True)
        except OSError as exc:
            raise StoreError(
                f"cannot create directory {path.parent} for results store {path}: "
                f"{exc.strerror or exc}"
            ) from None
        if not _writable(path.parent):
            # WAL mode creates PATH-wal and PATH-shm next to the file.
            raise StoreError(
                f"directory {path.parent} is read-only; cannot write results store "
                f"{path} (SQLite needs to create {path.name}-wal there)"
            )
        conn = _connect(path, readonly=False)
        try:
            _check_foreign(conn, path)
            with _translate(path, "initialise"):
                conn.execute("PRAGMA journal_mode=WAL")
                # NORMAL is durable against process crashes in WAL mode, which is what a sweep
                # needs; FULL would also survive power loss at the price of an fsync per task.
                conn.execute("PRAGMA synchronous=NORMAL")
                with conn:
                    for stmt in _SCHEMA.split(";"):
                        if stmt.strip():
                            conn.execute(stmt)
            meta = _read_meta(conn, path)
            if meta is None:
                meta = _write_meta(conn, path, plan)
            else:
                problem = _mismatch(meta, plan)
                if problem:
                    if not force:
                        n = conn.execute("SELECT COUNT(*) FROM runs").fetchone()[0]
                        raise StoreError(
                            f"results store {path} belongs to {problem}. Refusing to mix "
                            f"results: use another --out file, or --force (force=True) to "
                            f"discard its {n} stored runs and start over."
                        )
                    with _translate(path, "reset"), conn:
                        conn.execute("DELETE FROM runs")
                        conn.execute("DELETE FROM tasks")
                        conn.execute("DELETE FROM meta")
                    meta = _write_meta(conn, path, plan)
        except BaseException:
            conn.close()
            raise
        return cls(path, conn, plan, meta, writable=True)

    @classmethod
    def read(cls, path: str | Path) -> Store:
        """Open an existing store read-only (reports, plots); its plan comes from the file."""
        path = Path(path)
        if not path.is_file():
            raise StoreError(f"no results store at {path}")
        conn = _connect(path, readonly=True)
        try:
            _check_foreign(conn, path)
            meta = _read_meta(conn, path)
            if meta is None:
                raise StoreError(
                    f"{path} is a SQLite file but not a mawdo results store (no meta row)"
                )
            try:
                from mawdo.experiments.study import plan_from_json

                plan = plan_from_json(meta["plan_json"])
            except PlanError as exc:
                raise StoreError(f"{path}: its stored plan is no longer valid: {exc}") from None
        except BaseException:
            conn.close()
            raise
        return cls(path, conn, plan, meta, writable=False)

    def close(self) -> None:
        """Close the connection. A writer folds the WAL back into the file first, so a closed
        store is one self-contained file (copy it anywhere)."""
        if self.writable:
            try:
                self.conn.execute("PRAGMA wal_checkpoint(TRUNCATE)")
                self.conn.execute("PRAGMA journal_mode=DELETE")
            except sqlite3.Error:
                pass  # another reader holds the file; WAL stays, which is still consistent
        self.conn.close()

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
            algorithm, function, first_run, n_runs), ``rows`` (one dict per run), ``wall``,
            ``worker``.

        Returns
        -------
        int
            The task's id in the ``tasks`` table.
        """
        if not self.writable:
            raise StoreError(f"results store {self.path} was opened read-only")
        t = outcome["task"]
        version = library_version()
        shifted = int(self.plan.shifted)
        with _translate(self.path, "write to"), self.conn:
            cur = self.conn.execute(
                "INSERT INTO tasks (algorithm, function, first_run, n_runs, wall_time, worker, "
                "finished) VALUES (?, ?, ?, ?, ?, ?, ?)",
                (
                    t["algorithm"],
                    t["function"],
                    t["first_run"],
                    t["n_runs"],
                    outcome["wall"],
                    outcome.get("worker"),
                    _now(),
                ),
            )
            task_id = cur.lastrowid
            values = []
            for r in outcome["rows"]:
                curve = r.get("curve")
                values.append(
                    (
                        self.plan.plan_hash,
                        t["algorithm"],
                        t["function"],
                        shifted,
                        r["run"],
                        json.dumps(r.get("params") or {}, sort_keys=True, default=_json_default),
                        json.dumps(r["seed_entropy"]),
                        r.get("shift_seed"),
                        r.get("fun"),
                        r.get("error"),
                        r.get("f_star"),
                        r.get("nfev"),
                        r.get("nit"),
                        r.get("status"),
                        r.get("wall_time"),
                        None if curve is None else encode_f64(curve),
                        None if curve is None else encode_i64(r["curve_nfev"]),
                        None if curve is None else int(len(curve)),
                        version,
                        r.get("error_text"),
                        task_id,
                        None
                        if r.get("metrics") is None
                        else json.dumps(r["metrics"], default=_json_default),
                        r.get("payload"),
                    )
                )
            self.conn.executemany(
                f"INSERT INTO runs ({', '.join(_RUN_COLUMNS)}) "
                f"VALUES ({', '.join('?' * len(_RUN_COLUMNS))})",
                values,
            )
        return int(task_id)

    def delete_failed(self) -> int:
        """Remove failed runs (so a re-run retries them); returns how many were removed."""
        with _translate(self.path, "write to"), self.conn:
            cur = self.conn.execute("DELETE FROM runs WHERE error_text IS NOT NULL")
        return cur.rowcount

    # ------------------------------------------------------------------ reading
    def done_keys(self) -> set[tuple[str, str, int]]:
        """``(algorithm, function, run)`` of every stored run, failed ones included."""
        rows = self.conn.execute("SELECT algorithm, function, run FROM runs").fetchall()
        return {(a, f, int(k)) for a, f, k in rows}

    def count(self, failed: bool | None = None) -> int:
        """Number of stored runs (all, only failed, or only successful)."""
        where = {
            None: "",
            True: " WHERE error_text IS NOT NULL",
            False: " WHERE error_text IS NULL",
        }[failed]
        return int(self.conn.execute(f"SELECT COUNT(*) FROM runs{where}").fetchone()[0])

    def records(
        self, algorithm: str | None = None, function: str | None = None, curves: bool = True
    ) -> list[RunRecord]:
        """Stored runs, ordered by algorithm, function and run; optionally filtered."""
        cond, args = [], []
        if algorithm is not None:
            cond.append("algorithm = ?")
            args.append(algorithm)
        if function is not None:
            cond.append("function = ?")
            args.append(function)
        where = f" WHERE {' AND '.join(cond)}" if cond else ""
        cols = (
            "algorithm, function, shifted, run, fun, error, f_star, nfev, nit, status, "
            "wall_time, params_json, seed_entropy, shift_seed, "
            + ("curve, curve_nfev, curve_len, " if curves else "NULL, NULL, NULL, ")
            + "library_version, error_text"
        )
        rows = self.conn.execute(
            f"SELECT {cols} FROM runs{where} ORDER BY algorithm, function, run", args
        ).fetchall()
        out = []
        for a, f, sh, k, fun, err, fs, nfev, nit, st, wall, pj, se, ss, c, cn, cl, lv, et in rows:
            out.append(
                RunRecord(
                    algorithm=a,
                    function=f,
                    shifted=bool(sh),
                    run=int(k),
                    fun=fun,
                    error=err,
                    f_star=fs,
                    nfev=nfev,
                    nit=nit,
                    status=st,
                    wall_time=wall,
                    params=json.loads(pj),
                    seed_entropy=json.loads(se),
                    shift_seed=ss,
                    curve=decode(c, "<f8", cl),
                    curve_nfev=decode(cn, "<i8", cl),
                    library_version=lv,
                    error_text=et,
                )
            )
        return out

    def finals(self) -> dict[tuple[str, str], dict[str, np.ndarray]]:
        """Final values per ``(algorithm, function)``: arrays ``run, fun, error, nfev, wall``
        of the successful runs (run order) and ``failed``, the number of failed runs."""
        out: dict[tuple[str, str], dict[str, Any]] = {}
        rows = self.conn.execute(
            "SELECT algorithm, function, run, fun, error, nfev, wall_time, error_text FROM runs "
            "ORDER BY algorithm, function, run"
        ).fetchall()
        acc: dict[tuple[str, str], list] = {}
        for a, f, k, fun, err, nfev, wall, et in rows:
            acc.setdefault((a, f), []).append((k, fun, err, nfev, wall, et))
        for key, items in acc.items():
            ok = [i for i in items if i[5] is None]
            out[key] = {
                "run": np.array([i[0] for i in ok], dtype=np.int64),
                "fun": np.array([i[1] for i in ok], dtype=float),
                "error": np.array([i[2] for i in ok], dtype=float),
                "nfev": np.array([i[3] for i in ok], dtype=float),
                "wall": np.array([i[4] for i in ok], dtype=float),
                "failed": len(items) - len(ok),
            }
        return out

    def curves(self, algorithm: str, function: str) -> tuple[np.ndarray, np.ndarray, float]:
        """Best-so-far curves of the successful runs of one (algorithm, function).

        Returns
        -------
        curve : numpy.ndarray
            ``(R, T)`` best-so-far values; shorter curves are padded with their last value.
        curve_nfev : numpy.ndarray
            ``(R, T)`` evaluations spent, padded the same way.
        f_star : float
            The function's optimum (NaN if unknown).
        """
        recs = [r for r in self.records(algorithm, function) if not r.failed]
        if not recs:
            return np.empty((0, 0)), np.empty((0, 0)), float("nan")
        T = max(r.curve.size for r in recs)
        c = np.stack([np.pad(r.curve, (0, T - r.curve.size), mode="edge") for r in recs])
        n = np.stack([np.pad(r.curve_nfev, (0, T - r.curve_nfev.size), mode="edge") for r in recs])
        fs = recs[0].f_star
        return c, n, float("nan") if fs is None else float(fs)

    def study_runs(self, algorithm: str | None = None, payload: bool = False) -> list[dict]:
        """Planning-study runs: ``algorithm, run, metrics`` (dict), and the serialised run
        (``payload``, bytes) when asked; failed runs have ``metrics=None`` and ``error_text``."""
        where, args = ("WHERE algorithm = ?", [algorithm]) if algorithm else ("", [])
        rows = self.conn.execute(
            f"SELECT algorithm, run, metrics_json, {'payload' if payload else 'NULL'}, "
            f"error_text, curve, curve_len FROM runs {where} ORDER BY algorithm, run",
            args,
        ).fetchall()
        return [
            {
                "algorithm": a,
                "run": int(k),
                "metrics": None if mj is None else json.loads(mj),
                "payload": pl,
                "error_text": et,
                "curve": decode(c, "<f8", cl),
            }
            for a, k, mj, pl, et, c, cl in rows
        ]

    def task_log(self) -> list[dict[str, Any]]:
        """Every executed task, in execution order."""
        rows = self.conn.execute(
            "SELECT id, algorithm, function, first_run, n_runs, wall_time, worker, finished "
            "FROM tasks ORDER BY id"
        ).fetchall()
        keys = (
            "id",
            "algorithm",
            "function",
            "first_run",
            "n_runs",
            "wall_time",
            "worker",
            "finished",
        )
        return [dict(zip(keys, r, strict=True)) for r in rows]


# ---------------------------------------------------------------------- helpers
def _connect(path: Path, readonly: bool) -> sqlite3.Connection:
    try:
        if readonly:
            # mode=ro: a report never writes, and works on a store someone made read-only.
            return sqlite3.connect(f"{path.resolve().as_uri()}?mode=ro", uri=True, timeout=30)
        return sqlite3.connect(path, timeout=30)
    except sqlite3.Error as exc:
        raise StoreError(f"cannot open results store {path}: {exc}") from None


def _check_foreign(conn: sqlite3.Connection, path: Path) -> None:
    """Fail clearly on a file that is not SQLite, or SQLite that is not ours."""
    try:
        tables = {
            r[0]
            for r in conn.execute("SELECT name FROM sqlite_master WHERE type = 'table'").fetchall()
        }
    except sqlite3.DatabaseError as exc:
        raise StoreError(
            f"{path} is not a readable SQLite results store ({exc}); the file is corrupt or "
            f"of another kind. Move it away or choose another --out file."
        ) from None
    ours = {"meta", "runs", "tasks"}
    if tables and not ours & tables:
        raise StoreError(
            f"{path} is a SQLite database of something else (tables: "
            f"{', '.join(sorted(tables))}), not a mawdo results store"
        )


class _translate:
    """Turn sqlite3 errors into StoreError messages that name the file and the action."""

    def __init__(self, path: Path, action: str) -> None:
        self.path, self.action = path, action

    def __enter__(self) -> None:
        return None

    def __exit__(self, typ, exc, tb) -> bool:
        if exc is None or not isinstance(exc, sqlite3.Error):
            return False
        msg = str(exc)
        if "readonly" in msg or "read-only" in msg:
            raise StoreError(
                f"cannot {self.action} results store {self.path}: it is read-only ({msg})"
            ) from None
        if isinstance(exc, sqlite3.IntegrityError):
            raise StoreError(
                f"cannot {self.action} results store {self.path}: {msg} (a run "
                f"was computed twice; is another sweep writing to this file?)"
            ) from None
        raise StoreError(f"cannot {self.action} results store {self.path}: {msg}") from None


def _read_meta(conn: sqlite3.Connection, path: Path) -> dict[str, Any] | None:
    try:
        row = conn.execute(
            "SELECT schema_version, plan_hash, plan_json, library_version, created FROM meta"
        ).fetchone()
    except sqlite3.DatabaseError as exc:
        raise StoreError(f"{path} is not a mawdo results store ({exc})") from None
    if row is None:
        return None
    keys = ("schema_version", "plan_hash", "plan_json", "library_version", "created")
    return dict(zip(keys, row, strict=True))


def _write_meta(conn: sqlite3.Connection, path: Path, plan: ExperimentPlan) -> dict[str, Any]:
    meta = {
        "schema_version": SCHEMA_VERSION,
        "plan_hash": plan.plan_hash,
        "plan_json": plan.to_json(),
        "library_version": library_version(),
        "created": _now(),
    }
    with _translate(path, "initialise"), conn:
        conn.execute(
            "INSERT INTO meta (id, schema_version, plan_hash, plan_json, library_version, "
            "created) VALUES (1, ?, ?, ?, ?, ?)",
            tuple(meta.values()),
        )
    return meta


def _mismatch(meta: dict[str, Any], plan: ExperimentPlan) -> str | None:
    """Why a stored meta row does not match ``plan`` and this library, or None."""
    if meta["schema_version"] != SCHEMA_VERSION:
        return f"store schema {meta['schema_version']} (this library writes {SCHEMA_VERSION})"
    if meta["library_version"] != library_version():
        return (
            f"mawdo {meta['library_version']} (this is mawdo {library_version()}; results "
            f"of different versions may differ)"
        )
    if meta["plan_hash"] != plan.plan_hash:
        try:
            old = ExperimentPlan.from_json(meta["plan_json"]).numbers_spec()
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


def _now() -> str:
    return datetime.now(UTC).isoformat(timespec="seconds")


def _json_default(o: Any) -> Any:
    if isinstance(o, np.generic):
        return o.item()
    if isinstance(o, np.ndarray):
        return o.tolist()
    return str(o)
