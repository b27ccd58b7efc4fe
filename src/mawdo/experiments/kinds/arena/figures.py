"""Figures of a planning arena, read from its store: runtime and gap ECDFs, and the swarm's
measured contribution over the same planner with its optimizer switched off (``guide_only``)."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from mawdo.experiments.kinds.arena.execute import NO_TRACE, is_timed
from mawdo.experiments.store import Store


def label(name: str) -> str:
    """A planner's display name (an optimizer's, else the planner's own)."""
    from mawdo.optimizers import OPTIMIZERS

    return OPTIMIZERS[name].display if name in OPTIMIZERS else name


def _ecdf(ax, x: np.ndarray, label: str, color: str) -> None:
    x = np.sort(x[np.isfinite(x)])
    if x.size:  # starts at 0 on the left of the smallest value, so one run is a visible step
        y = np.arange(0, x.size + 1) / x.size
        ax.step(np.concatenate([x[:1], x]), y, where="post", label=label, color=color)


def arena_figures(store: Store, out: Path) -> list[Path]:
    """Runtime ECDF (all families) and gap ECDF (one panel per family), from stored rows."""
    from matplotlib.lines import Line2D
    from matplotlib.ticker import MaxNLocator

    from mawdo.planning.render import new_figure

    plan = store.plan
    rows = {
        (a, f): [r for _, _, r in store.rows(a, f, skip=NO_TRACE)]
        for a in plan.planners
        for f in plan.families
    }
    # one colour per planner in every panel, whether or not it has data there
    colors = {p: f"C{i % 10}" for i, p in enumerate(plan.planners)}
    fig = new_figure((7, 4.5), 120)
    ax = fig.add_subplot()
    for p in plan.planners:
        w = np.array(
            [
                r.wall_time
                for f in plan.families
                for r in rows[p, f]
                if r.status == "ok" and r.wall_time
            ],
            dtype=float,
        )
        _ecdf(ax, w, label(p), colors[p])
    ax.set(
        xscale="log",
        xlabel="wall time per run (s)",
        ylabel="fraction of runs",
        title="Runtime ECDF, all families",
    )
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    paths = [out / "ecdf_runtime.png"]
    fig.savefig(paths[0])
    nf = len(plan.families)
    cols = min(nf, 3)
    nrows = -(-nf // cols)
    fig = new_figure((4 * cols, 3.2 * nrows + 0.4), 110)
    axes = np.atleast_1d(fig.subplots(nrows, cols, squeeze=False)).ravel()
    for ax, f in zip(axes, plan.families, strict=False):
        timed = all(
            r.t_star is not None for p in plan.planners for r in rows[p, f] if r.status == "ok"
        )
        key, what = ("time_gap", "T / T*") if timed else ("gap", "L / L*")
        for p in plan.planners:
            ok = [r for r in rows[p, f] if r.status == "ok" and r.success]
            _ecdf(ax, np.array([getattr(r, key) for r in ok], float), label(p), colors[p])
        if not ax.lines:
            ax.text(0.5, 0.5, "no successful run", ha="center", transform=ax.transAxes)
        ax.set(title=f, xlabel=f"gap {what} (successful runs)", ylabel="fraction")
        ax.ticklabel_format(axis="x", useOffset=False)
        ax.xaxis.set_major_locator(MaxNLocator(4))
        ax.grid(alpha=0.3)
    for ax in axes[nf:]:
        ax.set_visible(False)
    handles = [Line2D([], [], color=colors[p], label=label(p)) for p in plan.planners]
    fig.legend(handles=handles, loc="outside lower center", ncols=min(6, len(handles)))
    paths.append(out / "ecdf_gap.png")
    fig.savefig(paths[1])
    return paths


def swarm_figure(store: Store, out: Path, base: str = "guide_only") -> list[Path]:
    """``swarm.png``: per family, the median and 10-90 % range of the gap (L/L* on static
    families, T/T* on timed ones) of each optimizer-driven planner and of ``base`` (the same
    planner without its optimizer), over the scenes all of them solve; empty without ``base``."""
    from mawdo.planning.render import new_figure

    plan = store.plan
    if base not in plan.planners or not plan.algorithms:
        return []
    who = [*plan.algorithms, base]
    fig = new_figure((max(7.0, 0.75 * len(plan.families) + 2), 4.2), 120)
    ax = fig.add_subplot()
    width = 0.8 / len(who)
    for j, p in enumerate(who):
        xs, med, lo, hi = [], [], [], []
        for i, f in enumerate(plan.families):
            rows = {q: {r.scene_name: r for _, _, r in store.rows(q, f, skip=NO_TRACE)
                        if r.status == "ok" and r.success} for q in who}  # fmt: skip
            both = set.intersection(*(set(v) for v in rows.values()))
            if not both:
                continue
            key = "time_gap" if is_timed(rows[p].values()) else "gap"
            g = np.array([getattr(rows[p][n], key) for n in sorted(both)], float)
            xs.append(i - 0.4 + width * (j + 0.5))
            med.append(np.median(g))
            lo.append(np.median(g) - np.percentile(g, 10))
            hi.append(np.percentile(g, 90) - np.median(g))
        style = {"marker": "s", "color": "0.3"} if p == base else {"marker": "o", "color": f"C{j}"}
        ax.errorbar(xs, med, yerr=[lo, hi], ls="none", capsize=2, label=label(p), **style)
    ax.set_xticks(range(len(plan.families)), plan.families, rotation=30, ha="right")
    ax.set(ylabel="gap (L/L* static, T/T* timed), median and 10-90 %",
           title=f"The swarm's share: each optimizer against {base} (no optimizer)")  # fmt: skip
    ax.ticklabel_format(axis="y", useOffset=False)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    path = out / "swarm.png"
    fig.savefig(path)
    return [path]
