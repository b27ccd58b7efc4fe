"""Figures begun at a command's start: a forked process sets them up while the planner runs.

A warm ``mawdo plan paper`` spends about 4 s planning and, after it, about 3 s of CPU on its
figures: importing matplotlib, laying out the snapshot grid and the GIF's panel (axes, ticks,
static obstacles, legend), then drawing the run on them. Only the last part needs the run.
:class:`EarlyFigures` forks a child once the command has set its run up (arguments checked,
modules imported and kernels loaded, which the child then shares: forked at argument parsing
it imported Numba and the planner a second time, 1.3 s more CPU); the child does the first
part on the second core while the parent plans, then waits for the run on a pipe. The
parent sends the run (pickled: a few hundred kB) and waits for the child's answer: the paths
it wrote, or its error, raised again in the parent. While the run goes on, the parent
also hands the child the steps made so far (:meth:`EarlyFigures.feed`, :mod:`.live`), and the
child draws each GIF frame once the run has passed its time. After the run the child draws the
grid itself and finishes the GIF in a grandchild (:class:`~mawdo.planning.render.forked.Forked`:
the frames not drawn yet, the palette, the file), so only the grid's moving parts, the palette
and the file writing are left.

Where ``fork`` is missing or there is one core, nothing runs early: :meth:`EarlyFigures.send`
then sets up and draws in this process, the same figures one after the other.

Interrupts: the child shares the terminal's process group, so Ctrl-C reaches it too; it ends
quietly (exit 130) and the parent's ``KeyboardInterrupt`` ends it if it still runs. A parent
that stops early (bad input, an error) calls :meth:`EarlyFigures.cancel` (``with`` does): the
child ends without writing anything. A parent killed outright closes its end of the pipe, and
the child, waiting on it, ends.
"""

from __future__ import annotations

import multiprocessing
import os
import signal
import warnings
from collections.abc import Callable
from contextlib import contextmanager

from mawdo.planning.render import style
from mawdo.planning.render.forked import can_fork, send_back

#: ``prepare()`` runs early and returns ``finish(payload) -> value``; a ``finish`` with a
#: ``feed`` attribute also takes what :meth:`EarlyFigures.feed` sends before the payload, as
#: ``feed(data, payload_waiting)`` (the second a callable: True once the payload has come).
Prepare = Callable[[], Callable[[object], object]]


class News:
    """Data sent to the child before the payload (:meth:`EarlyFigures.feed`)."""

    __slots__ = ("data",)

    def __init__(self, data) -> None:
        self.data = data


class Given(News):
    """What ``prepare`` takes, learnt by the parent after the fork (:meth:`EarlyFigures.begin`)."""

    __slots__ = ()


#: The child's answer to each :class:`News`: it took it, the next may come.
_TAKEN = None
_NONE = object()


