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
from typing import Annotated, Any, ClassVar, Literal, get_args, get_origin

from pydantic import BaseModel, ConfigDict, Field, ValidationError

from mawdo.util.nesting import NestingError, loads

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
        refuse_bools(cls, data)
        try:
            plan = cls.model_validate(dict(data), context={"stored": stored})
        except ValidationError as exc:
            raise PlanError(format_errors(exc, cls)) from None
        check_size(plan)
        return plan

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
        try:
            data = loads(text, "json", what="plan JSON", needs=PLAN_NEEDS)
        except (NestingError, json.JSONDecodeError) as exc:
            raise PlanError(str(exc)) from None
        return cls.from_dict(data)

    def to_json(self) -> str:
        """The full plan (name and batch size included) as JSON, for the store's meta table."""
        return json.dumps(self.model_dump(mode="json"), sort_keys=True)

    def with_overrides(self, **changes: Any):
        """A new, re-validated plan with some fields replaced (``None`` values are ignored:
        a flag not given); :meth:`with_fields` sets ``None`` too."""
        return self.with_fields(**{k: v for k, v in changes.items() if v is not None})

    def with_fields(self, **changes: Any):
        """A new, re-validated plan with the fields ``changes`` replaced, ``None`` included
        (``final_target=None``: a field whose legal value is None; a field that does not allow
        None is refused with its type)."""
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


MAX_PLAN_RUNS = 1_000_000
"""Most runs one plan may hold. Its task list and the store's keys are built in memory before
the first run (a plan of 10^10 runs sat silent, 10^6 scenes per family held 765 MB before any
run); the largest preset holds 64 800."""


def check_size(plan: Any) -> None:
    """Refuse a plan of more than :data:`MAX_PLAN_RUNS` runs, saying how many it has."""
    total = getattr(plan, "total_runs", None)
    if isinstance(total, int) and total > MAX_PLAN_RUNS:
        raise PlanError(
            f"the plan has {total:,} runs ({plan.describe()}); one plan holds at most "
            f"{MAX_PLAN_RUNS:,}: lower its counts (runs, n, instances ...) or split the study "
            "into several plans"
        )


def _admits_bool(annotation: Any) -> bool:
    """Whether a field's type accepts a bool anywhere in it (``bool``, ``Any``, a literal
    ``True``, or a container or union with one of those)."""
    if annotation is bool or annotation is Any:
        return True
    args = get_args(annotation)
    if get_origin(annotation) is Literal:
        return any(isinstance(a, bool) for a in args)
    if get_origin(annotation) is Annotated:
        return _admits_bool(args[0])
    return any(_admits_bool(a) for a in args if a is not Ellipsis)


def _has_bool(value: Any) -> bool:
    if isinstance(value, bool):
        return True
    if isinstance(value, dict):
        return any(_has_bool(v) for v in value.values())
    if isinstance(value, list | tuple):
        return any(_has_bool(v) for v in value)
    return False


def refuse_bools(model: type[BaseModel], data: Mapping[str, Any]) -> None:
    """Refuse ``true``/``false`` given for a field that holds numbers or names: pydantic's lax
    mode reads ``true`` as 1 (``n = true`` ran one scene); a bool is no number here."""
    bad = [
        f"{key}: must be {_kind_of(field.annotation)}, not true/false (got {value!r})"
        for key, value in data.items()
        if (field := model.model_fields.get(key)) is not None
        and not _admits_bool(field.annotation)
        and _has_bool(value)
    ]
    if bad:
        raise PlanError("\n".join(bad))


def _leaves(annotation: Any) -> set[Any]:
    if get_origin(annotation) is Annotated:
        return _leaves(get_args(annotation)[0])
    args = [a for a in get_args(annotation) if a is not Ellipsis]
    if not args or get_origin(annotation) is Literal:
        return {annotation}
    return set().union(*(_leaves(a) for a in args))


def _kind_of(annotation: Any) -> str:
    """``"an integer"``, ``"a number"`` ... : what a field holds, for a message."""
    leaves = _leaves(annotation) - {type(None)}
    many = get_origin(annotation) in (tuple, list) or any(
        get_origin(a) in (tuple, list) for a in get_args(annotation)
    )
    words = {frozenset({int}): "integers", frozenset({float}): "numbers", frozenset({str}): "names"}
    word = words.get(frozenset(leaves), "names or numbers")
    if many:
        return f"a list of {word}"
    one = {"integers": "an integer", "numbers": "a number", "names": "a name"}
    return one.get(word, "a name or a number")


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
        return preset(name).with_fields(**data)
    except PlanError as exc:
        raise PlanError(f"{path}: {exc}") from None


PLAN_NEEDS = "a plan needs 3 levels at most (e.g. options -> algorithm -> option)"


def read_plan_file(path) -> dict[str, Any]:
    """The fields of a plan file: TOML (JSON by a ``.json`` suffix), at top level or under a
    ``[plan]`` table. A UTF-8 byte order mark (which some editors write) is skipped. Raises
    :class:`PlanError` naming the file, also for nesting deeper than
    :data:`mawdo.util.nesting.MAX_NESTING` (checked before parsing)."""
    path = Path(path)
    try:
        text = path.read_text(encoding="utf-8-sig")
    except (OSError, UnicodeDecodeError) as exc:
        why = getattr(exc, "strerror", None) or exc
        raise PlanError(f"cannot read plan file {path}: {why}") from None
    fmt = "json" if path.suffix.lower() == ".json" else "toml"
    try:
        data = loads(text, fmt, what=str(path), needs=PLAN_NEEDS)
    except NestingError as exc:
        raise PlanError(str(exc)) from None
    except (tomllib.TOMLDecodeError, json.JSONDecodeError) as exc:
        raise PlanError(f"{path}: not valid {fmt.upper()}: {exc}") from None
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
