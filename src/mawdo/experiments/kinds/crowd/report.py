"""The crowd study's report: one table, a row per (setting, policy), CrowdNav's metrics.

Rates are shares of the episodes that ran; time to goal is the mean over successes (seconds);
discomfort the mean share of steps closer than 0.2 m to a person; latency the median over
episodes of each episode's p50 / p95 decision time (wall time of the policy's ``act``).
Every policy meets the same people (common random numbers), so the columns compare directly;
and since episode ``k`` of a setting is the same crowd for every policy, each
optimizer-driven policy (``mawdo``, and ``woa``, ``gwo``, ``wdo_plus`` when the plan has them)
is compared with ``guide_only`` (the same planner with its optimizer switched off) episode by
episode in ``crowd_share`` (:func:`crowd_share_table`): paired Wilcoxon signed-rank tests of
time to goal and discomfort on the episodes both succeed, Holm over a policy's settings
(:mod:`mawdo.experiments.kinds.arena.share`).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from mawdo.experiments.progress import say
from mawdo.experiments.store import Store
from mawdo.experiments.tables import Table, to_csv, to_latex, to_markdown

COLUMNS = [
    "setting", "policy", "episodes", "success", "robot-caused", "collision", "timeout",
    "time (s)", "discomfort", "min sep. (m)", "length (m)", "p50 (ms)", "p95 (ms)",
]  # fmt: skip


def _mean(xs) -> float:
    xs = [x for x in xs if x is not None]
    return float(np.mean(xs)) if xs else float("nan")


def _median(xs) -> float:
    xs = [x for x in xs if x is not None]
    return float(np.median(xs)) if xs else float("nan")


def crowd_summary(store: Store) -> dict[tuple[str, str], dict[str, float]]:
    """Per ``(setting, policy)``: episodes and the report's aggregates (floats; NaN where no
    episode gives the value)."""
    plan = store.plan
    rows: dict[tuple[str, str], list] = {}
    for a, s, r in store.rows():
        if r.status == "ok":
            rows.setdefault((s, a), []).append(r)
    out = {}
    for s in plan.settings:
        for p in plan.policies:
            rs = rows.get((s, p), [])
            if not rs:
                continue
            out[(s, p)] = {
                "episodes": len(rs),
                "success": _mean(r.success for r in rs),
                "robot_caused": _mean(r.robot_caused for r in rs),
                "collision": _mean(r.collision for r in rs),
                "timeout": _mean(r.timeout for r in rs),
                "time_s": _mean(r.time_s for r in rs),
                "discomfort": _mean(r.discomfort for r in rs),
                "min_separation_m": _median(r.min_separation_m for r in rs),
                "length_m": _mean(r.length_m for r in rs),
                "latency_p50_ms": _median(r.latency_p50_ms for r in rs),
                "latency_p95_ms": _median(r.latency_p95_ms for r in rs),
            }
    return out


def crowd_headline(store: Store) -> list[str]:
    """One sentence per setting (Markdown bullets), from the stored rows: each policy observing
    the people beside the oracle-fed upper bound and the baselines."""
    summary = crowd_summary(store)
    plan = store.plan
    out = []
    for s in plan.settings:
        here = {p: summary[(s, p)] for p in plan.policies if (s, p) in summary}
        if not here:
            continue
        parts = []
        for p, m in here.items():
            part = (f"{p} {100 * m['success']:.1f} % success, {100 * m['robot_caused']:.1f} % "
                    f"robot-caused collisions")  # fmt: skip
            if np.isfinite(m["time_s"]):
                part += f", {m['time_s']:.2f} s to the goal"
            parts.append(part)
        counts = {p: m["episodes"] for p, m in here.items()}
        out.append(f"- {s}, {episodes_phrase(counts)}: " + "; ".join(parts) + ".")
    return out


def episodes_phrase(counts: dict[str, int]) -> str:
    """How many episodes each policy's figures of a setting rest on: ``"500 episodes"``, or,
    in a study still running, the count most policies have and the policies that differ
    (``"50 episodes (mawdo 90; the study is incomplete)"``)."""
    values = list(counts.values())
    common = max(set(values), key=lambda n: (values.count(n), n))
    odd = [f"{p} {n}" for p, n in counts.items() if n != common]
    if not odd:
        return f"{common} episodes"
    return f"{common} episodes ({', '.join(odd)}; the study is incomplete)"


def crowd_table(store: Store) -> Table:
    """The report's table (see the module docstring)."""
    keys = [
        "episodes", "success", "robot_caused", "collision", "timeout", "time_s",
        "discomfort", "min_separation_m", "length_m", "latency_p50_ms", "latency_p95_ms",
    ]  # fmt: skip
    rows = [[s, p, *(m[k] for k in keys)] for (s, p), m in crowd_summary(store).items()]
    fmts = {c: ".3f" for c in [*COLUMNS[3:7], "discomfort", "min sep. (m)"]}
    fmts |= {"time (s)": ".2f", "length (m)": ".2f", "p50 (ms)": ".1f", "p95 (ms)": ".1f"}
    return Table(
        name="crowd", title="Crowd navigation (CrowdNav settings)", columns=COLUMNS, rows=rows,
        formats=fmts,
        notes=["rates are shares of episodes; time over successes; min sep. is the median "
               "over episodes of the smallest clearance (negative: contact)"],
    )  # fmt: skip


