"""The shared base of every study plan: validation messages, identity (plan hash), JSON round
trip and overrides.

A plan is data: a frozen pydantic model that is validated once, with messages that name the
offending field (``runs: must be >= 1``). Each study kind subclasses :class:`StudyPlanBase`,
declares its fields and says which of them affect stored numbers (:meth:`numbers_spec`); the
hash of that spec ties a results store to its plan.
"""

from __future__ import annotations

import difflib
import hashlib
import json
import tomllib
from collections.abc import Callable, Mapping
from pathlib import Path
from typing import Annotated, Any, ClassVar

from pydantic import BaseModel, ConfigDict, Field, ValidationError

#: A plan's count field: an int >= 1, strictly (a TOML ``runs = 3.5`` or ``true`` is an error,
#: not silently 3 or 1). Shared by the kinds' plans.
PositiveInt = Annotated[int, Field(strict=True, ge=1)]


class PlanError(ValueError):
    """An invalid study plan; the message has one ``field: problem`` line per error."""


class StudyPlanBase(BaseModel):
    """Plan hashing, serialisation and overrides, shared by every study kind.

    Subclasses set the class attribute ``study_kind`` (their registered kind's name), declare a
    field ``kind: Literal[<that name>]`` so the stored JSON names its kind, and implement
    :meth:`numbers_spec`, ``tasks``, ``task_spec``, ``describe`` and ``total_runs``
    (:class:`mawdo.experiments.protocol.Study`).
    """

    model_config = ConfigDict(frozen=True, extra="forbid")

    study_kind: ClassVar[str] = ""
    name: str = "custom"

    # ----------------------------------------------------------------------- construction
    @classmethod
    def from_dict(cls, data: Mapping[str, Any], *, stored: bool = False):
        """Validate ``data`` (e.g. parsed TOML); raise :class:`PlanError` naming each field.

        ``stored=True`` marks a plan read back from a results store: validators then get the
        context ``{"stored": True}`` and must not resolve anything outside the plan (files,
        registries of data), so a crafted store cannot make a report open other files.
        """
        if not isinstance(data, Mapping):
            raise PlanError(f"a plan must be a table of fields, got {type(data).__name__}")
        try:
            return cls.model_validate(dict(data), context={"stored": stored})
        except ValidationError as exc:
            raise PlanError(format_errors(exc, cls)) from None

    @classmethod
    def from_file(cls, path):
        """Load a plan from a TOML file (or JSON, by its ``.json`` suffix).

        The file holds the fields at top level, or under a ``[plan]`` table; a ``preset = "..."``
        key starts from that preset (:meth:`preset`) and the other keys override it. Errors
        are :class:`PlanError` naming the file.
        """
        return plan_from_data(path, read_plan_file(path), cls.preset, cls.from_dict)

    @classmethod
    def preset(cls, name: str):
        """The kind's named plan ``name`` (for ``preset = "..."`` in a plan file); kinds with
        presets override this."""
        raise PlanError(f"preset: {cls.study_kind or 'this'} study has no presets (got {name!r})")

    @classmethod
    def from_json(cls, text: str):
        """The plan written by :meth:`to_json`."""
        return cls.from_dict(json.loads(text))

    def to_json(self) -> str:
        """The full plan (name and batch size included) as JSON, for the store's meta table."""
        return json.dumps(self.model_dump(mode="json"), sort_keys=True)

    def with_overrides(self, **changes: Any):
        """A new, re-validated plan with some fields replaced (``None`` values are ignored)."""
        changes = {k: v for k, v in changes.items() if v is not None}
        if not changes:
            return self
        data = self.model_dump()
        data.update(changes)
        return type(self).from_dict(self._adjust_overrides(data, changes))

    def _adjust_overrides(self, data: dict[str, Any], changes: dict[str, Any]) -> dict[str, Any]:
        """Hook: fix up dependent fields after ``changes`` were applied to ``data``."""
        return data

    # ----------------------------------------------------------------------- identity
    NUMBER_FREE: ClassVar[tuple[str, ...]] = ("name", "batch_size")
    """Fields that never change a stored number (left out of the default numbers spec)."""

    def numbers_spec(self) -> dict[str, Any]:
        """Everything that affects stored numbers, as plain JSON data (default: every field but
        :attr:`NUMBER_FREE`); part of the plan hash."""
        d = self.model_dump(mode="json")
        for k in self.NUMBER_FREE:
            d.pop(k, None)
        return d

    @property
    def plan_hash(self) -> str:
        """SHA-256 of the canonical JSON of :meth:`numbers_spec` (hex)."""
        blob = json.dumps(self.numbers_spec(), sort_keys=True, separators=(",", ":"))
        return hashlib.sha256(blob.encode("utf-8")).hexdigest()