class EarlyFigures:
    """Run ``prepare()`` now in a forked child; :meth:`send` gives its ``finish`` the payload.

    Parameters
    ----------
    prepare : callable
        Takes nothing and returns ``finish``, a callable that takes the payload (picklable)
        and returns a picklable value (the paths written). Neither may print (the child shares
        the terminal) nor start Numba's parallel threads. A ``prepare`` with a ``warm``
        attribute (a callable: imports, say) is begun in two steps: the child calls ``warm()``
        at once, then waits for :meth:`begin`'s data and calls ``prepare(data)``; so the child
        can be forked before the parent knows all that ``prepare`` needs (a parent that sends
        News or the payload without :meth:`begin` gets ``prepare()``).
    parallel : bool
        False: run both in this process, at :meth:`send` (what happens without ``fork``).
    """

    def __init__(self, prepare: Prepare, parallel: bool = True) -> None:
        self.prepare = prepare
        self.proc = self.conn = None
        self.payload = self.given = None
        self.waiting = False  # a News not yet taken by the child (None: no more News)
        self.answer = _NONE  # the child's answer, if feed() received it
        if not (parallel and can_fork()):
            return
        ctx = multiprocessing.get_context("fork")
        self.conn, child_end = ctx.Pipe()
        # Ctrl-C held back while forking: one that came in between (the command's start, when
        # the terminal's user is most likely to press it) would otherwise stop this process
        # half-way through start() with a child it cannot end; now it comes after, to both
        try:
            with warnings.catch_warnings(), _sigint_held():
                warnings.simplefilter("ignore", DeprecationWarning)  # (>= 3.12, other threads)
                # not a daemon: the child forks the GIF's drawing process itself
                self.proc = ctx.Process(target=_child, args=(prepare, child_end, self.conn))
                self.proc.start()
        except BaseException:  # that Ctrl-C: no child left behind
            if self.proc is not None and self.proc.pid is not None:
                self.cancel()
            raise
        finally:
            child_end.close()

    @property
    def early(self) -> bool:
        """Whether a child set the figures up while this process planned."""
        return self.proc is not None

    def feed(self, make: Callable[[], object]) -> None:
        """Send ``make()`` to the child (its ``finish.feed``) if it has taken the last one.

        ``make`` is called only then (it returns what is new since its last call, or None for
        nothing), so at most one message waits in the pipe and the caller, the planner between
        two steps, never waits for the child; a child that falls behind gets more at once.
        Without a child this does nothing.
        """
        if self.proc is None or self.waiting is None:
            return
        try:
            while self.waiting and self.conn.poll():
                answer = self.conn.recv()
                if answer is not _TAKEN:  # the child's end (its error): result() raises it
                    self.answer, self.waiting = answer, None
                    return
                self.waiting = False
            if self.waiting:
                return
            data = make()
            if data is not None:
                self.conn.send(News(data))
                self.waiting = True
        except (BrokenPipeError, EOFError, ConnectionResetError):
            self.waiting = None  # the child ended: result() says how

    def begin(self, data) -> None:
        """Hand the child what its ``prepare`` takes (see the class); without a child, keep it
        for :meth:`result`."""
        if self.proc is None:
            self.given = data
            return
        try:
            self.conn.send(Given(data))
        except (BrokenPipeError, EOFError):
            pass  # the child ended early: result() says how

    def send(self, payload) -> None:
        """Hand the run to the child (without one: keep it for :meth:`result`)."""
        if self.proc is None:
            self.payload = payload
            return
        try:
            self.conn.send(payload)
        except (BrokenPipeError, EOFError):
            pass  # the child ended early: result() says how

    def result(self):
        """Wait for the figures and return ``finish``'s value, or raise the child's error."""
        if self.proc is None:
            prepare = self.prepare
            return (prepare() if self.given is None else prepare(self.given))(self.payload)
        try:
            answer = self.answer
            while answer is _NONE or answer is _TAKEN:  # (answers to the last News)
                answer = self.conn.recv()
            ok, value = answer
        except EOFError:  # it died without a word (killed, out of memory)
            self.proc.join()
            raise RuntimeError(
                f"the drawing process ended (exit code {self.proc.exitcode}) with no result"
            ) from None
        except BaseException:  # Ctrl-C while waiting: no child left behind
            self.cancel()
            raise
        self.conn.close()
        self.proc.join()
        if not ok:
            raise value
        return value

    def cancel(self) -> None:
        """End the child now if it still runs (nothing more is written)."""
        if self.proc is None:
            return
        if self.proc.is_alive():
            self.proc.terminate()
        self.proc.join()
        self.conn.close()

    def __enter__(self) -> EarlyFigures:
        return self

    def __exit__(self, *exc) -> None:
        self.cancel()  # a no-op once result() has joined the child


@contextmanager
def _sigint_held():
    """Block SIGINT in this thread inside the block (where signal masks exist); one that
    arrives meanwhile is delivered when the block ends. A child forked inside inherits the
    mask: :func:`_child` unblocks it."""
    held = hasattr(signal, "pthread_sigmask")
    if held:
        signal.pthread_sigmask(signal.SIG_BLOCK, {signal.SIGINT})
    try:
        yield
    finally:
        if held:
            signal.pthread_sigmask(signal.SIG_UNBLOCK, {signal.SIGINT})


def _child(prepare: Prepare, conn, parent_end) -> None:
    """The child: ``prepare()``, then the payload from ``conn``, then ``(ok, value)`` back."""
    parent_end.close()  # so that the parent's death closes the pipe for us
    try:
        if hasattr(signal, "pthread_sigmask"):  # (forked with SIGINT held: _sigint_held)
            signal.pthread_sigmask(signal.SIG_UNBLOCK, {signal.SIGINT})
        try:
            first = _given(prepare, conn)
            if isinstance(first, Given):
                finish, error, first = prepare(first.data), None, _NONE
            else:
                finish, error = prepare(), None
        except EOFError:  # the parent stopped before its run: nothing to draw
            os._exit(0)
        except Exception as exc:  # said once the parent asks for the figures
            finish, error, first = None, exc, _NONE
        try:
            payload = _news(conn, getattr(finish, "feed", None), first)
        except EOFError:  # the parent stopped before its run: nothing to draw
            os._exit(0)
        message = (False, error) if error else (True, finish(payload))
    except KeyboardInterrupt:  # the parent has its own and says so
        os._exit(130)
    except Exception as exc:
        message = (False, exc)
    send_back(conn, message)


