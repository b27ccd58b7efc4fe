"""The function registry: canonical names, paper-id aliases and :func:`get_function`
(docs/functions.md#f-table).

``FUNCTIONS`` maps canonical names (``"rastrigin"``) to the default records (paper bounds and
dimensions). The paper ids ``"F1"`` .. ``"F16"`` are accepted as case-insensitive aliases for
lookups but are not iterated, so ``list(FUNCTIONS)`` shows each function once.
"""

from __future__ import annotations

from mawdo.registry import Registry, UnknownNameError, unknown_name_message

from .base import BenchmarkFunction
from .catalog import alternate_functions, paper_suite
from .shift import shifted as _shift

PRESETS: dict[str, dict[str, tuple[float, float]]] = {
    "paper": {},
    # docs/functions.md#f-preset table, "decision" column: the customary boxes of F2 and F7.
    "standard": {"schwefel_2_22": (-10.0, 10.0), "rastrigin": (-5.12, 5.12)},
}
"""Bound presets: ``paper`` keeps Table 2's boxes; ``standard`` overrides the named functions."""


class FunctionRegistry(Registry[BenchmarkFunction]):
    """A :class:`~mawdo.registry.Registry` whose aliases are the paper ids (F1..F16).

    Aliases are looked up case-insensitively like names but are not part of iteration, ``len``
    or the list of known names in error messages.
    """

    def canonical(self, name: str) -> str:
        """The canonical registered name for ``name`` or an alias of it."""
        return self[name].name

    def __getitem__(self, name: str) -> BenchmarkFunction:
        try:
            return super().__getitem__(name)
        except UnknownNameError:
            message = unknown_name_message(self.kind, name, self._items)
            raise UnknownNameError(
                f"{message} Paper ids F1..F16 are accepted as aliases."
            ) from None


FUNCTIONS = FunctionRegistry("function")
"""Every benchmark function by canonical name; ``FUNCTIONS["F7"]`` also works."""

_paper = paper_suite()
_alternates = alternate_functions()
for _f in (*_paper, *_alternates):
    FUNCTIONS.register(_f.name, _f)
for _f in _paper:
    FUNCTIONS.add_alias(_f.paper_id, _f.name)

PAPER_SUITE: tuple[str, ...] = tuple(f.name for f in _paper)
"""Canonical names of F1..F16, in paper order."""
ALTERNATES: tuple[str, ...] = tuple(f.name for f in _alternates)
"""Canonical names of the literal readings and forensic alternates
(docs/functions.md#f-decisions)."""
del _f, _paper, _alternates


def get_function(
    name: str,
    *,
    dim: int | None = None,
    preset: str = "paper",
    shifted: bool = False,
    shift_seed: int = 0,
) -> BenchmarkFunction:
    """Look up a benchmark function and build the requested variant.

    Parameters
    ----------
    name : str
        Canonical name (``"rastrigin"``) or paper id (``"F7"``), case-insensitive.
    dim : int, optional
        Dimension for a scalable function (default: the paper's, 30). A fixed-dimension function
        accepts only its own dimension.
    preset : {"paper", "standard"}, default "paper"
        Bounds preset: ``"standard"`` uses [-10, 10] for F2 and [-5.12, 5.12] for F7
        (docs/functions.md#f-preset).
    shifted : bool, default False
        Move the optimum to a random point in the middle 80% of the box (see :func:`shifted`).
    shift_seed : int, default 0
        Seed of the shift (non-negative int); ignored unless ``shifted``.

    Returns
    -------
    BenchmarkFunction
        A new record (or the registered one when nothing changes).

    Raises
    ------
    UnknownNameError
        For an unknown name (a ``KeyError`` and ``ValueError``); the message suggests close names.
    ValueError
        For an unknown preset, a ``dim`` a function cannot take, or a bad shift seed.
    """
    f = FUNCTIONS[name]
    if preset not in PRESETS:
        raise ValueError(f"unknown preset {preset!r}; choose one of {', '.join(PRESETS)}")
    if dim is not None:
        if isinstance(dim, bool) or not isinstance(dim, int):
            raise TypeError(f"dim must be an int or None, got {type(dim).__name__}")
        if not f.scalable and dim != f.dim:
            raise ValueError(f"{f.name} has a fixed dimension {f.dim}; dim={dim} is not allowed")
        if dim < max(1, f.min_dim):
            raise ValueError(f"{f.name} needs dim >= {max(1, f.min_dim)}, got dim={dim}")
        f = f.with_dim(dim)
    if f.name in PRESETS[preset]:
        lo, hi = PRESETS[preset][f.name]
        f = f.with_bounds(lo, hi)
    if shifted:
        f = _shift(f, shift_seed)
    return f
