"""Typed rows: what one stored run of a study kind holds, and how each field goes to SQLite.

Every study kind declares its row as a frozen dataclass deriving from :class:`RunRow`; each
field beyond the common ones is declared with :func:`column`, which names its storage:

============  ==============================  ==========================================
storage       Python value                    SQLite
============  ==============================  ==========================================
``real``      float or None                   REAL
``int``       int or None                     INTEGER
``text``      str or None                     TEXT
``json``      dict / list (or None)           TEXT (canonical JSON)
``blob``      bytes or None                   BLOB
``f64``       1-D float array (or None)       BLOB, little-endian float64
``i64``       1-D integer array (or None)     BLOB, little-endian int64
============  ==============================  ==========================================

The store creates one column per field, so rows of different kinds never share a field: a
benchmark row has ``fun`` and ``nit``, a planning row has ``metrics`` and ``route``.
"""

from __future__ import annotations

import dataclasses
import json
from dataclasses import dataclass
from typing import Any

import numpy as np

from mawdo.util.nesting import NestingError, loads

STORAGE_SQL = {
    "real": "REAL",
    "int": "INTEGER",
    "text": "TEXT",
    "json": "TEXT",
    "blob": "BLOB",
    "f64": "BLOB",
    "i64": "BLOB",
}


class RowError(ValueError):
    """A row does not fit its kind's schema, or a stored value is damaged."""


def column(storage: str, default: Any = None, *, required: bool = False) -> Any:
    """Declare a row field stored as ``storage`` (a key of :data:`STORAGE_SQL`); ``required``:
    every finished run (no ``error_text``) has a value in it, so a NULL there is damage."""
    if storage not in STORAGE_SQL:
        raise ValueError(f"storage {storage!r} is not one of {', '.join(STORAGE_SQL)}")
    return dataclasses.field(default=default, metadata={"storage": storage, "required": required})


@dataclass(frozen=True)
class RunRow:
    """The fields every stored run has.

    Attributes
    ----------
    run : int
        Run index within its (algorithm, problem), ``0 .. runs - 1``.
    wall_time : float or None
        Seconds spent on the run (a batch's share for vectorised batches).
    error_text : str or None
        The exception of a failed run; None for a run that finished.
    """

    run: int = column("int")
    wall_time: float | None = column("real")
    error_text: str | None = column("text")

    @property
    def failed(self) -> bool:
        return self.error_text is not None


def schema(row_type: type[RunRow]) -> tuple[tuple[str, str], ...]:
    """``(field name, storage)`` of every field of ``row_type``, in declaration order."""
    out = []
    for f in dataclasses.fields(row_type):
        storage = f.metadata.get("storage")
        if storage is None:
            raise RowError(f"{row_type.__name__}.{f.name} is not declared with column(storage)")
        out.append((f.name, storage))
    return tuple(out)


def required_fields(row_type: type[RunRow]) -> frozenset[str]:
    """The fields of ``row_type`` that every finished run has (declared ``required``)."""
    return frozenset(f.name for f in dataclasses.fields(row_type) if f.metadata.get("required"))


#: Python types SQLite gives back for each storage (None aside).
_STORED_TYPES = {
    "real": (float, int),
    "int": (int,),
    "text": (str,),
    "json": (str,),
    "blob": (bytes,),
    "f64": (bytes,),
    "i64": (bytes,),
}


def stored_value_problem(value: Any, storage: str) -> str:
    """What is wrong with a value SQLite gave back for a column of ``storage`` ("" if nothing):
    SQLite keeps any value in any column, so a hand-edited store may hold text in a number's
    column."""
    if value is None or isinstance(value, _STORED_TYPES[storage]):
        return ""
    shown = repr(value) if len(repr(value)) <= 40 else repr(value)[:37] + "..."
    return f"holds {shown} ({type(value).__name__}), not a value of a {storage} column"


def encode_f64(a) -> bytes:
    """Array -> little-endian float64 bytes (explicit byte order: files move between hosts)."""
    return np.ascontiguousarray(a, dtype="<f8").tobytes()


def encode_i64(a) -> bytes:
    return np.ascontiguousarray(a, dtype="<i8").tobytes()


def decode(blob: bytes | None, dtype: str, n: int | None = None) -> np.ndarray:
    """Bytes -> native-order writable array; ``n`` checks the expected length."""
    if blob is None:
        return np.empty(0, dtype=dtype[1:])
    if len(blob) % 8:
        raise RowError(f"stored array has {len(blob)} bytes, not a whole number of 8-byte values")
    arr = np.frombuffer(blob, dtype=dtype)
    if n is not None and arr.size != n:
        raise RowError(f"stored array has {arr.size} entries, expected {n}: the store is damaged")
    return arr.astype(dtype[1:])


def json_default(o: Any) -> Any:
    if isinstance(o, np.generic):
        return o.item()
    if isinstance(o, np.ndarray):
        return o.tolist()
    return str(o)


def to_sql(value: Any, storage: str) -> Any:
    """One field value -> the value SQLite stores."""
    if value is None:
        return None
    if storage == "json":
        return json.dumps(value, sort_keys=True, default=json_default)
    if storage == "f64":
        return encode_f64(value)
    if storage == "i64":
        return encode_i64(value)
    if storage == "int":
        return int(value)
    if storage == "real":
        return float(value)
    return value


def from_sql(value: Any, storage: str) -> Any:
    """A stored value -> the field value (arrays decoded, JSON parsed)."""
    if storage == "f64":
        return decode(value, "<f8")
    if storage == "i64":
        return decode(value, "<i8")
    if value is None:
        return None
    if storage == "json":
        try:
            return loads(value, "json", what="stored JSON")
        except (json.JSONDecodeError, NestingError) as exc:
            raise RowError(f"stored JSON cannot be read: {exc}") from None
    return value


def check_row(row: Any, row_type: type[RunRow]) -> None:
    """Refuse a row of another type: a kind stores only its own rows."""
    if type(row) is not row_type:
        raise RowError(
            f"a {row_type.__name__} was expected, got {type(row).__name__}: each study kind "
            f"stores only its own row type"
        )
