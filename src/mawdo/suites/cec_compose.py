"""Plain, hybrid and composition functions of CEC 2017 / CEC 2022 on a whole population.

A function is a tree of records: :class:`Plain` (one basic function, shifted and rotated),
:class:`Hybrid` (the shuffled point cut into groups, one basic function per group) and
:class:`Composition` (weighted components around their own optima). :func:`compile_function`
flattens a tree and its official data into a :class:`Program` of arrays, which one compiled
loop (:func:`run`) walks for a batch ``X`` of shape ``(n, D)`` exactly as
``cec17_test_func.cpp`` / ``cec22_test_func.cpp`` walk it for one point, including what the C
code leaves in its shared ``y`` buffer (read by Schaffer's F7: the shifted, unrotated point,
and inside a hybrid the first group's coordinates, whichever group it is given).

One compiled call per batch, with the points innermost, instead of one NumPy or Numba call per
component and step: 1.7 times less time per point at D = 30 and batch 100, 2 times at D = 10,
the same values bit for bit (benchmarks/log/optimizers.md).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import NamedTuple

import numpy as np

from mawdo.suites import cec_basic as B
from mawdo.suites import cec_kernels as K
from mawdo.suites.cec_basic import kernel

BLOCK = 128
"""Points per block: the block's transposed buffers stay in the first-level cache."""
PLAIN, BI_RASTRIGIN, HYBRID = 0, 1, 2


@dataclass(frozen=True)
class Plain:
    """A basic function (its name in :data:`cec_basic.NAMES`), shifted, and rotated unless
    ``rotated`` is False."""

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
    """Components weighted by their closeness to their own optima (``cf_cal``)."""

    components: tuple[Component, ...]


class Program(NamedTuple):
    """A function tree in arrays, one row per component (``c``; 1 unless a composition), one
    column per group (``g``; 1 unless a hybrid).

    ``kind`` (c,): PLAIN, BI_RASTRIGIN or HYBRID; ``rotated`` (c,; never a plain Schaffer's
    F7); ``groups`` (c,): groups in use; ``codes``, ``sizes``, ``rates`` (c, g): the groups'
    basic functions (index in :data:`cec_basic.NAMES`), sizes and scalings (a plain
    function's before the rotation, as ``sr_func``; a hybrid group's after it); ``consts``
    (c, g, w): their :func:`cec_basic.constants`; ``weight`` (c, 4): each component's delta,
    bias, ``a``, ``b``; ``composite``: whether to weigh components (``cf_cal``); ``shift``
    (c, D), ``matrix`` (c, D, D), ``perm`` (c, D): the official data (perm 0-based; zeros if
    unused).
    """

    kind: np.ndarray
    rotated: np.ndarray
    groups: np.ndarray
    codes: np.ndarray
    sizes: np.ndarray
    rates: np.ndarray
    consts: np.ndarray
    weight: np.ndarray
    composite: bool
    shift: np.ndarray
    matrix: np.ndarray
    perm: np.ndarray


def _parts(fn: Plain | Hybrid, dim: int) -> tuple[int, list[tuple[str, int]]]:
    if isinstance(fn, Hybrid):
        return HYBRID, list(zip(fn.names, fn.sizes(dim), strict=True))
    return (BI_RASTRIGIN if fn.name == "bi_rastrigin" else PLAIN), [(fn.name, dim)]


def compile_function(node, data) -> Program:
    """The :class:`Program` of function ``node`` on its official ``data``
    (:class:`~mawdo.suites.cec_data.Data`)."""
    parts = node.components if isinstance(node, Composition) else (Component(node, 0.0, 0.0),)
    c, dim = len(parts), data.shift.shape[1]
    g = max(len(_parts(p.function, dim)[1]) for p in parts)
    kind, rotated, groups = (np.zeros(c, dtype=np.int64) for _ in range(3))
    codes, sizes = np.zeros((c, g), dtype=np.int64), np.zeros((c, g), dtype=np.int64)
    rates, weight = np.ones((c, g)), np.zeros((c, 4))
    consts = np.zeros((c, g, max(B.WIDTH, dim)))
    perm = np.zeros((c, dim), dtype=np.int64)
    for i, part in enumerate(parts):
        kind[i], groups_i = _parts(part.function, dim)
        rotated[i] = getattr(part.function, "rotated", True) and not (
            kind[i] == PLAIN and part.function.name == "schaffer_f7"
        )  # Schaffer's F7 reads the C code's unrotated buffer y, rotated or not
        groups[i] = len(groups_i)
        for k, (name, size) in enumerate(groups_i):
            codes[i, k], sizes[i, k] = B.CODE[name], size
            rates[i, k] = B.RATE.get(name, 1.0)
            t = B.constants(codes[i, k], size)
            consts[i, k, : t.size] = t
        weight[i] = (part.delta, part.bias, *part.scale)
        if kind[i] == HYBRID:
            perm[i] = data.shuffle[i]
    return Program(
        kind, rotated, groups, codes, sizes, rates, consts, weight, isinstance(node, Composition),
        np.array(data.shift[:c]), np.array(data.matrix[:c]), perm,
    )  # fmt: skip