SHARE_COLUMNS = [
    "policy", "setting", "pairs", "success", "{b} success", "robot-caused", "{b} robot-caused",
    "time (s)", "{b} time (s)", "time p", "time p Holm", "time verdict", "discomfort",
    "{b} discomfort", "discomfort p", "discomfort p Holm", "discomfort verdict",
]  # fmt: skip


def share_policies(plan, base: str = "guide_only") -> list[str]:
    """The plan's optimizer-driven policies that observe as ``base`` does (MAWDO and the
    other swarms in its place: each is ``base`` with an optimizer), in plan order."""
    from mawdo.optimizers import OPTIMIZERS
    from mawdo.planning.run.policies import POLICIES

    if base not in POLICIES:
        return []
    know = POLICIES[base].knowledge
    swarms = [p for p in plan.policies if p != base and p in OPTIMIZERS and p in POLICIES]
    return [p for p in swarms if POLICIES[p].knowledge == know]


def crowd_share(store: Store, ours: str = "mawdo", base: str = "guide_only") -> list[dict]:
    """Per setting, ``ours`` against ``base`` episode by episode; empty unless both policies
    are in the plan.

    Each dict: ``setting``, ``pairs`` (episodes both succeed), ``success`` and
    ``robot_caused`` (pairs of rates over each one's episodes), ``time_s`` and ``discomfort``
    (pairs of means over the paired episodes), and per metric ``{metric}_test``
    (:class:`~mawdo.experiments.kinds.arena.share.Paired`), ``{metric}_holm`` and
    ``{metric}_verdict`` (Holm over the settings; ``helps`` = lower for ``ours``).
    """
    from mawdo.experiments.kinds.arena.share import holm_verdicts, signed_rank

    plan = store.plan
    if not {ours, base} <= set(plan.policies):
        return []
    out = []
    for s in plan.settings:
        mine, theirs = ({r.run: r for _, _, r in store.rows(p, s) if r.status == "ok"}
                        for p in (ours, base))  # fmt: skip
        if not mine or not theirs:
            continue
        both = sorted(k for k in set(mine) & set(theirs) if mine[k].success and theirs[k].success)
        row = {"setting": s, "pairs": len(both)}
        for key in ("success", "robot_caused"):
            row[key] = tuple(_mean(getattr(r, key) for r in rs.values()) for rs in (mine, theirs))
        for key in ("time_s", "discomfort"):
            a, b = ([getattr(rs[k], key) for k in both] for rs in (mine, theirs))
            row[key] = (_mean(a), _mean(b))
            row[f"{key}_test"] = signed_rank(a, b)
        out.append(row)
    for key in ("time_s", "discomfort"):
        for row, (p, v) in zip(out, holm_verdicts([r[f"{key}_test"] for r in out]), strict=True):
            row[f"{key}_holm"], row[f"{key}_verdict"] = p, v
    return out


