"""The SHADE family on CEC 2017 at D = 10 against the means the authors published.

Not a speed benchmark (``make bench`` does not run it): a spread check of ``lshade``, ``jso``
and ``nlshade_rsp`` under the CEC 2017 protocol (10 000 D evaluations, errors below 1e-8 count
as 0, 51 runs) on the official functions (the ``cec2017`` suite, a port of the official C code
in the official numbering, F1-F30).

The full protocol::

    nice python -m benchmarks.shade_cec2017 --runs 51 --out shade_cec2017_d10.jsonl

A reduced check (a few runs, some functions)::

    nice python -m benchmarks.shade_cec2017 --runs 5 --functions 1,4,5,6,7,8,9,10 \\
        --algorithms jso,lshade

Each (algorithm, function) row is appended to ``--out`` as it finishes (JSON lines), and
``--report FILE`` prints the table of a finished file again. Every run is reproducible from
``--seed``: run ``k`` of a function is the ``k``-th child of ``SeedSequence((seed, F))``.
"""

from __future__ import annotations

import argparse
import json
import sys
import time

import numpy as np

DIM = 10
EPS = 1e-8  # CEC: an error at or below 1e-8 is 0

# jSO, CEC 2017, D = 10: the mean final error over 51 runs of each official function, computed
# from the authors' result files submitted to the competition (jSO_<F>_10.txt, last row =
# 100 000 evaluations; repository P-N-Suganthan/CEC2017-BoundContrained, as collected in
# dgsotiropoulos/CEC-Benchmarks, folder A01). They agree with Table I of Brest, Maucec &
# Boskovic, CEC 2017 (e.g. F5 1.76, F10 35.9, F30 395).
JSO_PUBLISHED = {
    1: 0.0, 2: 0.0, 3: 0.0, 4: 0.0, 5: 1.75581, 6: 0.0, 7: 11.7916, 8: 1.95091, 9: 0.0,
    10: 35.8974, 11: 0.0, 12: 2.66205, 13: 2.96442, 14: 0.058527, 15: 0.220835, 16: 0.568839,
    17: 0.502268, 18: 0.308, 19: 0.0107034, 20: 0.342778, 21: 132.378, 22: 100.0,
    23: 301.206, 24: 296.598, 25: 405.963, 26: 300.0, 27: 389.387, 28: 339.076, 29: 234.196,
    30: 394.519,
}  # fmt: skip
PUBLISHED = {"jso": JSO_PUBLISHED}
OFFICIAL = tuple(range(1, 31))  # CEC 2017's official functions


def check_function(official: int) -> int:
    """``official`` if it is a CEC 2017 function number (1..30), else a ValueError."""
    if not 1 <= official <= 30:
        raise ValueError(f"official F{official}: CEC 2017 has F1..F30")
    return official


def run_function(algorithm: str, official: int, runs: int, seed: int) -> dict:
    """``runs`` runs of ``algorithm`` on official F``official`` at D = 10: final errors."""
    from mawdo import minimize
    from mawdo.suites import get_problem

    problem = get_problem("cec2017", check_function(official), dim=DIM)
    t0 = time.perf_counter()
    res = minimize(
        problem,
        algorithm=algorithm,
        runs=runs,
        seed=[seed, official],
        max_evals=10_000 * DIM,
        target=problem.f_star + EPS,  # a run at the CEC threshold is done: its error is 0
    )
    err = res.fun - problem.f_star
    err = np.where(err <= EPS, 0.0, err)
    return {
        "algorithm": algorithm,
        "official": official,
        "runs": runs,
        "seed": seed,
        "errors": err.tolist(),
        "mean": float(err.mean()),
        "std": float(err.std()),
        "seconds": time.perf_counter() - t0,
    }


def table(rows: list[dict]) -> str:
    """Markdown: measured mean (std) per algorithm beside the published mean."""
    algos = list(dict.fromkeys(r["algorithm"] for r in rows))
    by = {(r["algorithm"], r["official"]): r for r in rows}
    head = ["F"]
    for a in algos:
        head += [f"{a} mean (std), runs"] + ([f"{a} published"] if a in PUBLISHED else [])
    lines = ["| " + " | ".join(head) + " |", "|" + "---|" * len(head)]
    for f in sorted({r["official"] for r in rows}):
        cells = [f"F{f}"]
        for a in algos:
            r = by.get((a, f))
            cells.append(f"{r['mean']:.3g} ({r['std']:.2g}), {r['runs']}" if r else "")
            if a in PUBLISHED:
                cells.append(f"{PUBLISHED[a][f]:.3g}")
        lines.append("| " + " | ".join(cells) + " |")
    return "\n".join(lines)


def friedman_ranks(rows: list[dict]) -> dict[str, float]:
    """Each algorithm's mean rank over the functions all of them ran (rank 1: the least mean
    error on a function; ties share the mean of their ranks), best first."""
    from scipy.stats import rankdata

    algos = list(dict.fromkeys(r["algorithm"] for r in rows))
    by = {(r["algorithm"], r["official"]): r["mean"] for r in rows}
    common = sorted({r["official"] for r in rows if all((a, r["official"]) in by for a in algos)})
    ranks = np.array([rankdata([by[(a, f)] for a in algos]) for f in common])
    mean = dict(zip(algos, ranks.mean(axis=0).tolist(), strict=True))
    return dict(sorted(mean.items(), key=lambda kv: kv[1]))


def rank_table(rows: list[dict]) -> str:
    """Markdown: the Friedman mean ranks (:func:`friedman_ranks`), best first."""
    lines = ["| algorithm | Friedman mean rank |", "|---|---|"]
    lines += [f"| {a} | {r:.2f} |" for a, r in friedman_ranks(rows).items()]
    return "\n".join(lines)


def main(argv: list[str]) -> int:
    ap = argparse.ArgumentParser(prog="python -m benchmarks.shade_cec2017", description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)  # fmt: skip
    ap.add_argument("--algorithms", default="jso,lshade,nlshade_rsp")
    ap.add_argument("--functions", default=",".join(map(str, OFFICIAL)),
                    help="official CEC 2017 numbers (1..30)")  # fmt: skip
    ap.add_argument("--runs", type=int, default=51)
    ap.add_argument("--seed", type=int, default=2017)
    ap.add_argument("--out", default="shade_cec2017_d10.jsonl")
    ap.add_argument(
        "--report", help="print the tables of finished --out files (comma list) and stop"
    )
    args = ap.parse_args(argv)
    if args.report:
        rows = []
        for path in args.report.split(","):
            with open(path, encoding="utf-8") as fh:
                rows += [json.loads(line) for line in fh if line.strip()]
        print(table(rows))
        print()
        print(rank_table(rows))
        return 0
    functions = [int(f) for f in args.functions.split(",")]
    for f in functions:
        check_function(f)  # refuse unknown numbers before anything runs
    rows = []
    for algorithm in args.algorithms.split(","):
        for f in functions:
            row = run_function(algorithm, f, args.runs, args.seed)
            rows.append(row)
            with open(args.out, "a", encoding="utf-8") as fh:
                fh.write(json.dumps(row) + "\n")
            print(f"{algorithm} F{f}: mean {row['mean']:.4g} ({row['seconds']:.0f} s)", flush=True)
    print(table(rows))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