def _given(prepare: Prepare, conn):
    """A ``prepare`` with ``warm``: ``warm()``, then the parent's first message (its
    :class:`Given`, or what it sent without one); else :data:`_NONE`, nothing received."""
    warm = getattr(prepare, "warm", None)
    if warm is None:
        return _NONE
    warm()
    return conn.recv()


def _news(conn, feed, first=_NONE):
    """Receive until the payload (``first`` if it was received already), handing each
    :class:`News` to ``feed`` (if any) with ``conn.poll`` and saying it was taken; return the
    payload. While ``feed`` works, the parent waits for the answer before sending more News, so
    a message waiting is the payload: ``feed`` may stop early when ``poll()`` says so (the run
    is over, its figures come first). A :class:`Given` nobody waited for is dropped."""
    payload = conn.recv() if first is _NONE else first
    while isinstance(payload, News):
        if isinstance(payload, Given):
            payload = conn.recv()  # (no answer: the parent waits for none)
            continue
        if feed is not None:
            feed(payload.data, conn.poll)
        conn.send(_TAKEN)
        payload = conn.recv()
    return payload


def run_figures(scenario, algorithm: str, seed: int, grid, gif, label: str | None = None,
                every: int = 2) -> Prepare:  # fmt: skip
    """What :class:`EarlyFigures` runs for one planning run: the snapshot grid and the GIF.

    Parameters
    ----------
    scenario : Scenario
        The run's scenario (the figures' static parts are drawn from it before the run).
    algorithm : str
        The run's algorithm (the GIF's title; the grid's when ``label`` is None).
    seed : int
        The run's seed (the titles).
    grid, gif : Path
        Output paths of the snapshot grid (``.png``) and the GIF.
    label : str, optional
        The grid's label for the run (default: the algorithm's display label).
    every : int
        Time steps between GIF frames.

    Returns
    -------
    callable
        ``prepare(optimum=None)`` with ``warm`` (:class:`EarlyFigures`); ``optimum``: the
        static optimum path if the parent computed it (the child then loads no kernel). Its
        ``finish`` takes ``(result, metrics, metadata)`` (metrics and PNG text may be None) and
        returns ``(grid path, gif path)``.
    """

    def prepare(optimum=None):
        from mawdo.planning.render.animation import GifFrame
        from mawdo.planning.render.forked import Forked
        from mawdo.planning.render.live import PartialRun
        from mawdo.planning.render.snapshots import GridFrame, grid_blocks, save_grid

        if optimum is not None:
            style.know_optimum(scenario, optimum)
        frame = GridFrame([scenario])
        movie = GifFrame(scenario, style.display_name(algorithm), seed)
        partial = PartialRun()

        def feed(news, run_over):  # the run so far: draw the GIF frames it fixes (.live)
            partial.add(news)
            movie.draw_ready(partial, every, stop=run_over)  # the rest after the run

        def finish(payload):
            result, metrics, metadata = payload
            grid_out = style.checked_output_path(grid, style.IMAGE_SUFFIXES)
            gif_out = style.checked_output_path(gif, (".gif",))
            job = Forked(lambda: movie.write(result, gif_out, every=every))  # beside the grid
            key = label or result.algorithm
            blocks = grid_blocks([(key, result)], None, frame.rows * frame.cols, {key: metrics})
            path = save_grid(frame.fill(blocks), grid_out, metadata)
            return path, job.result()

        finish.feed = feed
        return finish

    prepare.warm = warm_up
    return prepare


def warm_up() -> None:
    """What every figure's set-up imports and loads first (matplotlib, Pillow and its common
    image formats, the optimizer catalog for the labels, the default font): 0.6-0.7 s of CPU,
    done by a figures' process forked before its parent's run is set up, while the parent
    sets it up (Pillow's formats were imported by the first save, after the run, twice: the
    grid's and the GIF's process, 0.02 s each)."""
    import matplotlib.backends.backend_agg  # noqa: F401
    import matplotlib.figure  # noqa: F401
    import matplotlib.lines  # noqa: F401
    import matplotlib.patches  # noqa: F401
    import PIL.Image
    from matplotlib import font_manager

    import mawdo.optimizers  # noqa: F401  (display_name)

    PIL.Image.preinit()
    font_manager.get_font(font_manager.findfont(font_manager.FontProperties()))