def crowd_share_table(store: Store, base: str = "guide_only") -> Table | None:
    """:func:`crowd_share` of every optimizer-driven policy (:func:`share_policies`) against
    ``base`` as one table (``crowd_share.md/.tex/.csv``); None without ``base`` or any."""
    rows = [(p, r) for p in share_policies(store.plan, base) for r in crowd_share(store, p, base)]
    if not rows:
        return None
    cols = [c.format(b=base) for c in SHARE_COLUMNS]
    body = [
        [p, r["setting"], r["pairs"], *r["success"], *r["robot_caused"], *r["time_s"],
         r["time_s_test"].pvalue, r["time_s_holm"], r["time_s_verdict"], *r["discomfort"],
         r["discomfort_test"].pvalue, r["discomfort_holm"], r["discomfort_verdict"]]
        for p, r in rows
    ]  # fmt: skip
    fmts = {c: ".3f" for c in cols[3:7] + cols[12:14]} | {c: ".2f" for c in cols[7:9]}
    fmts |= {c: ".2g" for c in (cols[9], cols[10], cols[14], cols[15])}
    return Table(
        name="crowd_share", columns=cols, rows=body, formats=fmts,
        title=f"Each optimizer-driven policy against {base} (the same planner without its "
        "optimizer), episode by episode",
        notes=[f"pairs: episodes both succeed (the same people for both); success and robot-caused "
               "are shares of each one's episodes; time and discomfort are means over the pairs. "
               "p: two-sided Wilcoxon signed-rank test of the paired values (scipy.stats.wilcoxon; "
               "p = 1 when no pair differs); p Holm: Holm over a policy's settings, per metric. "
               f"Verdict at 0.05 after Holm: helps = the policy significantly lower than {base}, "
               "hurts = higher."],
    )  # fmt: skip


def write_crowd_report(store_path, out_dir, *, figures: bool = True, **_options) -> Path:
    """The table (Markdown, LaTeX, CSV), the figures (rates per setting and policy; one
    episode of each policy, re-run) and ``crowd.md`` into ``out_dir``; returns its path."""
    from mawdo.experiments.kinds.crowd.figures import episode_figure, rates_figure

    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    with Store.read(store_path) as store:
        plan = store.plan
        if plan.kind != "crowd":
            raise ValueError(f"{store_path} holds a {plan.kind!r} study, not a crowd study")
        say("crowd table")
        table = crowd_table(store)
        share = crowd_share_table(store)
        headline = crowd_headline(store)
        errors = [(a, s, r.run, r.error_text) for a, s, r in store.rows() if r.error_text]
        figs = []
        if figures:
            say("figures: rates, and episode 0 re-run with every policy")
            figs = [rates_figure(store, crowd_summary(store), out)]
            figs += [f for f in [episode_figure(store, out)] if f is not None]
    for ext, f in (("md", to_markdown), ("tex", to_latex), ("csv", to_csv)):
        (out / f"crowd_table.{ext}").write_text(f(table))
        if share is not None:
            (out / f"crowd_share.{ext}").write_text(f(share))
    (out / "summary.md").write_text("\n".join(headline) + "\n", encoding="utf-8")
    md = [f"# Crowd navigation: {plan.name}", "", plan.describe(), "", *headline, ""]
    md += [to_markdown(table), ""]
    md += [to_markdown(share), ""] if share is not None else []
    md += [f"![{p.stem}]({p.name})\n" for p in figs]
    if errors:
        md += ["", "## Runs that raised", ""]
        md += [f"- {a} on {s} episode {k}: {e}" for a, s, k, e in errors]
    path = out / "crowd.md"
    path.write_text("\n".join(md) + "\n")
    return path
