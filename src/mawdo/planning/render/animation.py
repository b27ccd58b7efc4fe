"""An animated GIF of one planning run (Pillow, no ffmpeg).

Fast by blitting: the figure (legend, axes, ticks, labels) is rendered once as a background;
each frame restores it, moves the map's artists to the frame's time (:func:`world_state`, the
same one that draws the snapshot panels) and draws only them and the panel title. Redrawing the
whole figure per frame cost about 0.14 s of CPU a frame, mostly in the legend's and the ticks'
text layout; blitting costs a few milliseconds. The frames share one palette, so Pillow maps
them to it instead of quantizing each frame on its own.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from mawdo.planning.render.style import (
    axis_label,
    checked_output_path,
    display_name,
    new_figure,
    optimum_path,
    route_of,
    time_title,
)
from mawdo.planning.render.world import (
    add_layer,
    draw_world,
    legend_handles,
    set_layer,
    world_state,
)
from mawdo.planning.run.result import PlanResult

#: Colours of the shared palette taken exactly as drawn (the rest of the 256 by median cut).
_EXACT_COLOURS = 96


def animation_times(result: PlanResult, every: int = 2, max_frames: int = 200) -> np.ndarray:
    """Frame times of :func:`animate`: every ``every`` steps, thinned to ``max_frames``.

    The end of the run is always the last frame.
    """
    if not isinstance(every, int | np.integer) or every < 1:
        raise ValueError(f"every={every!r} must be a positive integer")
    if not isinstance(max_frames, int | np.integer) or max_frames < 2:
        raise ValueError(f"max_frames={max_frames!r} must be an integer >= 2")
    end = float(route_of(result)[1][-1])
    ts = np.arange(0.0, end + 1e-9, every)
    if ts[-1] < end - 1e-9:
        ts = np.append(ts, end)
    if ts.size > max_frames:
        ts = ts[np.unique(np.linspace(0, ts.size - 1, max_frames).round().astype(int))]
    return ts


def animate(
    result: PlanResult,
    path,
    fps: int = 12,
    every: int = 2,
    max_frames: int = 200,
    optimum: bool = True,
    dpi: int = 80,
    label: str | None = None,
) -> Path:
    """Animated GIF of one run: the snapshot panel of :func:`snapshot_grid`, one frame per time.

    Parameters
    ----------
    result : PlanResult
    path : str or Path
        Output ``.gif``; missing directories are created.
    fps : int
        Frames per second.
    every : int
        Time steps between frames (2: about half as many frames to draw and encode as steps,
        the GIF twice as short; the demo and the study report used 2 already).
    max_frames : int
        Upper bound on frames (the times are thinned evenly, the last one kept).
    optimum : bool
        Draw the static optimum path.
    dpi : int
        Resolution of the 5 x 5.6 in figure (80 dpi: 400 x 448 px, a few MB at most).
    label : str, optional
        Title (default the algorithm's display label).

    Returns
    -------
    Path
        The written GIF.
    """
    if not isinstance(result, PlanResult):
        raise TypeError(f"animate needs a PlanResult, got {type(result).__name__}")
    if not (isinstance(fps, int | np.integer | float) and fps > 0):
        raise ValueError(f"fps={fps!r} must be > 0")
    out = checked_output_path(path, (".gif",))
    label = label or display_name(result.algorithm)
    frame = GifFrame(result.scenario, label, result.seed, optimum=optimum, dpi=dpi)
    return frame.write(result, out, fps=fps, every=every, max_frames=max_frames)


class GifFrame:
    """The GIF's figure before the run: what :func:`animate` draws once, then the frames.

    ``GifFrame(scenario, label, seed)`` lays out the panel (title, legend, axes, ticks, labels)
    and renders everything that never moves as the background the frames are blitted on;
    :meth:`write` draws the run's frames on it and writes the GIF. The first step needs no
    run, so it can be done while the planner runs (:mod:`.early`); the frames are the same.
    """

    def __init__(self, scenario, label: str, seed: int, optimum: bool = True, dpi: int = 80):
        self.scenario = scenario
        self.opt = optimum_path(scenario, {}) if optimum else None
        self.fig, self.ax = _figure(scenario, f"{label}  (seed {seed})", dpi)
        # the world at t = 0 (every frame's first time) without a run: its layers and the
        # background behind them; the run's layers are added by write()
        draw_world(self.ax, scenario, 0.0, optimum=self.opt, clear=False)
        self.frames = _Frames(
            self.fig, self.ax, scenario, world_state(scenario, 0.0, None, self.opt)
        )
        self.drawn: dict[float, _Shot] = {}  # frames drawn while the run went on, by time
        self.seen = np.zeros(1 << 24, dtype=bool)  # their colours, a flag per 0xRRGGBB
        self._last = None  # the last of them (its colours are flagged)

    def draw_ready(self, partial, every: int = 2, max_frames: int = 200, stop=None) -> int:
        """Draw the frames the run so far fixes: those at the times ``0, every, 2 every, ...``
        before the end of ``partial`` (a run under way, :class:`~.live.PartialRun`), at most
        ``max_frames`` in all; :meth:`write` uses them. A frame shows the route up to its time
        and the last plan made at or before it, which later steps do not change, and it is a
        function of what it shows alone, so it is the frame :meth:`write` would draw.
        ``stop()`` (if given) is asked before each frame: True ends the drawing (what is
        left, :meth:`write` draws). Returns how many frames were drawn now."""
        if not len(partial.route_times):
            return 0
        if not self.drawn:
            self.frames.add(world_state(self.scenario, 0.0, partial, self.opt))
        done = 0
        t = float(every * len(self.drawn))
        while len(self.drawn) < max_frames and t < partial.end and not (stop and stop()):
            state = world_state(self.scenario, t, partial, self.opt)
            self.drawn[t] = _Shot(self.frames.grab(state, t), self.seen, self._last)
            self._last = self.drawn[t].packed
            done, t = done + 1, float(every * len(self.drawn))
        return done

    def write(self, result: PlanResult, out: Path, fps=12, every=2, max_frames=200) -> Path:
        """Draw ``result``'s frames (:func:`animation_times`) and write them to ``out``; frames
        :meth:`draw_ready` drew are used as they are."""
        ts = animation_times(result, every, max_frames)
        sc, opt = self.scenario, self.opt
        self.frames.add(world_state(sc, float(ts[0]), result, opt))
        shots = []
        for t in ts:
            shot = self.drawn.get(float(t))
            if shot is None:
                shot = _Shot(self.frames.grab(world_state(sc, float(t), result, opt), t))
            shots.append(shot)
        _write_gif(shots, out, fps, self.seen if self.drawn else None)
        return out


def _figure(scenario, title: str, dpi: int):
    """The GIF's figure: title, legend, one axes with its labels, laid out once (frames keep
    that layout: the panel title's text changes, not its height); ``(figure, axes)``."""
    fig = new_figure((5.0, 5.6), dpi)
    fig.get_layout_engine().set(w_pad=0.02, h_pad=0.02)
    fig.suptitle(title, fontsize=10)
    ax = fig.add_subplot()
    handles = legend_handles(scenario.robot_radius, scenario.units)
    fig.legend(
        handles=handles,
        loc="outside lower center",
        ncols=3,
        fontsize=6.5,
        frameon=False,
        handlelength=2.0,
        columnspacing=1.0,
    )
    draw_world(ax, scenario, 0.0, clear=False, moving=False)  # limits, ticks (a new axes)
    ax.set_xlabel(axis_label(scenario, "x"), fontsize=7)
    ax.set_ylabel(axis_label(scenario, "y"), fontsize=7)
    # the layout alone, not a whole draw with rendering off (the frames' first draw renders)
    fig.get_layout_engine().execute(fig)
    fig.set_layout_engine("none")
    for artist in [*ax.lines, *ax.patches]:
        artist.remove()  # the caller draws the world
    return fig, ax


def _panel(result: PlanResult, t: float, opt, dpi: int, label: str | None):
    """The GIF's figure with its map panel drawn at time ``t`` in one go (what a frame shows);
    ``(figure, axes)``."""
    title = f"{label or display_name(result.algorithm)}  (seed {result.seed})"
    fig, ax = _figure(result.scenario, title, dpi)
    draw_world(ax, result.scenario, t, result=result, optimum=opt, clear=False)
    return fig, ax


class _Frames:
    """Frames of one map panel by blitting (see the module docstring)."""

    def __init__(self, fig, ax, scenario, state: dict) -> None:
        self.fig, self.ax, self.scenario = fig, ax, scenario
        self.layers = {}  # gid -> its artists
        for a in [*ax.lines, *ax.patches]:
            self.layers.setdefault(a.get_gid(), []).append(a)
        self.gids: list = []
        self.add(state)
        ax.title.set_animated(True)
        fig.canvas.draw()
        self.background = fig.canvas.copy_from_bbox(fig.bbox)

    def add(self, state: dict) -> None:
        """Layers of ``state`` not drawn yet: added as empty artists, every layer animated
        (drawn per frame, not in the background)."""
        for gid, data in state.items():
            if gid not in self.layers:
                self.layers[gid] = add_layer(self.ax, self.scenario, gid, data)
        self.gids = list(state)
        for a in self._artists():
            a.set_animated(True)

    def _artists(self) -> list:
        # the order of a fresh panel: by zorder, ties in the order draw_world adds them
        arts = [a for gid in self.gids for a in self.layers[gid]]
        return sorted(arts, key=lambda a: a.get_zorder())  # (a stable sort)

    def grab(self, state: dict, t: float) -> np.ndarray:
        """The frame at time ``t`` (state from :func:`world_state`), its pixels packed
        (:func:`_packed_rgba`)."""
        for gid in self.gids:
            data = state.get(gid)
            arts = self.layers[gid]
            if not set_layer(arts, gid, data):
                for a in arts:
                    a.remove()
                arts[:] = add_layer(self.ax, self.scenario, gid, data)
                for a in arts:
                    a.set_animated(True)
            for a in arts:
                a.set_visible(data is not None)
        self.ax.title.set_text(time_title(self.scenario, float(t)))
        canvas = self.fig.canvas
        canvas.restore_region(self.background)
        for a in [*self._artists(), self.ax.title]:
            self.ax.draw_artist(a)
        return _packed_rgba(np.asarray(canvas.buffer_rgba()))  # (a new array: it is reused)


def _packed(rgb: np.ndarray) -> np.ndarray:
    """RGB pixels ``(h, w, 3)`` uint8 as one integer each, ``0xRRGGBB``, ``(h, w)``."""
    px = rgb.astype(np.uint32)
    return (px[..., 0] << 16) | (px[..., 1] << 8) | px[..., 2]


def _packed_rgba(rgba: np.ndarray) -> np.ndarray:
    """RGBA pixels ``(h, w, 4)`` uint8 packed as :func:`_packed` packs their RGB: each pixel's
    four bytes read as one big-endian word ``0xRRGGBBAA``, alpha shifted out. Three times
    cheaper than copying the RGB out and packing it (a frame drawn while the run is planned
    spent a third of its 15 ms there)."""
    words = np.ascontiguousarray(rgba).view(">u4")[..., 0]
    return (words >> 8).astype(np.uint32, copy=False)  # (the shift made a new, native array)


class _Shot:
    """One frame: its pixels packed, ``(h, w)`` (:func:`_packed`); its colours are flagged in
    ``seen`` (one flag per ``0xRRGGBB``) if given. With ``before``, a frame of the same size
    whose colours are all flagged already, only the pixels that differ from it are flagged:
    the same colours (every other pixel has a colour of ``before``), in a fraction of the time
    (``plan paper``'s frames: 0.8 -> 0.2 ms a frame measured alone, more between draws, when
    the 16 MB of flags have left the cache)."""

    __slots__ = ("packed",)

    def __init__(self, packed: np.ndarray, seen=None, before: np.ndarray | None = None) -> None:
        self.packed = packed
        if seen is not None:
            seen[packed if before is None else packed[packed != before]] = True

    @classmethod
    def of(cls, rgb: np.ndarray, seen: np.ndarray | None = None) -> _Shot:
        """The frame of RGB pixels ``(h, w, 3)`` uint8."""
        return cls(_packed(rgb), seen)

    @property
    def rgb(self) -> np.ndarray:
        """The RGB pixels ``(h, w, 3)`` uint8 (unpacked: only the palette's three frames)."""
        p = self.packed
        return np.stack([p >> 16, (p >> 8) & 255, p & 255], -1).astype(np.uint8)


class _Palette:
    """One palette for every frame, from the first, middle and last frame: their most frequent
    colours exactly (background, fills and lines stay pure), the anti-aliased rest by median
    cut. Each colour of a frame maps to its nearest palette entry (squared RGB distance, the
    first on a tie), through a table over all 2^24 colours filled as colours appear: a frame
    costs a lookup per pixel, not a search (Pillow's own mapping was a quarter of the GIF's
    time, and its coarse colour cache could turn white into 252 grey). Each colour's entry
    depends on that colour alone, so the table may be filled in any order: colours flagged
    while the frames were drawn early are mapped in one pass."""

    def __init__(self, shots: list[_Shot]) -> None:
        from PIL import Image

        picks = [shots[k] for k in (0, len(shots) // 2, -1)]
        packed = np.concatenate([s.packed for s in picks])
        colours, counts = np.unique(packed, return_counts=True)
        top = np.sort(colours[np.argsort(-counts, kind="stable")[:_EXACT_COLOURS]])
        exact_rgb = np.stack([top >> 16, (top >> 8) & 255, top & 255], 1)
        n_cut = 256 - len(top)
        rgb = np.concatenate([s.rgb for s in picks])
        cut = Image.fromarray(rgb).quantize(n_cut, Image.Quantize.MEDIANCUT)
        rest = np.asarray(cut.getpalette()[: 3 * n_cut]).reshape(-1, 3)
        self.entries = np.concatenate([exact_rgb, rest]).astype(np.int64)  # (<= 256, 3)
        self.rgb = self.entries.astype(np.uint8).ravel().tolist()
        # 0xRRGGBB -> 1 + its entry (0: not yet). Zeros, not -1: a fresh zeroed array costs no
        # time until a page is written (np.full wrote all 32 MB: 0.1 s of CPU per GIF)
        self.table = np.zeros(1 << 24, dtype=np.int16)
        self.table[top] = np.arange(1, len(top) + 1)
        # |c - e|^2 = |c|^2 - 2 c.e + |e|^2: the first term is the same for every entry
        self._norms = (self.entries**2).sum(1)

    def learn(self, colours: np.ndarray) -> None:
        """Fill the table for ``colours`` (packed, unique) not in it yet: each its nearest entry
        by squared RGB distance, the first on a tie. The distances are computed as
        ``|e|^2 - 2 c.e`` (``|c|^2`` dropped) in integers, channel by channel: exact, and no
        BLAS call (a matrix product here was the GIF process's first BLAS call, whose start-up
        cost 0.1 s of CPU of the 0.15 s of a GIF's colours)."""
        new = colours[self.table[colours] == 0]
        e = self.entries.T  # (3, entries) int64
        for lo in range(0, new.size, 8192):
            part = new[lo : lo + 8192].astype(np.int64)[:, None]
            dot = (part >> 16) * e[0] + ((part >> 8) & 255) * e[1] + (part & 255) * e[2]
            self.table[part[:, 0]] = np.argmin(self._norms[None, :] - 2 * dot, axis=1) + 1

    def __call__(self, shot: _Shot):
        """A frame as a palette image on this palette."""
        from PIL import Image

        index = self.table[shot.packed]
        if not index.all():
            self.learn(np.unique(shot.packed[index == 0]))
            index = self.table[shot.packed]
        out = Image.fromarray((index - 1).astype(np.uint8).reshape(shot.packed.shape), "P")
        out.putpalette(self.rgb)
        return out


def _write_gif(shots: list[_Shot], out: Path, fps, seen: np.ndarray | None = None) -> None:
    """Write frames as one looping GIF on a shared palette, each shown ``1 / fps`` s; ``seen``
    flags colours known to occur (mapped to the palette in one pass before the frames)."""
    palette = _Palette(shots)
    if seen is not None:
        palette.learn(np.flatnonzero(seen).astype(np.uint32))
    frames = [palette(shot) for shot in shots]
    try:
        frames[0].save(
            out,
            save_all=True,
            append_images=frames[1:],
            duration=round(1000 / fps),
            loop=0,
            optimize=False,
        )
    except OSError as exc:
        raise OSError(f"cannot write {str(out)!r}: {exc.strerror or exc}") from exc