@kernel
def _bi_rastrigin(xt, m, rotated, t, shift, matrix, yt, zt, out):
    """``bi_rastrigin_func`` (shifting by itself) at the block's ``m`` points."""
    d = xt.shape[0]
    K.shift_t(xt, m, shift, 1.0, yt)
    K.bi_rastrigin(yt, d, m, shift, t, zt, out)
    if rotated:
        K.rotate_t(zt, m, matrix, yt)
        K.bi_rastrigin_tail(yt, d, m, out)
    else:
        K.bi_rastrigin_tail(zt, d, m, out)


@kernel
def _points(xt, m, p, i, yt, zt):
    """The block's points as component ``i`` reads them: shifted, scaled (plain: by its rate
    before the rotation, as ``sr_func``), rotated unless the program says not, and for a
    hybrid shuffled. Returns the buffer holding them."""
    kind = p.kind[i]
    K.shift_t(xt, m, p.shift[i], p.rates[i, 0] if kind == PLAIN else 1.0, yt)
    if kind == PLAIN and not p.rotated[i]:
        return yt
    K.rotate_t(yt, m, p.matrix[i], zt)
    if kind == PLAIN:
        return zt
    perm = p.perm[i]
    for k in range(xt.shape[0]):  # the shuffled points, into the free buffer yt
        src, dst = zt[perm[k]], yt[k]
        for r in range(m):
            dst[r] = src[r]
    return yt


@kernel
def _component(xt, m, p, i, yt, zt, part, val, out):
    """Component ``i`` of program ``p`` at the block's ``m`` points: a plain function, or
    ``hf01``..``hf10`` summing its groups' functions (scaled and biased when ``p`` is a
    composition)."""
    if p.kind[i] == BI_RASTRIGIN:
        _bi_rastrigin(xt, m, p.rotated[i], p.consts[i, 0], p.shift[i], p.matrix[i], yt, zt, out)
    else:
        y = _points(xt, m, p, i, yt, zt)
        hybrid = p.kind[i] == HYBRID
        if hybrid:
            out[:m] = 0.0
        start = 0
        for g in range(p.groups[i]):
            size, code, t = p.sizes[i, g], p.codes[i, g], p.consts[i, g]
            z = y  # Schaffer's F7 in a hybrid reads y[0..size), whichever its group, as in C
            if hybrid and code != B.SCHAFFER_F7:  # the group, scaled by its rate
                rate, z = p.rates[i, g], part
                for k in range(size):
                    src, dst = y[start + k], part[k]
                    for r in range(m):
                        dst[r] = src[r] * rate
            if code == B.BI_RASTRIGIN:  # in a hybrid: unshifted, the mirror's signs from o
                K.bi_rastrigin(z, size, m, p.shift[i], t, zt, val)
                K.bi_rastrigin_tail(zt, size, m, val)
            else:
                K.basic(code, z, size, m, t, val if hybrid else out)
            if hybrid:
                for r in range(m):
                    out[r] = out[r] + val[r]
            start += size
    if p.composite:
        bias, a, b = p.weight[i, 1], p.weight[i, 2], p.weight[i, 3]
        for r in range(m):
            out[r] = (a * out[r] / b if (a != 1.0 or b != 1.0) else out[r]) + bias


def run(x: np.ndarray, program: Program, bias: float) -> np.ndarray:
    """Value of ``program`` plus ``bias`` (its official optimum value, 0 for none) at the rows
    of ``x`` (n, D), C-contiguous float64; inf and nan where the C code's formulas give them."""
    return _run(x, bias, *program)  # the fields one by one: Numba types arrays fastest


@kernel
def _run(x, bias, *fields):
    p = Program(*fields)
    n, d = x.shape
    c = p.kind.size
    f = np.empty(n)
    buffers = np.empty((4, d, BLOCK))  # the block transposed, and three work buffers
    xt, yt, zt, part = buffers[0], buffers[1], buffers[2], buffers[3]
    fits, w, val = np.empty((c, BLOCK)), np.empty((c, BLOCK)), np.empty(BLOCK)
    deltas = p.weight[:, 0].copy()
    for r0 in range(0, n, BLOCK):
        m = min(BLOCK, n - r0)
        K.transpose(x, r0, m, xt)
        for i in range(c):
            _component(xt, m, p, i, yt, zt, part, val, fits[i])
        if p.composite:
            K.cf_cal(xt, m, p.shift, deltas, fits, w, val)
        for r in range(m):
            f[r0 + r] = (val[r] if p.composite else fits[0, r]) + bias
    return f


def evaluate(node, x, data, bias: float = 0.0) -> np.ndarray:
    """Value of the function ``node`` plus ``bias`` at the rows of ``x`` (n, D), on its
    official ``data``; inf and nan where the C code's formulas give them."""
    return run(np.ascontiguousarray(x, dtype=np.float64), compile_function(node, data), bias)
