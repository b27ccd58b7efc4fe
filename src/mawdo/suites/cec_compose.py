"""Plain, hybrid and composition functions of CEC 2017 / CEC 2022 on a whole population.

A function is a tree of records: :class:`Plain` (one basic function, shifted and rotated),
:class:`Hybrid` (the shuffled point cut into groups, one basic function per group) and
:class:`Composition` (weighted components around their own optima). :func:`evaluate` walks it
for a batch ``X`` of shape ``(n, D)`` exactly as ``cec17_test_func.cpp`` / ``cec22_test_func.cpp``
walk it for one point, including what the C code leaves in its shared ``y`` buffer (read by
Schaffer's F7 inside a hybrid: the first group's coordinates, whichever group it is given).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from mawdo.suites import cec_basic as B
from mawdo.suites import cec_kernels as K


@dataclass(frozen=True)
class Plain:
    """A basic function (its name in :data:`cec_basic.BASIC`, ``"schaffer_f7"`` or
    ``"bi_rastrigin"``), shifted, and rotated unless ``rotated`` is False."""

    name: str
    rotated: bool = True


@dataclass(frozen=True)
class Hybrid:
    """Basic functions of the groups of the shuffled point; ``shares`` are their parts of D
    (the last group takes what the rounded-up others leave)."""

    names: tuple[str, ...]
    shares: tuple[float, ...]

    def sizes(self, dim: int) -> list[int]:
        """Group sizes, as the C code rounds them (``ceil(share * D)``; the last the rest)."""
        head = [math.ceil(g * dim) for g in self.shares[:-1]]
        return [*head, dim - sum(head)]


@dataclass(frozen=True)
class Component:
    """One component of a composition: a function, its ``sigma`` (``delta`` in the C code),
    its bias, and the value scale ``a * f / b`` (``(1, 1)``: none)."""

    function: Plain | Hybrid
    delta: float
    bias: float
    scale: tuple[float, float] = (1.0, 1.0)


@dataclass(frozen=True)
class Composition:
    components: tuple[Component, ...]


def _sr(x, shift, matrix_t, rate, shifted=True, rotated=True):
    """``sr_func``: ``(y, z)`` with ``y`` the shifted, scaled point the C code leaves in its
    buffer (None when it leaves it alone) and ``z`` the function's input."""
    d = (x - shift) * rate if shifted else x * rate
    if rotated:
        return d, K.rotate(d, matrix_t)
    return None, d


def plain(node: Plain, x, shift, matrix_t, shifted=True):
    """Value of a shifted (and rotated) basic function at the rows of ``x``."""
    if node.name == "bi_rastrigin":
        return K.bi_rastrigin(x, shift, matrix_t, shifted, node.rotated)
    if node.name == "schaffer_f7":  # reads the buffer y: the shifted point, never rotated
        y, z = _sr(x, shift, matrix_t, 1.0, shifted, node.rotated)
        return B.schaffer_f7(z if y is None else y)
    _, z = _sr(x, shift, matrix_t, B.RATE.get(node.name, 1.0), shifted, node.rotated)
    return B.BASIC[node.name](z)


def hybrid(node: Hybrid, x, shift, matrix_t, perm):
    """``hf01``..``hf10``: shift and rotate, shuffle by ``perm``, one function per group."""
    _, z = _sr(x, shift, matrix_t, 1.0)
    y = z[:, perm]
    total = np.zeros(x.shape[0])
    start = 0
    for name, size in zip(node.names, node.sizes(x.shape[1]), strict=True):
        part = y[:, start : start + size]
        if name == "schaffer_f7":  # the C code reads y[0..size), not this group
            total = total + B.schaffer_f7(y[:, :size])
        elif name == "bi_rastrigin":
            total = total + K.bi_rastrigin(part, shift, matrix_t, False, False)
        else:
            total = total + B.BASIC[name](part * B.RATE.get(name, 1.0))
        start += size
    return total


def composition(node: Composition, x, data):
    """``cf01``..``cf10``: the components' values weighted by closeness to their optima."""
    fits = np.empty((x.shape[0], len(node.components)))
    for i, c in enumerate(node.components):
        if isinstance(c.function, Hybrid):
            f = hybrid(c.function, x, data.shift[i], data.matrix_t[i], data.shuffle[i])
        else:
            f = plain(c.function, x, data.shift[i], data.matrix_t[i])
        a, b = c.scale
        fits[:, i] = (a * f / b if (a, b) != (1.0, 1.0) else f) + c.bias
    deltas = np.array([c.delta for c in node.components], dtype=float)
    return K.cf_cal(x, data.shift[: len(deltas)], deltas, fits)


def evaluate(node, x, data):
    """Value of the function ``node`` (without its bias) at the rows of ``x`` (n, D)."""
    with np.errstate(all="ignore"):  # as in C: inf and nan where the formula gives them
        if isinstance(node, Composition):
            return composition(node, x, data)
        if isinstance(node, Hybrid):
            return hybrid(node, x, data.shift[0], data.matrix_t[0], data.shuffle[0])
        return plain(node, x, data.shift[0], data.matrix_t[0])
