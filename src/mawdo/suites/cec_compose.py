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

INF = 1.0e99


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


def _sr(x, shift, matrix, rate, shifted=True, rotated=True):
    """``sr_func``: ``(y, z)`` with ``y`` the shifted, scaled point the C code leaves in its
    buffer (None when it leaves it alone) and ``z`` the function's input."""
    d = (x - shift) * rate if shifted else x * rate
    if rotated:
        return d, B.rotate(d, matrix)
    return None, d


def plain(node: Plain, x, shift, matrix, shifted=True):
    """Value of a shifted (and rotated) basic function at the rows of ``x``."""
    if node.name == "bi_rastrigin":
        return B.bi_rastrigin(x, shift, matrix, shifted, node.rotated)
    if node.name == "schaffer_f7":  # reads the buffer y: the shifted point, never rotated
        y, z = _sr(x, shift, matrix, 1.0, shifted, node.rotated)
        return B.schaffer_f7(z if y is None else y)
    _, z = _sr(x, shift, matrix, B.RATE.get(node.name, 1.0), shifted, node.rotated)
    return B.BASIC[node.name](z)


def hybrid(node: Hybrid, x, shift, matrix, perm):
    """``hf01``..``hf10``: shift and rotate, shuffle by ``perm``, one function per group."""
    _, z = _sr(x, shift, matrix, 1.0)
    y = z[:, perm]
    total = np.zeros(x.shape[0])
    start = 0
    for name, size in zip(node.names, node.sizes(x.shape[1]), strict=True):
        part = y[:, start : start + size]
        if name == "schaffer_f7":  # the C code reads y[0..size), not this group
            total = total + B.schaffer_f7(y[:, :size])
        elif name == "bi_rastrigin":
            total = total + B.bi_rastrigin(part, shift, matrix, False, False)
        else:
            total = total + B.BASIC[name](part * B.RATE.get(name, 1.0))
        start += size
    return total


def composition(node: Composition, x, data):
    """``cf01``..``cf10``: the components' values weighted by closeness to their optima."""
    n, dim = x.shape
    fits, weights = [], []
    for i, c in enumerate(node.components):
        if isinstance(c.function, Hybrid):
            f = hybrid(c.function, x, data.shift[i], data.matrix[i], data.shuffle[i])
        else:
            f = plain(c.function, x, data.shift[i], data.matrix[i])
        a, b = c.scale
        fits.append(a * f / b + c.bias if (a, b) != (1.0, 1.0) else f + c.bias)
        d2 = B.seqsum((x - data.shift[i]) ** 2)
        safe = np.where(d2 != 0, d2, 1.0)
        w = np.power(1.0 / safe, 0.5) * np.exp(-safe / 2.0 / dim / c.delta**2)
        weights.append(np.where(d2 != 0, w, INF))
    w = np.stack(weights, axis=1)
    w_sum = B.seqsum(w)
    flat = np.max(w, axis=1) == 0  # every weight underflowed: equal weights
    w = np.where(flat[:, None], 1.0, w)
    w_sum = np.where(flat, len(fits), w_sum)
    return B.seqsum(w / w_sum[:, None] * np.stack(fits, axis=1))


def evaluate(node, x, data):
    """Value of the function ``node`` (without its bias) at the rows of ``x`` (n, D)."""
    with np.errstate(all="ignore"):  # as in C: inf and nan where the formula gives them
        if isinstance(node, Composition):
            return composition(node, x, data)
        if isinstance(node, Hybrid):
            return hybrid(node, x, data.shift[0], data.matrix[0], data.shuffle[0])
        return plain(node, x, data.shift[0], data.matrix[0])
