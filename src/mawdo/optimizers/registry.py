"""The algorithm registry: names -> (implementation, preset options, reference).

Variants are registered configurations of one implementation, not copied classes; the CLI,
the experiment plans and the contract test suite all iterate over ``OPTIMIZERS``.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

from mawdo.optimizers.base import Optimizer
from mawdo.registry import Registry


@dataclass(frozen=True)
class AlgorithmSpec:
    """A registered algorithm.

    Attributes
    ----------
    name : str
        Registry name (lower case).
    cls : type
        The :class:`~mawdo.optimizers.base.Optimizer` subclass that implements it.
    preset : dict
        Options fixed by this entry (on top of the class defaults); a user may still override them.
    reference : str
        The publication (and reference code) it follows.
    description : str
        One line for ``mawdo list``.
    reconstructed : bool
        True when no published text was available and the algorithm is our reconstruction.
    label : str
        Display name in tables ("MAWDO-1", "MEWDO (reconstructed)").
    """

    name: str
    cls: type
    preset: dict[str, Any] = field(default_factory=dict)
    reference: str = ""
    description: str = ""
    reconstructed: bool = False
    label: str = ""

    @property
    def display(self) -> str:
        base = self.label or self.name.upper()
        return f"{base} (reconstructed)" if self.reconstructed else base

    def metadata(self) -> dict[str, Any]:
        return {
            "name": self.name,
            "label": self.display,
            "reference": self.reference,
            "reconstructed": self.reconstructed,
        }


OPTIMIZERS: Registry[AlgorithmSpec] = Registry("algorithm")


def register(spec: AlgorithmSpec) -> AlgorithmSpec:
    _PARAMS.clear()  # a name registered anew may bring another class or preset
    return OPTIMIZERS.register(spec.name, spec)


def unregister(name: str) -> AlgorithmSpec:
    """Remove a registered algorithm (a throw-away entry of a test) and return its spec."""
    _PARAMS.clear()
    return OPTIMIZERS.unregister(name)


def make_optimizer(algorithm: str | Optimizer, **options) -> Optimizer:
    """Instantiate a registered algorithm with its preset and the given options.

    Parameters
    ----------
    algorithm : str or Optimizer
        A registered name (see ``mawdo list``) or an optimizer instance (returned as is when no
        options are given).
    **options
        Coefficients of the algorithm (``pop_size``, ``groups``, ...); unknown names raise
        ``ValueError`` listing the valid ones. Each option must satisfy the constraint its
        ``Params`` field declares (:func:`mawdo.optimizers.base.option`): a finite real number
        in its range, an integer, a bool, one of its words; NaN, inf and strings for numbers
        are refused.

    Raises
    ------
    ValueError
        An unknown option, or a value out of its range (NaN and inf included).
    mawdo.util.validate.ArgumentTypeError
        A value of the wrong type (also a ``ValueError``).
    """
    # Building the Params checks every option (Params.__post_init__ -> check_options).
    if isinstance(algorithm, Optimizer):
        if options:
            algorithm = type(algorithm)(algorithm.params, name=algorithm.name, **options)
        return algorithm
    spec = OPTIMIZERS[algorithm]
    key = _params_key(spec.name, options)
    params = _PARAMS.get(key) if key is not None else None
    if params is None:
        opt = spec.cls(name=spec.name, **{**spec.preset, **options})
        if key is not None and len(_PARAMS) < _PARAMS_MAX:
            _PARAMS[key] = opt.params
    else:  # the same name and options were checked before: their (frozen) Params are valid
        opt = spec.cls(params, name=spec.name)
    opt.metadata = spec.metadata()
    return opt


# Validated Params per (algorithm, options): a receding-horizon planner builds the same
# optimizer every replan, and the checks cost ~0.1 ms each time.
_PARAMS: dict = {}
_PARAMS_MAX = 1024
_PLAIN = (int, float, str, bool)


def _params_key(name: str, options: dict):
    """A cache key for plain option values, typed and by ``repr`` (so ``True`` is not ``1``
    and ``-0.0`` is not ``0.0``); None when a value is anything else."""
    items = []
    for k, v in options.items():
        if type(v) is tuple:
            if not all(type(x) in _PLAIN for x in v):
                return None
        elif type(v) not in _PLAIN:
            return None
        items.append((k, type(v).__name__, repr(v)))
    return name, tuple(sorted(items))
