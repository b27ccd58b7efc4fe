"""The README's result tables, rendered from the committed result files.

Each number comes from a file that a report wrote from its store (``friedman.md``,
``wilcoxon_totals.md``, ``table6.md``, ``swarm_share.md``, and the headline sentences
``summary.md``, which the tests recompute from the committed stores). The README holds each
table (or generated sentence) between ``<!-- table: NAME -->`` and ``<!-- /table -->``;
``tests/test_readme_results.py`` checks that it is exactly what :func:`render` gives, and
``python docs/readme_tables.py`` rewrites the README's tables after a report was regenerated.
"""

from __future__ import annotations

import re
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
RESULTS = ROOT / "docs" / "results"
BLOCK = re.compile(r"(<!-- table: ([\w-]+) -->\n)(.*?)(<!-- /table -->)", re.S)


def _rows(path: Path) -> list[dict[str, str]]:
    """The body rows of the Markdown table in ``path``, each a dict by column header."""
    lines = [s for s in path.read_text(encoding="utf-8").splitlines() if s.startswith("|")]
    cells = [[c.strip() for c in s.strip("|").split("|")] for s in lines]
    return [dict(zip(cells[0], row, strict=True)) for row in cells[2:]]


def friedman(folder: str, algorithm: str) -> tuple[str, int, int, str, str]:
    """(rank, place, of, best algorithm, its rank) of ``algorithm`` in ``folder/friedman.md``."""
    rows = _rows(RESULTS / folder / "friedman.md")
    ranks = {r["Algorithm"]: float(r["Average rank"]) for r in rows}
    place = 1 + sum(r < ranks[algorithm] for r in ranks.values())
    best = min(ranks, key=ranks.get)
    return f"{ranks[algorithm]:.2f}", place, len(rows), best, f"{ranks[best]:.2f}"


def wins(folder: str, rival: str) -> tuple[int, int, int]:
    """MAWDO's (+, =, -) against ``rival`` in ``folder/wilcoxon_totals.md`` (Wilcoxon, 5 %)."""
    for row in _rows(RESULTS / folder / "wilcoxon_totals.md"):
        if row["Rival"] == rival:
            return int(row["+"]), int(row["="]), int(row["-"])
    raise KeyError(f"{rival} not in {folder}/wilcoxon_totals.md")


def _place(n: int) -> str:
    return f"{n}{ {1: 'st', 2: 'nd', 3: 'rd'}.get(n if n < 20 else n % 10, 'th') }"


def paper_table() -> list[str]:
    """One line per table of the paper: where MAWDO stands in our reproduction."""
    lines = ["| paper | our reproduction |", "|---|---|"]
    for label, folder in [
        ("Table 3: F1-F16, D = 30, 30 runs", "paper-table3"),
        ("Table 3, optimum moved off the box centre", "paper-table3-shifted"),
    ]:
        rank, place, of, best, best_rank = friedman(folder, "MAWDO")
        plus, tie, minus = wins(folder, "WDO")
        lead = "" if place == 1 else f" (best: {best} {best_rank})"
        lines.append(
            f"| {label} | MAWDO's Friedman rank {rank}, {_place(place)} of {of}{lead}; better "
            f"than WDO on {plus} of {plus + tie + minus} functions, worse on {minus} "
            "(Wilcoxon, 5 %) |"
        )
    rank, place, of, best, best_rank = friedman("paper-ablation", "MAWDO")
    lines.append(
        f"| Table 5: ablation | full MAWDO's rank {rank}, {_place(place)} of {of} "
        f"(best: {best} {best_rank}) |"
    )
    rows = _rows(RESULTS / "paper-table6" / "table6.md")
    gaps = {r["algorithm"]: float(r["gap L/L*"]) for r in rows}
    ours = next(r for r in rows if "stabilisation on at" in r["algorithm"])
    best = min(gaps, key=gaps.get).split(" (")[0]
    place = 1 + sum(g < float(ours["gap L/L*"]) for g in gaps.values())
    lines.append(
        f"| Table 6: planning on the paper's map, {ours['runs']} runs | MAWDO (stabilised): "
        f"{ours['success']} success, {ours['collision-free']} collision-free, gap L/L* "
        f"{ours['gap L/L*']}, {_place(place)} of {len(rows)} (best: {best} "
        f"{min(gaps.values()):.3f}) |"
    )
    return lines


SUITE = re.compile(
    r"^(?P<suite>.+?), \d+ evaluations per run .*?: WDO\+ (?P<rank>[\d.]+), "
    r"place (?P<place>\d+) of (?P<of>\d+)"
)
BBOB = re.compile(
    r"^- D = (?P<dim>\d+): mawdo has Friedman mean rank (?P<rank>[\d.]+) .*?, place "
    r"(?P<place>\d+) of (?P<of>\d+) \(best: (?P<best>\w+) (?P<best_rank>[\d.]+)\)"
)
BEHIND = re.compile(r"behind (?P<best>[^(;]+?) (?P<rank>[\d.]+)[ ,(;]")


