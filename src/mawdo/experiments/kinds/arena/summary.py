"""Headline sentences and worst scenes of a planning arena, generated from its store.

The README quotes the sentences verbatim (``summary.md``; a test checks the quote), so every
claim about the planner's success, collisions and optimality gap is a number of stored runs.
The worst scenes of a planner are its failed or colliding runs first, then its largest gaps;
their images are drawn by re-running the planner on the stored scene with the stored seed (the
store keeps traces of failures only), and the re-run must give the stored verdict and gap, so
an image can never show a different run from the one the table counts.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from mawdo.experiments.kinds.arena.rows import judged_gap, ok_rows, timed_families
from mawdo.experiments.progress import say
from mawdo.experiments.store import Store

GAP_NOTE = (
    "- Gap: arrival time over the earliest arrival (T/T*) on the timed families, route length "
    "over the exact static optimum (L/L*) on the others; over successful runs."
)


def _rates(rows: list) -> tuple[float, float, float]:
    n = len(rows)
    succ = sum(bool(r.success) for r in rows) / n
    coll = sum(r.collision_free == 0 for r in rows) / n
    gaps = [judged_gap(r) for r in rows if r.success]
    return succ, coll, float(np.median(gaps)) if gaps else float("nan")


def _gap(g: float) -> str:
    return "no successful run" if np.isnan(g) else f"median gap {g:.3f}"


def headline(store: Store) -> list[str]:
    """Sentences (Markdown list items) about every planner of the arena, from stored rows.

    Per planner over all families: success and collision rates, median gap (`judged_gap`);
    and the family where it succeeds least (ties: the largest median gap).
    """
    from mawdo.experiments.kinds.arena.share import swarm_share

    plan = store.plan
    lines = [GAP_NOTE] if timed_families(store) else []
    for p in plan.planners:
        rows = ok_rows(store, p)
        if not rows:
            continue
        succ, coll, gap = _rates(rows)
        per_fam = {f: _rates(ok_rows(store, p, f)) for f in plan.families if ok_rows(store, p, f)}
        worst = min(per_fam, key=lambda f: (per_fam[f][0], -np.nan_to_num(per_fam[f][2])))
        ws, _, wg = per_fam[worst]
        lines.append(
            f"- {p}: {100 * succ:.1f} % success and {100 * coll:.1f} % colliding runs over "
            f"{len(rows)} scenes, {_gap(gap)}; weakest family {worst} "
            f"({100 * ws:.0f} % success, {_gap(wg)})."
        )
    return lines + timed_lines(store) + strengths(store) + swarm_share(store)


def timed_lines(store: Store) -> list[str]:
    """Per planner that sees time, on the timed families together: success over the scenes
    with a ``T*``, active collisions (the robot moving) in all runs, successful or not, and
    the arrival-time gap T/T* median and p95; then its weakest timed family."""
    from mawdo.planning.run.planners import PLANNERS, PREDICTED

    fams = timed_families(store)
    if not fams:
        return []
    lines = []
    for p in store.plan.planners:
        if p not in PLANNERS or PLANNERS[p].sees_time != PREDICTED:
            continue
        per = {f: ok_rows(store, p, f) for f in fams}
        rows = [r for f in fams for r in per[f]]
        if not rows:
            continue
        active = sum(r.active_collisions or 0 for r in rows)
        tg = np.array([r.time_gap for r in rows if r.success], dtype=float)
        stats = (
            f"T/T* median {np.median(tg):.3f}, p95 {np.percentile(tg, 95):.3f}"
            if tg.size
            else ("no successful run")
        )
        succ = {f: sum(bool(r.success) for r in per[f]) / len(per[f]) for f in fams if per[f]}
        worst = min(succ, key=lambda f: (succ[f], -_median_time_gap(per[f])))
        lines.append(
            f"- {p} on the {len(fams)} timed families ({', '.join(fams)}): "
            f"{100 * sum(bool(r.success) for r in rows) / len(rows):.1f} % success over "
            f"{len(rows)} scenes with an earliest arrival T*, {active} active collisions, "
            f"{stats}; weakest family {worst} ({100 * succ[worst]:.0f} % success, "
            f"T/T* median {_median_time_gap(per[worst]):.3f}){_early(tg)}."
        )
    return lines


def _early(tg: np.ndarray) -> str:
    """T* is exact over roadmap routes with waits at roadmap vertices, an upper bound of the
    free-space optimum: say how often and how far a run arrived before it."""
    early = tg[tg < 1.0]
    if not early.size:
        return ""
    return (
        f"; {early.size} runs arrived before T* (lowest T/T* {early.min():.3f}: T* is the "
        "earliest arrival over the roadmap, an upper bound of the free-space optimum)"
    )


def _median_time_gap(rows: list) -> float:
    g = [r.time_gap for r in rows if r.success and r.time_gap is not None]
    return float(np.median(g)) if g else float("nan")


def strengths(store: Store) -> list[str]:
    """Where our planner is good and where it is weak, as sentences of stored numbers.

    Against each baseline that does not see time: our planners' success and median gap on the
    scenes where that baseline's route collides. Then per optimizer its largest gap (and
    family), and the range over families of the median per-run replan latency p95 (wall time
    of the machine that filled the store).
    """
    plan = store.plan
    ours = [a for a in plan.algorithms if ok_rows(store, a)]
    if not ours:
        return []
    by_scene = {a: {r.scene_name: r for r in ok_rows(store, a)} for a in ours}
    lines = []
    for b in plan.baselines:
        hit = {r.scene_name for r in ok_rows(store, b) if r.collision_free == 0}
        if not hit:
            continue
        parts = []
        for a in ours:
            rows = [by_scene[a][n] for n in hit if n in by_scene[a]]
            succ, _, gap = _rates(rows) if rows else (float("nan"), 0.0, float("nan"))
            parts.append(f"{a} {100 * succ:.0f} % success, {_gap(gap)}")
        lines.append(
            f"- On the {len(hit)} scenes where {b}'s route collides: " + "; ".join(parts) + "."
        )
    worst, lat = [], []
    for a in ours:
        gaps = [
            (judged_gap(r), f) for f in plan.families for r in ok_rows(store, a, f) if r.success
        ]
        if gaps:
            g, f = max(gaps)
            worst.append(f"{a} {g:.3f} ({f})")
        meds = [
            float(np.median(v))
            for f in plan.families
            if (
                v := [
                    r.latency_p95_ms for r in ok_rows(store, a, f) if r.latency_p95_ms is not None
                ]
            )
        ]
        if meds:
            lat.append(f"{a} {min(meds):.1f}-{max(meds):.1f} ms")
    if worst:
        lines.append("- Largest gap of a successful run: " + ", ".join(worst) + ".")
    if lat:
        lines.append(
            "- Replan latency p95, median over a family's scenes, lowest-highest family: "
            + ", ".join(lat)
            + " (wall time on the machine that ran the study)."
        )
    return lines


def worst_runs(store: Store, planner: str, k: int = 3) -> list[tuple[str, object]]:
    """The ``k`` worst runs of ``planner`` as ``(family, row)``: failures, then the largest
    gaps (`judged_gap`)."""

    def badness(item):
        _, r = item
        failed = not (r.success and r.collision_free)
        g = judged_gap(r)
        return (not failed, -(g if g is not None and np.isfinite(g) else np.inf))

    items = [(f, r) for f in store.plan.families for r in ok_rows(store, planner, f)]
    return sorted(items, key=badness)[:k]


def render_worst(store_path, out_dir, planner: str = "mawdo", k: int = 3) -> list[dict]:
    """Re-run and draw the ``k`` worst runs of ``planner``; returns one dict per run.

    Each dict has ``family``, ``scene``, ``image`` (relative to ``out_dir``), ``scene_file``,
    ``success``, ``collision_free``, ``gap``. Raises ``RuntimeError`` if a re-run does not
    reproduce the stored verdict and gap (the scene or the planner changed since the study).
    """
    from mawdo.experiments.kinds.arena.execute import plan_scene, scenario_from_toml
    from mawdo.planning import render

    out = Path(out_dir)
    (out / "worst").mkdir(parents=True, exist_ok=True)
    made = []
    with Store.read(store_path) as store:
        ap = store.plan
        if planner not in ap.algorithms:
            return []
        for i, (fam, r) in enumerate(worst_runs(store, planner, k)):
            say(f"re-running {planner}'s worst scene {i + 1} of {k} ({r.scene_name})")
            full = next(x for _, _, x in store.rows(planner, fam) if x.run == r.run)
            sc = scenario_from_toml(full.scene_toml, r.scene_name)
            res, m = plan_scene(planner, sc, r.l_star, r.planner_seed, ap.planner, ap.overrides,
                                t_star=r.t_star)  # fmt: skip
            same_gap = (np.isnan(m["gap"]) and not r.success) or (
                np.isclose(m["gap"], r.gap)
                and (r.t_star is None or np.isclose(m["time_gap"], r.time_gap))
            )
            if m["success"] != r.success or m["collision_free"] != r.collision_free or not same_gap:
                raise RuntimeError(
                    f"re-running {planner} on {r.scene_name} gave success={m['success']}, "
                    f"gap={m['gap']}, stored success={r.success}, gap={r.gap}: the planner or "
                    "the scene changed since the study; re-run the study"
                )
            img = Path("worst") / f"{r.scene_name}__{planner}.png"
            scene_file = Path("worst") / f"{r.scene_name}.toml"
            (out / scene_file).write_text(full.scene_toml, encoding="utf-8")
            gap = (
                f"{'T/T*' if r.t_star is not None else 'L/L*'} {judged_gap(r):.3f}"
                if r.success and r.collision_free
                else "failed"
            )
            render.snapshot_grid({f"{planner} on {r.scene_name} ({gap})": res}, out / img,
                                 rows=1, cols=4, dpi=80)  # fmt: skip
            made.append({"family": fam, "scene": r.scene_name, "image": str(img),
                         "scene_file": str(scene_file), "success": bool(r.success),
                         "collision_free": bool(r.collision_free), "gap": judged_gap(r),
                         "timed": r.t_star is not None})  # fmt: skip
    return made
