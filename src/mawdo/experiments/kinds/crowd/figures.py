"""Figures of a crowd study: rates and arrival times per setting and policy (from the store),
and one episode of every policy, re-run from its seed and drawn as a snapshot grid."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from mawdo.experiments.store import Store


def rates_title(plan, summary: dict) -> str:
    """The rates figure's title: the plan and the episodes its bars rest on (a range, and
    "incomplete", while the study is still running)."""
    counts = [m["episodes"] for m in summary.values()]
    if len(counts) == len(plan.settings) * len(plan.policies) and set(counts) == {plan.n}:
        return f"{plan.name}: {plan.n} episodes per setting"
    return (f"{plan.name}: {min(counts, default=0)}-{max(counts, default=0)} of {plan.n} "
            "episodes per setting and policy (incomplete)")  # fmt: skip


def rates_figure(store: Store, summary: dict, out: Path) -> Path:
    """Success, robot-caused collision and arrival time per setting (groups) and policy
    (bars), from :func:`~mawdo.experiments.kinds.crowd.report.crowd_summary`."""
    from mawdo.planning.render import new_figure

    plan = store.plan
    settings = [s for s in plan.settings if any((s, p) in summary for p in plan.policies)]
    fig = new_figure((max(7.0, 1.6 * len(settings) + 3), 7.5), 110)
    axes = fig.subplots(3, 1, sharex=True)
    width = 0.8 / len(plan.policies)
    x = np.arange(len(settings))
    for k, p in enumerate(plan.policies):
        for ax, key in zip(axes, ("success", "robot_caused", "time_s"), strict=True):
            v = [summary.get((s, p), {}).get(key, np.nan) for s in settings]
            ax.bar(x + (k - (len(plan.policies) - 1) / 2) * width, v, width, label=p,
                   color=f"C{k % 10}")  # fmt: skip
    axes[0].set(ylabel="success", ylim=(0, 1.05))
    axes[1].set(ylabel="robot-caused\ncollision share", ylim=(0, 1.05))
    axes[2].set(ylabel="time to goal (s)\n(successes)")
    axes[2].set_xticks(x, settings, rotation=20, ha="right")
    axes[0].legend(ncol=min(3, len(plan.policies)), fontsize=8, loc="lower left",
                   bbox_to_anchor=(0.0, 1.12))  # fmt: skip
    fig.suptitle(rates_title(plan, summary))
    for ax in axes:
        ax.grid(axis="y", alpha=0.3)
    path = out / "crowd_rates.png"
    fig.savefig(path)
    return path


def episode_figure(store: Store, out: Path, episode: int = 0) -> Path | None:
    """Episode ``episode`` of the plan's first setting, re-run with every policy that is not
    blind, as one snapshot grid per policy (``crowd_episode.png``)."""
    from mawdo.experiments.kinds.crowd.execute import run_one
    from mawdo.planning.render import snapshot_grid
    from mawdo.planning.run.policies import POLICIES

    plan = store.plan
    setting = plan.settings[0]
    results = {}
    for p in plan.policies:
        if POLICIES[p].knowledge == "none":
            continue
        spec = plan.task_spec(next(t for t in plan.tasks() if t.algorithm == p))
        spec = {**spec, "algorithm": p}
        res, _ = run_one(spec, setting, plan.episode_seed(setting, episode))
        results[f"{p} ({'ok' if res.success else 'fails'})"] = res
    if not results:
        return None
    path = out / "crowd_episode.png"
    snapshot_grid(results, path, rows=1, cols=4, optimum=False, dpi=80)
    return path