def reject_duplicates(values: tuple, field: str) -> tuple:
    """``values`` unchanged when no entry repeats; else a ``ValueError`` naming the repeat and
    its first place, e.g. ``functions[1]: 'sphere' is listed twice (also functions[0])``."""
    first: dict[Any, int] = {}
    for i, v in enumerate(values):
        if v in first:
            raise ValueError(f"{field}[{i}]: {v!r} is listed twice (also {field}[{first[v]}])")
        first[v] = i
    return values


def plan_from_data(path, data: dict[str, Any], preset: Callable, build: Callable):
    """The plan of a plan file's fields ``data``: ``preset(name)`` with the other fields as
    overrides when ``data`` has a ``preset`` key, else ``build(data)``; a :class:`PlanError`
    names the file ``path``."""
    data = dict(data)
    name = data.pop("preset", None)
    try:
        if name is None:
            return build(data)
        if not isinstance(name, str):
            raise PlanError(f"preset: must be a string, got {name!r}")
        return preset(name).with_overrides(**data)
    except PlanError as exc:
        raise PlanError(f"{path}: {exc}") from None


def read_plan_file(path) -> dict[str, Any]:
    """The fields of a plan file: TOML (JSON by a ``.json`` suffix), at top level or under a
    ``[plan]`` table. Raises :class:`PlanError` naming the file."""
    path = Path(path)
    try:
        text = path.read_text(encoding="utf-8")
    except (OSError, UnicodeDecodeError) as exc:
        why = getattr(exc, "strerror", None) or exc
        raise PlanError(f"cannot read plan file {path}: {why}") from None
    try:
        data = json.loads(text) if path.suffix.lower() == ".json" else tomllib.loads(text)
    except (tomllib.TOMLDecodeError, json.JSONDecodeError) as exc:
        what = "JSON" if path.suffix.lower() == ".json" else "TOML"
        raise PlanError(f"{path}: not valid {what}: {exc}") from None
    if not isinstance(data, dict):
        raise PlanError(f"{path}: a plan must be a table of fields")
    if "plan" in data and isinstance(data["plan"], dict) and len(data) == 1:
        data = data["plan"]
    return dict(data)


def format_errors(exc: ValidationError, model: type[BaseModel]) -> str:
    """One ``field: problem`` line per pydantic error, in the project's wording."""
    errors = exc.errors()
    # A list whose every item failed is also reported "too short" by pydantic; the item
    # errors already say what is wrong.
    failed_items = {e["loc"][0] for e in errors if len(e["loc"]) > 1}
    errors = [e for e in errors if not (e["type"] == "too_short" and e["loc"][0] in failed_items)]
    return "\n".join(_format_one(err, model) for err in errors)


def _loc(loc: tuple) -> str:
    out = ""
    for part in loc:
        if isinstance(part, int):
            out += f"[{part}]"
        else:
            out += f".{part}" if out else str(part)
    return out


def _format_one(err: dict, model: type[BaseModel]) -> str:
    typ, ctx, loc = err["type"], err.get("ctx") or {}, _loc(err["loc"])
    got = err.get("input")
    if typ == "greater_than_equal":
        msg = f"must be >= {ctx['ge']} (got {got!r})"
    elif typ in ("int_type", "int_parsing", "int_from_float"):
        msg = f"must be an integer (got {got!r})"
    elif typ == "bool_type":
        msg = f"must be true or false (got {got!r})"
    elif typ == "string_type":
        msg = f"must be a string (got {got!r})"
    elif typ == "literal_error":
        msg = f"must be one of {ctx['expected']} (got {got!r})"
    elif typ == "too_short":
        msg = "must not be empty: list at least one name"
    elif typ == "missing":
        msg = "is required"
    elif typ == "extra_forbidden":
        fields = list(model.model_fields)
        close = difflib.get_close_matches(str(err["loc"][-1]), fields, n=1)
        hint = f" Did you mean {close[0]!r}?" if close else ""
        msg = f"unknown field.{hint} Plan fields: {', '.join(fields)}"
    elif typ in ("tuple_type", "list_type"):
        msg = f"must be a list of names (got {got!r})"
    elif typ == "dict_type":
        msg = f"must be a table (got {got!r})"
    elif typ == "value_error":
        msg = str(ctx.get("error", err["msg"]))
        # Validators that know a finer location put it in front of their message.
        if not loc or msg.startswith(f"{loc}[") or msg.startswith(f"{loc}."):
            return msg
    else:
        msg = err["msg"]
    return f"{loc}: {msg}" if loc else msg
