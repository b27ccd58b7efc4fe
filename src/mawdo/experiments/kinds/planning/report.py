"""Report of a planning study (paper Table 6, Figs. 2-3), read from the store only.

Tables: our Table 6 (length, gap, smoothness of the executed route and of the first plan) beside
the paper's, plus success, collisions (independent checker), minimum clearance, latency and
evaluations; Wilcoxon rank-sum of MAWDO against each rival on length, gap and smoothness (none
for the deterministic baseline). Every sentence that states a result is generated from the store.
Figures: per algorithm the 2x4 snapshot grid of its best run, the first plan's cost convergence
(median and IQR), box plots, and an animated GIF of MAWDO's median run.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from mawdo.experiments import stats
from mawdo.experiments.kinds.planning.findings import (
    PAPER_TABLE6,
    label,
    plan_dims,
    short,
    table6_notes,
)
from mawdo.experiments.kinds.planning.plan import BASELINE, StudyPlan
from mawdo.experiments.store import Store
from mawdo.experiments.tables import Table, to_csv, to_latex, to_markdown

COMPARED = (("length_px", "length"), ("gap", "gap"), ("smoothness_rad", "smoothness"))


def study_runs(store: Store, algorithm: str | None = None, route: bool = False) -> list[dict]:
    """Stored runs of a planning study as dicts: ``algorithm, run, metrics`` (None for a failed
    run), ``error_text``, ``curve`` (first plan's convergence) and, when asked, ``route``
    (bytes of the serialised run)."""
    skip = () if route else ("route",)
    return [
        {
            "algorithm": a,
            "run": r.run,
            "metrics": r.metrics,
            "route": r.route,
            "error_text": r.error_text,
            "curve": r.first_plan_curve,
            "first_smoothness": r.first_plan_smoothness_rad,
            "dim": r.plan_dim,
        }
        for a, _, r in store.rows(algorithm, skip=skip)
    ]


def _metric(runs, key) -> np.ndarray:
    return np.array([r["metrics"][key] for r in runs if r["metrics"] is not None], dtype=float)


def study_tables(store: Store) -> list[Table]:
    """Table 6 with our extra columns, and the Wilcoxon table."""
    plan = store.plan
    if plan.kind != StudyPlan.study_kind:
        raise ValueError(
            f"{store.path} holds a {plan.kind!r} study, not a planning study; "
            f"write its report with its own command (mawdo bench report for benchmarks)"
        )
    by = {a: study_runs(store, a) for a in plan.algorithms}
    return [_table6(plan, by), _wilcoxon_table(plan, by)]


COLUMNS = {  # name -> format; the table's 19 columns in order
    "algorithm": None,
    "runs": None,
    "length (px)": ".2f",
    "std": ".2f",
    "gap L/L*": ".3f",
    "smoothness executed (rad)": ".2f",
    "smoothness first plan (rad)": ".2f",
    "paper length": ".2f",
    "paper gap": ".2f",
    "paper smooth": ".2f",
    "success": ".0%",
    "collision-free": ".0%",
    "collisions": ".2f",
    "min clearance (px)": ".2f",
    "snapshot gap": ".3f",
    "latency p50 (ms)": ".1f",
    "latency p95 (ms)": ".1f",
    "first plan (s)": ".2f",
    "nfev": ".3g",
}
NAN = float("nan")


def _table6(plan: StudyPlan, by: dict[str, list[dict]]) -> Table:
    """Our Table 6 beside the paper's, with the extra columns and generated notes."""
    main = Table(
        name="table6",
        title=f"Path planning ({plan.describe()}): ours beside the paper's Table 6, from a "
        "planner that differs from the paper's (budget, cost mode, guidance, guard: first note)",
        columns=list(COLUMNS),
        formats={k: f for k, f in COLUMNS.items() if f},
    )
    for a in plan.algorithms:
        runs = [r for r in by[a] if r["metrics"] is not None]
        main.rows.append(_table6_row(a, runs, plan_dims(by[a])))
        if len(by[a]) > len(runs):
            main.notes.append(
                f"{label(a)}: {len(by[a]) - len(runs)} runs failed (error text in the store)"
            )
    main.notes += table6_notes(plan, by)
    return main


def _table6_row(a: str, runs: list[dict], dims: tuple[int, ...]) -> list:
    ok = _metric(runs, "success").astype(bool)
    length = _metric(runs, "length_px")
    first = np.array([r["first_smoothness"] for r in runs], dtype=float)

    def mean_ok(x):  # over runs that reached the goal (a truncated run is short for no merit)
        return float(np.mean(x[ok])) if ok.any() else NAN

    def over_runs(f, key):
        return float(f(_metric(runs, key))) if runs else NAN

    return [
        label(a, dims),
        len(runs),
        mean_ok(length),
        float(np.std(length[ok], ddof=1)) if ok.sum() > 1 else NAN,
        float(np.nanmean(_metric(runs, "gap"))) if ok.any() else NAN,
        mean_ok(_metric(runs, "smoothness_rad")),
        mean_ok(first) if np.isfinite(first[ok]).all() else NAN,
        *PAPER_TABLE6.get(a, (None, None, None)),
        float(ok.mean()) if runs else NAN,
        over_runs(np.mean, "collision_free"),
        over_runs(np.mean, "collisions"),
        over_runs(np.min, "min_clearance_px"),
        over_runs(np.nanmedian, "snapshot_gap_median"),
        over_runs(np.nanmedian, "latency_p50_ms"),
        over_runs(np.nanmedian, "latency_p95_ms"),
        over_runs(np.mean, "first_plan_s"),
        over_runs(np.mean, "nfev"),
    ]


def _wilcoxon_table(plan: StudyPlan, by: dict[str, list[dict]]) -> Table:
    """Wilcoxon rank-sum of MAWDO against each rival on length, gap and smoothness."""
    from mawdo.planning.run.planners import PLANNERS

    wil = Table(
        name="table6_wilcoxon",
        title="Wilcoxon rank-sum of MAWDO (stabilised) against each rival on the runs that "
        "reached the goal (two-sided, 5%): + MAWDO significantly better, - worse, = no "
        "significant difference",
        columns=["rival", "runs", *[f"{n} p" for _, n in COMPARED], *[n for _, n in COMPARED]],
        formats={f"{n} p": ".3g" for _, n in COMPARED},
    )
    if "mawdo" in by:
        # only runs that reached the goal: a truncated run is "shorter" for the wrong reason
        ref = [r for r in by["mawdo"] if r["metrics"] and r["metrics"]["success"]]
        for a in plan.algorithms:
            if a == "mawdo" or not PLANNERS[a].seeded:  # one run of a deterministic one
                continue
            rival = [r for r in by[a] if r["metrics"] and r["metrics"]["success"]]
            runs = f"{len(ref)} / {len(rival)}"
            if not (ref and rival):  # no test without runs on both sides: say so, not "="
                wil.rows.append([short(a), runs, *[NAN] * len(COMPARED), *["n/a"] * len(COMPARED)])
                continue
            res = [
                stats.ranksum(_finite(_metric(ref, k)), _finite(_metric(rival, k)))
                for k, _ in COMPARED
            ]
            wil.rows.append([short(a), runs, *[r.pvalue for r in res], *[r.sign for r in res]])
        wil.notes.append("runs: runs that reached the goal, MAWDO (stabilised) / rival.")
        if BASELINE in by:
            wil.notes.append("The oracle follower is deterministic (one run): no test.")
    return wil


def _finite(x):
    return x[np.isfinite(x)]


def _pick(runs, how: str):
    ok = [r for r in runs if r["metrics"] and r["metrics"]["success"]]
    pool = ok or [r for r in runs if r["metrics"]]
    if not pool:
        return None
    lengths = np.array([r["metrics"]["length_px"] for r in pool])
    if how == "best":
        safe = [r for r in pool if r["metrics"]["collision_free"]] or pool
        return min(safe, key=lambda r: r["metrics"]["length_px"])
    return pool[int(np.argsort(lengths)[len(lengths) // 2])]


def study_figures(store: Store, out: Path, gif: bool = True) -> list[Path]:
    """Every figure of the study, from stored runs only."""
    from mawdo.planning import render
    from mawdo.planning.run.planners import PLANNERS
    from mawdo.planning.run.result import result_from_bytes

    plan = store.plan
    sc = plan.scenario_object()
    figs = []
    best, curves, boxes = {}, {}, {k: {} for k, _ in COMPARED}
    for a in plan.algorithms:
        runs = study_runs(store, a, route=True)
        lab = label(a, plan_dims(runs))
        pick = _pick(runs, "best")
        if pick is not None:
            best[a] = (lab, result_from_bytes(pick["route"], sc), pick["metrics"])
        c = [r["curve"] for r in runs if r["metrics"] and r["curve"].size]
        if c and PLANNERS[a].optimizer is not None:  # an optimizer's convergence
            T = max(len(x) for x in c)
            curves[lab] = np.stack([np.pad(x, (0, T - len(x)), mode="edge") for x in c])
        for k, _ in COMPARED:
            boxes[k][short(a)] = _metric([r for r in runs if r["metrics"]], k)
    for a, (lab, res, m) in best.items():
        # files are named by the study key: labels carry spaces and D
        figs.append(render.snapshot_grid({lab: res}, out / f"snapshots_{a}.png", metrics={lab: m}))
    if curves:
        figs.append(render.plot_cost_convergence(curves, out / "cost_convergence.png"))
    names = {
        "length_px": "executed length (px)",
        "gap": "gap L / L*",
        "smoothness_rad": "total turning (rad)",
    }
    for k, _ in COMPARED:
        # a metric no run has (the gap when no run reached the goal) gets no figure
        if any(np.isfinite(np.asarray(v, dtype=float)).any() for v in boxes[k].values()):
            figs.append(render.plot_metric_boxes(boxes[k], out / f"box_{k}.png", names[k]))
    if gif and "mawdo" in plan.algorithms:
        pick = _pick(study_runs(store, "mawdo", route=True), "median")
        if pick is not None:
            figs.append(
                render.animate(
                    result_from_bytes(pick["route"], sc), out / "mawdo_median_run.gif", every=2
                )
            )
    return figs


def write_study_report(store_path, out_dir, *, figures: bool = True, gif: bool = True) -> Path:
    """Tables (Markdown, LaTeX, CSV) and figures of a study store into ``out_dir``; returns the
    Markdown report's path."""
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    with Store.read(store_path) as store:
        tables = study_tables(store)
        figs = study_figures(store, out, gif=gif) if figures else []
        plan = store.plan
    for t in tables:
        (out / f"{t.name}.md").write_text(to_markdown(t))
        (out / f"{t.name}.tex").write_text(to_latex(t, label=f"tab:{t.name}"))
        (out / f"{t.name}.csv").write_text(to_csv(t))
    md = [f"# Path-planning study: {plan.name}", "", plan.describe(), ""]
    md += [to_markdown(t) for t in tables]
    if figs:
        md.append("## Figures\n")
        md += [f"![{p.stem}]({p.name})\n" for p in figs]
    path = out / "study.md"
    path.write_text("\n".join(md))
    return path