def suites_table() -> list[str]:
    """Standard suites: MAWDO on BBOB, WDO+ on the suites it was not designed on (CEC 2017,
    CEC 2022, the paper's F1-F16), each by its Friedman mean rank among the study's algorithms
    (1 = best)."""
    lines = ["| suite | algorithm | Friedman mean rank | place | best (rank) |"]
    lines.append("|---|---|---|---|---|")
    for s in (RESULTS / "bbob" / "summary.md").read_text(encoding="utf-8").splitlines():
        if m := BBOB.match(s):
            lines.append(
                f"| BBOB f1-f24, D = {m['dim']} | MAWDO | {m['rank']} | {m['place']} of "
                f"{m['of']} | {m['best']} ({m['best_rank']}) |"
            )
    for s in (RESULTS / "holdout" / "summary.md").read_text(encoding="utf-8").splitlines():
        if m := SUITE.match(s):
            behind = BEHIND.search(s)
            best = f"{behind['best']} ({behind['rank']})" if behind else "WDO+"
            # the stored CEC studies ran on opfunu's functions, not the competitions' own
            suite = f"{m['suite']} (opfunu)" if m["suite"].startswith("CEC") else m["suite"]
            lines.append(f"| {suite} | WDO+ | {m['rank']} | {m['place']} of {m['of']} | {best} |")
    return lines + official_rows()


#: Committed full-protocol CEC studies: (results folder, suite label).
OFFICIAL = (
    ("cec2022-official-d10", "CEC 2022 F1-F12, D = 10 (official: 200 000 evaluations, 30 runs)"),
    ("cec2022-official-d20", "CEC 2022 F1-F12, D = 20 (official: 1 000 000 evaluations, 30 runs)"),
    ("cec2017-official-d10", "CEC 2017 F1-F30, D = 10 (official: 100 000 evaluations, 51 runs)"),
    ("cec2017-official-d30", "CEC 2017 F1-F30, D = 30 (official: 300 000 evaluations, 51 runs)"),
)


def official_rows() -> list[str]:
    """WDO+ among the competition winners under a competition's own protocol: its Friedman
    mean rank over the functions (the ``all`` row of ``friedman.md``), place, and the best."""
    lines = []
    for folder, label in OFFICIAL:
        rows = _rows(RESULTS / folder / "friedman.md")
        ranks = {
            k: float(v)
            for k, v in next(r for r in rows if r["dimensions"] == "all").items()
            if k not in ("dimensions", "blocks", "chi2", "p")
        }
        place = 1 + sum(r < ranks["wdo_plus"] for r in ranks.values())
        best = min(ranks, key=ranks.get)
        lines.append(
            f"| {label} | WDO+ | {ranks['wdo_plus']:.2f} | {place} of {len(ranks)} | "
            f"{best} ({ranks[best]:.2f}) |"
        )
    return lines


ARENA = re.compile(
    r"^- (?P<planner>\w+): (?P<success>[\d.]+) % success and (?P<colliding>[\d.]+) % colliding "
    r"runs over (?P<n>\d+) scenes, median gap (?P<gap>[\d.]+);"
)


def arena_table() -> list[str]:
    """The planning arena: each planner's success, colliding runs and median gap."""
    lines = ["| planner | success | colliding runs | median gap |", "|---|---|---|---|"]
    summary = (RESULTS / "arena-default" / "summary.md").read_text(encoding="utf-8")
    for s in summary.splitlines():
        if m := ARENA.match(s):
            lines.append(f"| {m['planner']} | {m['success']} % | {m['colliding']} % | {m['gap']} |")
    return lines


def _listed(rows: list[dict[str, str]]) -> str:
    return ", ".join(f"{r['family']} ({r['mean difference']})" for r in rows) or "none"


def swarm_sentence() -> list[str]:
    """The swarm's share in one sentence: per optimizer-driven planner, the families where its
    gap is significantly smaller or larger than ``guide_only``'s, from the arena report's
    paired table (``swarm_share.md``: Wilcoxon signed-rank, Holm over the families, 5 %)."""
    rows = _rows(RESULTS / "arena-default" / "swarm_share.md")
    parts = []
    for planner in dict.fromkeys(r["planner"] for r in rows):
        mine = [r for r in rows if r["planner"] == planner]
        helps = [r for r in mine if r["verdict"] == "helps"]
        hurts = [r for r in mine if r["verdict"] == "hurts"]
        parts.append(
            f"{planner} shortens it on {_listed(helps)}, lengthens it on {_listed(hurts)}, no "
            f"measurable difference on the other {len(mine) - len(helps) - len(hurts)}"
        )
    families = len({r["family"] for r in rows})
    return [
        "Where the swarm helps: each optimizer's gap (L/L* or T/T*) against the same planner "
        f"with its optimizer off (`guide_only`), scene by scene over {families} families "
        "(Wilcoxon signed-rank, Holm, 5 %; in brackets the mean paired difference; "
        "[table](docs/results/arena-default/swarm_share.md)): "
        + "; ".join(parts)
        + ". "
        + _searched([r for r in rows if r["planner"] == "MAWDO"])
    ]


