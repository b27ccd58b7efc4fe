"""Tell a Ctrl-C apart from an error, even when compiled code has disguised it.

A terminal's Ctrl-C sends SIGINT; Python's handler raises ``KeyboardInterrupt`` at the next
bytecode it runs. When that bytecode runs inside a C call that does not expect an exception
(Numba's dispatcher boxing a result, for one), the call then fails with ``SystemError: ...
returned a result with an exception set`` whose ``__cause__`` is the ``KeyboardInterrupt``;
code catching ``Exception`` around it (a study kind turning a failing run into an error row)
would swallow the interrupt and record a failure that never happened. Two checks
catch every form: :func:`is_interrupt` looks for a ``KeyboardInterrupt`` in an exception's
cause/context chain, and :class:`SigintWatch` counts the SIGINTs that arrived while a piece
of work ran, whatever became of the exception they raised.
"""

from __future__ import annotations

import signal
import threading

__all__ = ["INTERRUPT_EXIT", "SigintWatch", "forget_caught_interrupt", "is_interrupt"]

INTERRUPT_EXIT = 130
"""Exit status of a command stopped by Ctrl-C (128 + SIGINT, as a shell reports it)."""


def is_interrupt(exc: BaseException | None) -> bool:
    """Whether ``exc`` is, or was caused by, a ``KeyboardInterrupt``.

    Parameters
    ----------
    exc : BaseException or None
        An exception; its ``__cause__`` and ``__context__`` links are followed (cycles are
        stopped).

    Returns
    -------
    bool
        True for a ``KeyboardInterrupt`` anywhere in the chain (e.g. the ``SystemError`` that
        a compiled call raises when Ctrl-C interrupts it).
    """
    seen: set[int] = set()
    todo = [exc]
    while todo:
        e = todo.pop()
        if e is None or id(e) in seen:
            continue
        if isinstance(e, KeyboardInterrupt):
            return True
        seen.add(id(e))
        todo += [e.__cause__, e.__context__]
    return False


def forget_caught_interrupt() -> None:
    """Let a ``KeyboardInterrupt`` that was caught and handled end the program with the exit
    status it chose, not killed by SIGINT.

    CPython (3.11 and later) remembers a ``KeyboardInterrupt`` that left any code run by
    ``exec`` of a string (``dataclasses`` and ``collections.namedtuple`` build their methods so,
    on import) as unhandled, even when a caller catches it; a program started with ``python -m``
    then ends by killing itself with SIGINT after its own ``sys.exit(130)``, so its parent sees
    a signal instead of the status. Running ``exec`` of a string once more resets that memory.
    Call this where a Ctrl-C has been handled and the program is about to exit.
    """
    exec("None")  # noqa: S102 - (a fixed string: only CPython's reset matters)


class SigintWatch:
    """Count the SIGINTs this process receives inside a ``with`` block.

    The handler in place stays in charge (the default one still raises ``KeyboardInterrupt``
    at once, so a long computation stops early); the watch only counts. Where it cannot watch
    it does nothing: outside the main thread (signal handlers belong to it), or where SIGINT
    is ignored or left to the operating system (a pool worker that lets its parent handle
    Ctrl-C), since no Python code runs on a SIGINT there.

    Attributes
    ----------
    count : int
        SIGINTs received since the block was entered (>= 0).
    fired : bool
        A SIGINT arrived since the block was entered.
    """

    def __init__(self) -> None:
        self.count = 0
        self._previous = None

    @property
    def fired(self) -> bool:
        """A SIGINT arrived since the block was entered."""
        return self.count > 0

    def _handler(self, signum, frame):
        self.count += 1
        previous = self._previous
        if callable(previous):
            return previous(signum, frame)
        return None

    def __enter__(self) -> SigintWatch:
        if threading.current_thread() is threading.main_thread():
            current = signal.getsignal(signal.SIGINT)
            if callable(current):
                self._previous = current
                signal.signal(signal.SIGINT, self._handler)
        return self

    def __exit__(self, *exc) -> None:
        if self._previous is not None:
            signal.signal(signal.SIGINT, self._previous)
            self._previous = None
