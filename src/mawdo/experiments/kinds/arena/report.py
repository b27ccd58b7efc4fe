"""Report of a planning arena, read from its store only (no scene is generated, no run redone).

- ``arena.md/.tex/.csv``: per family and planner the success rate, collision rate (independent
  checker), gap L/L* median / p90 / max over successful runs, replan latency p95 / p99 and
  time to first plan; rejected scenes and planner errors are counted apart.
- ``swarm_share.md/.tex/.csv``: each optimizer-driven planner against ``guide_only`` per family,
  paired on the scenes both solve, with a Wilcoxon signed-rank test and Holm's correction
  (:mod:`mawdo.experiments.kinds.arena.share`).
- ``ecdf_runtime.png`` (wall time per run, all families) and ``ecdf_gap.png`` (one panel per
  family, T/T* on timed families), one line per planner; ``swarm.png``, the swarm's share over
  the guide alone (:mod:`mawdo.experiments.kinds.arena.figures`).
- ``gallery/``: one snapshot image per failed or colliding run, named after its scene, and
  ``scenes/``: the TOML file of each of those scenes (``mawdo plan scenes/<name>.toml``).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from mawdo.experiments.kinds.arena.execute import NO_TRACE, scenario_from_toml
from mawdo.experiments.kinds.arena.figures import arena_figures, swarm_figure
from mawdo.experiments.kinds.arena.figures import label as _label
from mawdo.experiments.kinds.arena.plan import ArenaPlan
from mawdo.experiments.progress import say
from mawdo.experiments.store import Store
from mawdo.experiments.tables import Table, to_csv, to_latex, to_markdown

COLUMNS = [
    "family",
    "planner",
    "sees time",
    "scenes",
    "rejected",
    "errors",
    "success",
    "collisions",
    "gap median",
    "gap p90",
    "gap max",
    "T/T* median",
    "T/T* p95",
    "active",
    "latency p95 (ms)",
    "latency p99 (ms)",
    "first plan (s)",
]


def _q(x: np.ndarray, q: float) -> float:
    return float(np.percentile(x, q)) if x.size else float("nan")


def cell_numbers(rows: list) -> dict[str, float]:
    """The table's numbers for one (family, planner) from its stored rows.

    Rates are over planned scenes (``status == "ok"``) plus runs that raised; rejected scenes
    count in no rate. Gap statistics are over successful runs; latencies are medians over runs
    of each run's p95 / p99 (runs with replans only).
    """
    planned = [r for r in rows if r.status == "ok" or r.error_text is not None]
    ok = [r for r in planned if r.error_text is None]
    n = len(planned)
    gaps = np.array([r.gap for r in ok if r.success], dtype=float)
    p95 = np.array([r.latency_p95_ms for r in ok if r.latency_p95_ms is not None], dtype=float)
    p99 = np.array([r.latency_p99_ms for r in ok if r.latency_p99_ms is not None], dtype=float)
    first = np.array([r.first_plan_s for r in ok if r.first_plan_s is not None], dtype=float)
    tgaps = np.array([r.time_gap for r in ok if r.success and r.time_gap is not None], float)
    timed = [r for r in ok if r.active_collisions is not None]
    return {
        "scenes": n,
        "rejected": sum(r.status == "rejected" for r in rows),
        "errors": n - len(ok),
        "success": sum(bool(r.success) for r in ok) / n if n else float("nan"),
        "collisions": sum(r.collision_free == 0 for r in ok) / n if n else float("nan"),
        "gap median": _q(gaps, 50),
        "gap p90": _q(gaps, 90),
        "gap max": float(gaps.max()) if gaps.size else float("nan"),
        "T/T* median": _q(tgaps, 50),
        "T/T* p95": _q(tgaps, 95),
        "active": sum(r.active_collisions for r in timed) if timed else float("nan"),
        "latency p95 (ms)": float(np.median(p95)) if p95.size else float("nan"),
        "latency p99 (ms)": float(np.median(p99)) if p99.size else float("nan"),
        "first plan (s)": float(np.median(first)) if first.size else float("nan"),
    }


def _plan_of(store: Store) -> ArenaPlan:
    plan = store.plan
    if plan.kind != ArenaPlan.study_kind:
        raise ValueError(
            f"{store.path} holds a {plan.kind!r} study, not a planning arena; write its report "
            "with its own command (mawdo bench report, mawdo plan report)"
        )
    return plan


def arena_tables(store: Store) -> list[Table]:
    """The per family and planner table (one row each, in plan order)."""
    from mawdo.planning.run.planners import PLANNERS, PREDICTED

    plan = _plan_of(store)
    t = Table(
        name="arena",
        title=f"Planning arena ({plan.describe()})",
        columns=COLUMNS,
        formats={
            "success": ".0%",
            "collisions": ".0%",
            "gap median": ".3f",
            "gap p90": ".3f",
            "gap max": ".3f",
            "T/T* median": ".3f",
            "T/T* p95": ".3f",
            "active": ".0f",
            "latency p95 (ms)": ".1f",
            "latency p99 (ms)": ".1f",
            "first plan (s)": ".3f",
        },
    )
    for fam in plan.families:
        for p in plan.planners:
            rows = [r for _, _, r in store.rows(p, fam, skip=NO_TRACE)]
            num = cell_numbers(rows)
            sees = PLANNERS[p].sees_time if p in PLANNERS else "?"
            sees = "yes" if sees == PREDICTED else sees
            t.rows.append([fam, _label(p), sees, *[num[c] for c in COLUMNS[3:]]])
    t.notes.append(
        "success = goal reached and the independent checker approves the executed route; "
        "collisions = runs whose route the checker rejects (space and time, moving obstacles "
        "included); gap = executed length / exact static optimum L*, over successful runs; "
        "T/T* = arrival step / earliest arrival T* (timed families only), over successful runs; "
        "active = the checker's collisions with the robot moving, summed over all runs (timed "
        "families only); "
        "latency = median over runs of each run's replan p95 / p99 (receding-horizon planners "
        "only); first plan = median wall time of the first plan (single shot for baselines)."
    )
    t.notes.append(
        "Sees time: our planner predicts obstacle motion; the oracle follower replans every "
        "step on obstacles frozen where they are; straight and OMPL (single shot, static "
        "obstacles only) do not see moving obstacles at all. Rejected scenes (no valid draw) "
        "count in no rate. OMPL runs are time-budgeted and not seeded: not reproducible."
    )
    return [t]


def first_collision_time(result) -> float | None:
    """Time (time steps, to 0.5) of the first checker-rejected contact of a run's route."""
    from mawdo.planning.judge.check import check_trajectory

    times = result.route_times
    if result.route is None or times is None or len(times) < 2:
        return None
    ts = np.append(np.arange(0.0, times[-1], 0.5), times[-1])
    pts = np.column_stack([np.interp(ts, times, result.route[:, i]) for i in (0, 1)])
    rep = check_trajectory(pts, result.scenario, times=ts)
    steps = [k for k, _ in rep.collisions] + list(rep.border)
    return float(ts[min(steps)]) if steps else None


