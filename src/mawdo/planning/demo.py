"""The demo run (``mawdo demo``, ``make demo``) and its snapshot grid, which is the README image.

``mawdo demo`` runs :func:`run_demo` and draws with :func:`write_figure`; ``make readme-img``
copies the figure that command wrote to ``docs/img/snapshots_mawdo.png``. So the README image is
drawn by the demo's code path from the demo's run, and it carries its title and caption as PNG
text chunks (:func:`figure_text`): a test compares them with a run made now, and the README
caption with the stored caption.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

from mawdo.planning.run.config import PRESETS
from mawdo.planning.run.result import PlanResult

#: What the demo runs: the paper scenario, MAWDO, the real-time planner preset.
SCENARIO = "paper"
ALGORITHM = "mawdo"
LABEL = "MAWDO"
PRESET = "realtime"
#: File name of the snapshot grid in the demo's folder (and of the README image).
FIGURE = "snapshots_mawdo.png"


@dataclass(frozen=True)
class DemoRun:
    """One demo run and its metrics.

    Attributes
    ----------
    result : PlanResult
        The planner's run.
    metrics : dict
        :func:`mawdo.planning.judge.metrics.run_metrics` of it (lengths in px, angles in rad,
        latencies in ms).
    """

    result: PlanResult
    metrics: dict

    @property
    def title(self) -> str:
        """The figure's title: label, seed, length (px), gap L/L* and smoothness (rad)."""
        from mawdo.planning.render.snapshots import run_headline

        return run_headline(LABEL, self.result, self.metrics)

    @property
    def caption(self) -> str:
        """One sentence on what the planner did in this run, its numbers from the run."""
        cfg = PRESETS[PRESET]
        replans = len(self.result.replans) - 1  # the first plan is made before the robot moves
        return (
            f"{LABEL} makes a first plan ({cfg.first_pop_size or cfg.pop_size} candidates x "
            f"{cfg.first_iters} iterations), replans {replans} times ({cfg.pop_size} candidates "
            f"x {cfg.replan_iters} iterations each) and keeps its plan without a replan on "
            f"{self.metrics['holds']} of its {self.metrics['steps']} steps"
        )

    def rows(self) -> list[tuple[str, str]]:
        """``(metric, value)`` pairs of the demo's table, formatted for people."""
        m = self.metrics
        latency = f"{m['latency_p50_ms']:.1f} / {m['latency_p95_ms']:.1f}"
        return [
            ("reached the goal", "yes" if m["success"] else f"no ({m['reason']})"),
            ("collision-free (independent check)", "yes" if m["collision_free"] else "NO"),
            ("executed length (px)", f"{m['length_px']:.1f}"),
            ("static optimum L* (px)", f"{m['l_star_px']:.1f}"),
            ("optimality gap L / L*", f"{m['gap']:.3f}"),
            ("smoothness: total turning (rad)", f"{m['smoothness_rad']:.2f}"),
            ("minimum clearance (px)", f"{m['min_clearance_px']:.2f}"),
            ("replan latency p50 / p95 (ms)", latency),
            ("steps", str(m["steps"])),
            ("steps on a kept plan (no replan)", str(m["holds"])),
        ]


def run_demo(seed: int = 0) -> DemoRun:
    """Run the demo: MAWDO on the ``paper`` scenario with the ``realtime`` planner preset.

    Parameters
    ----------
    seed : int
        Seed of the run (>= 0); the README image is seed 0.

    Returns
    -------
    DemoRun
        The run and its metrics (minutes on a cold Numba cache, then about a minute).
    """
    return finish_demo(prepare_demo(seed).execute())


def prepare_demo(seed: int = 0):
    """The demo's run set up, not run (:func:`mawdo.planning.run.planner.prepare`): ``.execute()``
    runs it, :func:`finish_demo` measures it; :func:`run_demo` is both."""
    from mawdo.planning.run.planner import prepare

    return prepare(SCENARIO, algorithm=ALGORITHM, seed=seed, config=PRESET)


def finish_demo(result: PlanResult) -> DemoRun:
    """The demo run of an executed :func:`prepare_demo`, with its metrics."""
    from mawdo.planning.judge.metrics import run_metrics

    return DemoRun(result, run_metrics(result))


def write_figure(run: DemoRun, path) -> Path:
    """The demo's snapshot grid, with its title and caption stored as PNG text.

    Parameters
    ----------
    run : DemoRun
        From :func:`run_demo`.
    path : str or Path
        Output ``.png``; missing directories are created.

    Returns
    -------
    Path
        The written file; :func:`figure_text` reads its ``Title`` and ``Description`` back.
    """
    from mawdo.planning.render import snapshot_grid

    if Path(path).suffix.lower() != ".png":
        raise ValueError(f"the demo figure {str(path)!r} must be a .png (it stores PNG text)")
    text = figure_text_chunks(run)
    return snapshot_grid({LABEL: run.result}, path, metrics={LABEL: run.metrics}, metadata=text)


def figure_text_chunks(run: DemoRun) -> dict[str, str]:
    """The PNG text the demo's figure stores: its ``Title``, ``Description`` (the caption) and
    ``Source``. ``mawdo demo`` draws the figure with it in a process begun at its start
    (:mod:`mawdo.planning.render.early`): the same grid :func:`write_figure` draws."""
    return {"Title": run.title, "Description": run.caption, "Source": "mawdo demo"}


def figure_text(path) -> dict[str, str]:
    """The text chunks of a PNG written by :func:`write_figure` (``Title``, ``Description``)."""
    from PIL import Image

    with Image.open(path) as im:
        return dict(getattr(im, "text", {}))
