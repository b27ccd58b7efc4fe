"""Draw one figure in a second process while this one draws another (the GIF beside the grid).

Drawing is Python-bound (matplotlib holds the GIL), so two figures of one run are drawn at once
only by two processes. :class:`Forked` runs a drawing function in a child made by ``fork``: the
child shares the run and the imported modules with no pickling and no second import, and sends
back only the function's value (a path) or its error. Where ``fork`` is missing (Windows,
macOS's default) or there is a single core, the function simply runs first, in this process.

Measured on the ``paper`` demo run (62 GIF frames, 2 x 4 grid): the grid took 1.7-2.3 s of CPU
and the GIF 1.4 s one after the other; side by side the pair takes the longer of the two.
"""

from __future__ import annotations

import multiprocessing
import os
import sys
import warnings
from collections.abc import Callable


def can_fork() -> bool:
    """Whether :class:`Forked` draws in a second process: ``fork`` exists (Linux) and there is
    more than one core."""
    return sys.platform.startswith("linux") and (os.cpu_count() or 1) > 1


class Forked:
    """Start ``fn()`` in a forked child; :meth:`result` waits for it and returns its value.

    Parameters
    ----------
    fn : callable
        Takes nothing; returns something picklable (a path), or raises. It must not print
        (the child shares the terminal) nor use Numba's parallel threads.
    parallel : bool
        False: run ``fn`` in this process when :meth:`result` is called (what happens anyway
        without ``fork`` or with one core).

    Notes
    -----
    An error in the child is raised again by :meth:`result` (same type and message; the
    traceback stays in the child). Ctrl-C reaches both processes (one process group): the
    child ends quietly and the parent's ``KeyboardInterrupt`` ends the child if it still runs.
    """

    def __init__(self, fn: Callable[[], object], parallel: bool = True) -> None:
        self.fn = fn
        self.proc = self.conn = None
        if not (parallel and can_fork()):
            return  # result() runs it
        # both processes draw: import the plotting modules once, before the fork
        import matplotlib.backends.backend_agg  # noqa: F401
        import PIL.Image  # noqa: F401

        ctx = multiprocessing.get_context("fork")
        self.conn, child_end = ctx.Pipe(duplex=False)
        with warnings.catch_warnings():  # Python >= 3.12 warns when other threads exist
            warnings.simplefilter("ignore", DeprecationWarning)
            self.proc = ctx.Process(target=_run, args=(fn, child_end), daemon=True)
            self.proc.start()
        child_end.close()

    def result(self):
        """Wait for ``fn`` and return its value, or raise its error (without a child: run it)."""
        if self.proc is None:
            return self.fn()
        try:
            ok, payload = self.conn.recv()
        except EOFError:  # it died without a word (killed, out of memory)
            self.proc.join()
            code = self.proc.exitcode
            raise RuntimeError(
                f"the drawing process ended (exit code {code}) with no result"
            ) from None
        except BaseException:  # Ctrl-C while waiting: no child left behind
            self.proc.terminate()
            self.proc.join()
            raise
        finally:
            self.conn.close()
        self.proc.join()
        if not ok:
            raise payload
        return payload


def forked_note(job: Forked) -> str:
    """``", drawn beside the grid"`` while ``job`` runs in a child (for a progress line: the
    time it reports is the wait that is left), else ``""``."""
    return ", drawn beside the grid" if job.proc is not None else ""


def _run(fn: Callable[[], object], conn) -> None:
    """The child: ``fn()``, then ``(True, value)`` or ``(False, error)`` on ``conn``."""
    try:
        message = (True, fn())
    except KeyboardInterrupt:  # the parent has its own and says so
        os._exit(130)
    except Exception as exc:
        message = (False, exc)
    send_back(conn, message)


def send_back(conn, message: tuple[bool, object]) -> None:
    """Send a child's ``(ok, value or error)`` on ``conn`` and close it; a value or an error
    that does not pickle becomes a ``RuntimeError`` that says what it was."""
    try:
        conn.send(message)
    except Exception as exc:
        what = f"{type(message[1]).__name__}: {message[1]}" if not message[0] else exc
        conn.send((False, RuntimeError(f"the drawing process could not send back {what}")))
    conn.close()