def _searched(rows: list[dict[str, str]]) -> str:
    """Where the default planner's swarm searched at all (the guide gate took every other
    plan), from the share table's ``runs searched`` column."""
    n = int(_arena_runs() / len(rows))
    some = [r for r in rows if int(r["runs searched"]) > 0]
    never = [r["family"] for r in rows if int(r["runs searched"]) == 0]
    listed = ", ".join(f"{r['family']} {r['runs searched']}" for r in some) or "none"
    return (
        "The default planner searches only where the guides cannot vouch for their route "
        f"(the guide gate): MAWDO's swarm ran in no run on {', '.join(never) or 'no family'} "
        "(a difference there is the gated route kept against `guide_only`'s re-ranking at "
        f"every step), and in some of the {n} runs of the others ({listed})."
    )


def _arena_runs() -> int:
    """The arena's scenes per planner (the summary's "over N scenes")."""
    summary = (RESULTS / "arena-default" / "summary.md").read_text(encoding="utf-8")
    return int(re.search(r"over (\d+) scenes", summary)[1])


def crowd_table() -> list[str]:
    """CrowdNav's circle crossing: each policy's success, robot-caused collisions and time to
    the goal, from the crowd report's table."""
    lines = [
        "| policy | knows | success | robot-caused collisions | time to goal (s) |",
        "|---|---|---|---|---|",
    ]
    knows = {"mawdo_oracle": "the future", "straight": "nothing"}
    for row in _rows(RESULTS / "crowdnav-circle5" / "crowd_table.md"):
        share = f"{100 * float(row['robot-caused']):.1f} %"
        lines.append(
            f"| {row['policy']} | {knows.get(row['policy'], 'what it sees')} | "
            f"{100 * float(row['success']):.1f} % | {share} | {row['time (s)']} |"
        )
    return lines


def _span(rows, policy: str, column: str) -> str:
    """A policy's lowest and highest value of a rate column over the rows' settings, in %."""
    vals = sorted(100 * float(r[column]) for r in rows if r["policy"] == policy)
    lo, hi = f"{vals[0]:.1f}", f"{vals[-1]:.1f}"
    return f"{lo} %" if lo == hi else f"{lo}-{hi} %"


def crowd_sentence() -> list[str]:
    """Beyond the headline setting: the 10- and 20-person settings in full and a noisy sensor,
    each policy's range over the settings, from the studies' crowd tables."""
    ten = _rows(RESULTS / "crowdnav-10" / "crowd_table.md")
    full = _rows(RESULTS / "crowdnav" / "crowd_table.md")
    twenty = [r for r in full if r["setting"].split("-")[1] == "20"]
    noisy = _rows(RESULTS / "crowdnav-noise" / "crowd_table.md")
    n_ten = {r["episodes"] for r in ten}.pop()
    n_twenty = {r["episodes"] for r in twenty}.pop()
    n_noisy = {r["episodes"] for r in noisy}.pop()

    def both(rows, policy):
        return (f"{policy} {_span(rows, policy, 'success')} success, "
                f"{_span(rows, policy, 'robot-caused')} robot-caused")  # fmt: skip

    mine = ", ".join(both(ten, p) for p in ("mawdo", "guide_only", "orca_robot"))
    many = ", ".join(both(twenty, p) for p in ("mawdo", "guide_only", "mawdo_oracle", "orca_robot"))
    noise = "; ".join(both(noisy, p) for p in ("mawdo", "guide_only"))
    return [
        f"With 10 people (`crowdnav-10`: circle and square crossing, the robot unseen or seen, "
        f"{n_ten} episodes each), over the four settings: {mine}. With 20 (`crowdnav`, every "
        f"setting, {n_twenty} episodes each): {many}. Behind a sensor with 0.05 m of noise "
        f"(`crowdnav-noise`: circle crossing with 5 and 10 people, {n_noisy} episodes each): "
        f"{noise}."
    ]


TABLES = {
    "paper": paper_table,
    "suites": suites_table,
    "arena": arena_table,
    "crowd": crowd_table,
    "crowd_more": crowd_sentence,
    "swarm": swarm_sentence,
}


def render(readme: str) -> str:
    """``readme`` with each marked table replaced by its rendering from the result files."""
    return BLOCK.sub(lambda m: m[1] + "\n".join(TABLES[m[2]]()) + "\n" + m[4], readme)


def tables_in(readme: str) -> dict[str, str]:
    """The README's marked tables by name, as written."""
    return {m[2]: m[3] for m in BLOCK.finditer(readme)}


if __name__ == "__main__":
    path = ROOT / "README.md"
    new = render(path.read_text(encoding="utf-8"))
    path.write_text(new, encoding="utf-8")
    sys.stdout.write(f"README tables rewritten: {', '.join(tables_in(new))}\n")
