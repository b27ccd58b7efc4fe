"""Elementwise ``tan``, ``arctan``, ``exp``, ``expm1``, ``log``, ``sin``, ``cos`` and ``power``
that give the same bits on every x86-64 processor: the C library's scalar routines, called
from a compiled loop.

Why not NumPy's: NumPy chooses a SIMD loop for these float64 functions by the processor it
runs on. On a processor with AVX-512 several of them come from Intel's SVML (within 4 ulp of
the true value), elsewhere from the C library, so the same call returns different last bits
on different machines. One changed bit in one draw or one fitness value sends a stochastic
optimizer down another trajectory, and a seeded run then gives other numbers on another
machine (it happened to the committed CEC 2022 stores: their SHADE-family rows, computed on
one machine, could not be computed again on another). The CEC kernels and the WDO kernels
already call the C library from Numba and reproduce across machines; the optimizers and the
paper's functions use these.

On a processor without AVX-512 NumPy's loops and these agree bit for bit (measured on 300 000
points per function; the tests check these against Python's ``math``, the C library's), so no
result computed there changes. The C library must be the same too: glibc picks its
own variant by processor (with or without FMA), and every x86-64 processor of the last decade
gets the FMA one. Where Numba is set up to vectorise with SVML (Intel's ``icc_rt`` installed),
it does so here as in every other kernel, and results differ from machines without it.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

__all__ = ["arctan", "cos", "exp", "expm1", "log", "power", "sin", "tan"]


_OPS = ("tan", "arctan", "exp", "expm1", "log", "sin", "cos")


@njit(cache=True, nogil=True)
def _unary(x, out, op):  # pragma: no cover - compiled
    # one kernel for all seven (one cache entry); LLVM unswitches the loop on ``op``
    for i in range(x.size):
        v = x[i]
        if op == 0:
            out[i] = math.tan(v)
        elif op == 1:
            out[i] = math.atan(v)
        elif op == 2:
            out[i] = math.exp(v)
        elif op == 3:
            out[i] = math.expm1(v)
        elif op == 4:
            out[i] = math.log(v)
        elif op == 5:
            out[i] = math.sin(v)
        else:
            out[i] = math.cos(v)


def _elementwise(name: str):
    op = _OPS.index(name)

    def apply(x):
        x = np.asarray(x, dtype=np.float64)
        flat = np.ascontiguousarray(x).reshape(-1)
        out = np.empty_like(flat)
        _unary(flat, out, op)
        return out.reshape(x.shape) if x.ndim else out[0]

    apply.__name__ = apply.__qualname__ = name
    apply.__doc__ = (
        f"NumPy's ``{name}`` of every element of ``x`` (float64, any shape), by the C "
        "library's scalar routine. Returns an array of ``x``'s shape (a float for a scalar)."
    )
    return apply


tan = _elementwise("tan")
arctan = _elementwise("arctan")
exp = _elementwise("exp")
expm1 = _elementwise("expm1")
log = _elementwise("log")
sin = _elementwise("sin")
cos = _elementwise("cos")


@njit(cache=True, nogil=True)
def _pow(a, b, out):  # pragma: no cover - compiled
    for i in range(a.size):
        out[i] = a[i] ** b[i]


def _flat(x: np.ndarray, shape: tuple) -> np.ndarray:
    """``x`` in ``shape`` as a flat, C-contiguous, writeable array: itself when it already is
    one, else a copy (a broadcast view would reach the kernel with NumPy's warn-on-write flag,
    which Numba's typing reports as a FutureWarning)."""
    if x.shape == shape and x.flags.c_contiguous and x.flags.writeable:
        return x.reshape(-1)
    return np.array(np.broadcast_to(x, shape), dtype=np.float64, order="C").reshape(-1)


def power(a, b) -> np.ndarray | float:
    """``a ** b`` elementwise with NumPy broadcasting, by the C library's ``pow``.

    Parameters
    ----------
    a, b : array_like
        Bases and exponents (float64 after conversion; any shapes that broadcast).

    Returns
    -------
    numpy.ndarray or float
        The powers, in the broadcast shape (a float when both inputs are scalars).
    """
    a, b = np.asarray(a, dtype=np.float64), np.asarray(b, dtype=np.float64)
    shape = np.broadcast_shapes(a.shape, b.shape)
    a, b = _flat(a, shape), _flat(b, shape)
    out = np.empty_like(a)
    _pow(a, b, out)
    return out.reshape(shape) if shape else out[0]