def _gallery_times(result) -> np.ndarray | None:
    """Start, shortly before and at the first collision, and the end (None: even spacing)."""
    t_c = first_collision_time(result)
    if t_c is None:
        return None
    end = float(result.route_times[-1])
    return np.unique(np.round([0.0, max(0.0, t_c - 8.0), t_c, end], 1))


def failure_gallery(store: Store, out: Path, limit: int | None = None) -> list[tuple[str, str]]:
    """One snapshot image per failed or colliding run, and the TOML of its scene.

    Returns ``(image file, scene file)`` pairs relative to ``out``; ``limit`` caps the images.
    """
    from mawdo.planning import render
    from mawdo.planning.run.result import result_from_bytes

    plan = _plan_of(store)
    items = []
    # planner-major: our planners' failures come first when ``limit`` cuts the gallery
    for p in plan.planners:
        for f in plan.families:
            for _, _, r in store.rows(p, f):
                if r.status != "ok" or r.trace is None:
                    continue
                if limit is not None and len(items) >= limit:
                    return items
                cap = f" of at most {limit}" if limit else ""
                say(f"failure gallery: image {len(items) + 1}{cap}")
                sc = scenario_from_toml(r.scene_toml, r.scene_name)
                scene_file = Path("scenes") / f"{r.scene_name}.toml"
                (out / scene_file).parent.mkdir(parents=True, exist_ok=True)
                (out / scene_file).write_text(r.scene_toml, encoding="utf-8")
                res = result_from_bytes(r.trace, sc)
                img = Path("gallery") / f"{r.scene_name}__{p}.png"
                why = "collides" if r.collision_free == 0 else f"failed: {r.reason}"
                render.snapshot_grid(
                    {f"{_label(p)} on {r.scene_name} ({why})": res},
                    out / img,
                    times=_gallery_times(res) if r.collision_free == 0 else None,
                    rows=1,
                    cols=4,
                    dpi=80,
                )
                items.append((str(img), str(scene_file)))
    return items


