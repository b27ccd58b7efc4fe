"""Ctrl-C is never a stored result (issue 28, item 1).

In process: a real SIGINT sent to this process while a task computes, in the three forms it
takes when compiled code is interrupted (a ``KeyboardInterrupt``, a ``SystemError`` caused by
it that the kind stores as an error row, and an interrupt the task swallows entirely). The
real command under a terminal-like Ctrl-C is in ``test_interrupt_cli.py``.
"""

from __future__ import annotations

import os
import signal

import pytest

from mawdo.experiments import Store, execute_task, run_plan
from mawdo.experiments.kinds.benchmark import execute as bench_exec_mod
from mawdo.util.interrupts import SigintWatch, is_interrupt

from .conftest import small_plan, stored_values


@pytest.fixture(autouse=True)
def _sigint_raises_keyboard_interrupt():
    """Python's own SIGINT handler, whatever this process inherited: a run started in the
    background of a non-interactive shell ignores SIGINT, and these tests need it raised."""
    before = signal.signal(signal.SIGINT, signal.default_int_handler)
    yield
    signal.signal(signal.SIGINT, before)


def _sigint_self() -> None:
    os.kill(os.getpid(), signal.SIGINT)


def _systemerror_like_numba() -> None:
    """What Numba's dispatcher raises when Ctrl-C lands in it: a SystemError whose cause is
    the KeyboardInterrupt that Python's handler raised inside the C call."""
    try:
        _sigint_self()  # (os.kill runs the handler before it returns)
    except KeyboardInterrupt as exc:
        raise SystemError(
            "CPUDispatcher(<function population_cost>) returned a result with an exception set"
        ) from exc
    raise AssertionError("SIGINT did not raise KeyboardInterrupt")


def _swallowed() -> None:
    """An interrupt that some library code caught and went on from."""
    try:
        _sigint_self()
    except BaseException:  # noqa: BLE001 - the point: the exception disappears
        pass


def test_is_interrupt_follows_the_cause_and_context_chain():
    try:
        _systemerror_like_numba()
    except SystemError as exc:
        disguised = exc
    assert is_interrupt(disguised) and is_interrupt(KeyboardInterrupt())
    ctx = ValueError("while handling")
    ctx.__context__ = KeyboardInterrupt()
    assert is_interrupt(ctx)
    assert not is_interrupt(SystemError("a real SystemError")) and not is_interrupt(None)
    a, b = ValueError("a"), ValueError("b")
    a.__context__, b.__context__ = b, a  # a cycle ends
    assert not is_interrupt(a)


def test_sigint_watch_counts_and_keeps_the_handler_in_charge():
    before = signal.getsignal(signal.SIGINT)
    with SigintWatch() as watch:
        assert not watch.fired
        with pytest.raises(KeyboardInterrupt):  # the default handler still raises at once
            _sigint_self()
        assert watch.count == 1
    assert signal.getsignal(signal.SIGINT) is before


@pytest.mark.parametrize("how", [_systemerror_like_numba, _swallowed])
def test_execute_task_turns_an_interrupted_task_into_keyboard_interrupt(monkeypatch, how):
    real = bench_exec_mod.minimize

    def interrupted(fun, **kw):
        how()
        return real(fun, **kw)

    monkeypatch.setattr(bench_exec_mod, "minimize", interrupted)
    plan = small_plan()
    spec = plan.task_spec(plan.tasks()[0])
    # the kind alone stores the disguised interrupt as a failed run, or as a result
    rows = bench_exec_mod.execute_benchmark_task(spec)
    if how is _systemerror_like_numba:
        assert all("SystemError" in r.error_text for r in rows)
    with pytest.raises(KeyboardInterrupt):
        execute_task(spec)


@pytest.mark.parametrize("how", [_systemerror_like_numba, _swallowed])
def test_an_interrupted_sweep_stores_nothing_of_its_task_and_resumes(
    monkeypatch, tmp_path, reference_store, how
):
    real = bench_exec_mod.minimize
    calls = []

    def third_call_interrupted(fun, **kw):
        calls.append(fun)
        if len(calls) == 3:
            how()
        return real(fun, **kw)

    monkeypatch.setattr(bench_exec_mod, "minimize", third_call_interrupted)
    plan, db = small_plan(), tmp_path / "int.db"
    summary = run_plan(plan, db, progress=False)
    assert summary.interrupted and (summary.tasks, summary.failed) == (2, 0)
    with Store.read(db) as store:
        assert store.count() == 2 * plan.batch_size and store.count(failed=True) == 0
    monkeypatch.setattr(bench_exec_mod, "minimize", real)
    again = run_plan(plan, db, progress=False)
    assert again.complete and again.skipped == 2 * plan.batch_size and again.failed == 0
    assert stored_values(db) == stored_values(reference_store)
