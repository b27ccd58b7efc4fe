"""mawdo.jit.inline: Numba's IR inlining without the copies of a fresh callee IR changes nothing
that is compiled (the same machine code, names aside), and only while asked."""

from __future__ import annotations

import copy
import re

import numpy as np
import pytest
from numba import njit
from numba.core import inline_closurecall as ic
from numba.core import ir

from mawdo.jit.inline import fresh_ir_inlining


@njit(inline="always")
def _inner(a, i):
    s = 0.0
    for k in range(i):
        if a[k] > 0:
            s += a[k]
        else:
            s -= 0.5 * a[k]
    return s


@njit(inline="always")
def _mid(a, n):
    t = _inner(a, n)  # inlined at two sites, one level down
    u = _inner(a, n // 2)
    return t * 2.0 + u


def _outer(a):
    acc = 0.0
    for j in range(a.shape[0]):
        acc += _mid(a, j)
    return acc


def _asm(disp) -> str:
    """Machine code of a dispatcher's one signature, with the dispatcher's own version tag
    (``B2v7``, one per compiled copy of a function) taken out of the symbol names, and so
    out of the sizes of the strings that hold a name (``v9`` and ``v10`` differ by a byte)."""
    text = re.sub(r"B\d+v\d+B", "B_v_B", disp.inspect_asm(disp.signatures[0]))
    return re.sub(r'(\.size\t"[^"\n]*B_v_B[^"\n]*", )\d+', r"\1N", text)


def test_same_machine_code_and_results():
    a = np.linspace(-1.0, 1.0, 17)
    plain = njit(_outer)
    want = plain(a)
    with fresh_ir_inlining() as active:
        fast = njit(_outer)
        got = fast(a)
    assert active
    assert got == want
    assert _asm(fast) == _asm(plain)


def test_no_block_is_deep_copied_while_active(monkeypatch):
    copied = []
    own = copy.deepcopy

    def counting(x, memo=None, _nil=[]):  # noqa: B006 - copy.deepcopy's own signature
        if isinstance(x, ir.Block):
            copied.append(x)
        return own(x, memo)

    monkeypatch.setattr(copy, "deepcopy", counting)
    a = np.ones(5)
    njit(_outer)(a)
    assert copied, "Numba's inliner no longer copies blocks: this module can go"
    copied.clear()
    with fresh_ir_inlining():
        njit(_outer)(a)
    assert copied == []


def test_patch_is_scoped_and_nests():
    own = ic.InlineWorker.inline_function
    with fresh_ir_inlining():
        patched = ic.InlineWorker.inline_function
        assert patched is not own
        with fresh_ir_inlining():
            assert ic.InlineWorker.inline_function is patched
        assert ic.InlineWorker.inline_function is patched  # the outer body still has it
    assert ic.InlineWorker.inline_function is own
    assert ic.copy is copy
    with pytest.raises(RuntimeError), fresh_ir_inlining():
        raise RuntimeError("a failed compile")
    assert ic.InlineWorker.inline_function is own


def test_does_nothing_where_numba_differs(monkeypatch):
    monkeypatch.delattr(ic.InlineWorker, "run_untyped_passes")
    own = ic.InlineWorker.inline_function
    with fresh_ir_inlining() as active:
        assert not active
        assert ic.InlineWorker.inline_function is own


@pytest.mark.slow
def test_moving_pass_compiles_to_the_same_machine_code():
    """The largest kernel (the moving-obstacle pass, several inline callees deep), compiled
    with and without the copies: the same code. About a minute of CPU."""
    from mawdo.jit import warm as jitwarm

    table = jitwarm.load_table()
    (row,) = [e for e in table if e.name == "moving_pass"]
    disp = jitwarm.dispatcher(row)
    opts = {k: v for k, v in disp.targetoptions.items() if k not in ("cache", "nopython")}
    sig = jitwarm.parse(row.sig)
    plain = njit(sig, **opts)(disp.py_func)
    with fresh_ir_inlining():
        fast = njit(sig, **opts)(disp.py_func)
    assert _asm(fast) == _asm(plain)