def write_arena_report(
    store_path, out_dir, *, figures: bool = True, gallery_limit: int | None = 200, worst: int = 3
) -> Path:
    """Tables (Markdown, LaTeX, CSV), headline sentences (``summary.md``), ECDFs, the failure
    gallery and the ``worst`` worst scenes of MAWDO (re-run, see
    :func:`mawdo.experiments.kinds.arena.summary.render_worst`) into ``out_dir``; returns the
    Markdown report's path."""
    from mawdo.experiments.kinds.arena.share import share_table
    from mawdo.experiments.kinds.arena.summary import headline, render_worst

    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    with Store.read(store_path) as store:
        plan = _plan_of(store)
        say("tables and sentences")
        tables = arena_tables(store)
        tables += [t for t in [share_table(store)] if t is not None]
        summary = headline(store)
        say("ECDFs and the swarm's share")
        figs = arena_figures(store, out) if figures else []
        figs += swarm_figure(store, out) if figures else []
        gallery = failure_gallery(store, out, gallery_limit) if figures else []
        rejected = [
            (f, r.run, r.reason)
            for f in plan.families
            for _, _, r in store.rows(None, f, skip=NO_TRACE)
            if r.status == "rejected"
        ]
        errors = [
            (a, f, r.run, r.error_text) for a, f, r in store.rows(skip=NO_TRACE) if r.error_text
        ]
        n_bad = sum(
            r.status == "ok" and not (r.success and r.collision_free)
            for _, _, r in store.rows(skip=NO_TRACE)
        )
    for t in tables:
        (out / f"{t.name}.md").write_text(to_markdown(t))
        (out / f"{t.name}.tex").write_text(to_latex(t, label=f"tab:{t.name}"))
        (out / f"{t.name}.csv").write_text(to_csv(t))
    if summary:
        (out / "summary.md").write_text("\n".join(summary) + "\n", encoding="utf-8")
    md = [f"# Planning arena: {plan.name}", "", plan.describe(), "", *summary, ""]
    md += [to_markdown(t) for t in tables]
    shown = render_worst(store_path, out, "mawdo", worst) if figures and worst else []
    if shown:
        md.append(f"\n## The {len(shown)} worst runs of mawdo (re-run from the stored scene)\n")
        for w in shown:
            ok = w["success"] and w["collision_free"]
            kind = "T/T*" if w["timed"] else "L/L*"
            verdict = f"succeeds, gap {kind} {w['gap']:.3f}" if ok else "fails (no gap)"
            md.append(f"- {w['family']}, `{w['scene_file']}`: {verdict}\n")
            md.append(f"  ![{Path(w['image']).stem}]({w['image']})\n")
    md += [f"![{p.stem}]({p.name})\n" for p in figs]
    if rejected:
        md.append("## Rejected scenes (not planner failures)\n")
        md += [f"- {f} scene {k}: {why}" for f, k, why in sorted(set(rejected))]
    if errors:
        md.append("\n## Runs that raised\n")
        md += [f"- {a} on {f} scene {k}: {e}" for a, f, k, e in errors]
    if gallery:
        md.append(f"\n## Failure gallery ({len(gallery)} of {n_bad} failed or colliding runs)\n")
        md.append("Re-run a scene alone: `mawdo plan scenes/<name>.toml -a <algorithm>`.\n")
        md += [f"- `{s}`\n\n  ![{Path(i).stem}]({i})\n" for i, s in gallery]
    path = out / "arena.md"
    path.write_text("\n".join(md))
    return path
