"""Check that a speed change leaves every planning run bit for bit the same.

``python benchmarks/plan_identity.py dump OUT.pkl [--quick]`` runs a fixed set of realtime
runs of ``mawdo`` and pickles every field of every :class:`~mawdo.planning.run.result.PlanResult`
(trajectory, route, route times, success, reason, counters, and each replan's fields);
``python benchmarks/plan_identity.py compare BASE.pkl NEW.pkl`` prints
``N runs compared (R replans): D differ`` and, per differing run, the first fields that differ;
it exits 1 when any run differs or is missing.

For a before/after, dump with each copy's ``src`` first on ``PYTHONPATH``:
``PYTHONPATH=<old>/src python benchmarks/plan_identity.py dump old.pkl``.

The full set (about 100 runs, 10-20 min on 2 cores once compiled): the paper scenario, seeds
0-4 with the time guide and 0-1 without; scenes 0-2 of every arena family (seed 0) with and
without the time guide; corridor, doorway and parked scene 0 under speed, acceleration and
turn limits. ``--quick`` keeps paper seeds 0-1 and scene 0 of every family (time guide on).
"""

from __future__ import annotations

import argparse
import dataclasses
import pickle
import sys
import time

import numpy as np

#: fields that measure wall time, not what the run did: never compared
TIMES = frozenset({"latency"})
LIMITS = {"max_speed": 6.0, "max_accel": 1.0, "max_turn": 0.5}


def cases(quick: bool = False) -> list[tuple[str, str, int, dict]]:
    """``(label, scene, seed, overrides)`` per run; ``scene`` is ``"paper"`` or
    ``"family:index"`` (scene seed 0)."""
    from mawdo.experiments.kinds.arena.plan import LARGE_FAMILIES
    from mawdo.planning.run.config import PRESETS
    from mawdo.planning.scenes import FAMILIES

    out = []
    for s in range(2 if quick else 5):
        out.append((f"paper-s{s}", "paper", s, {}))
    for s in () if quick else range(2):
        out.append((f"paper-s{s}-noguide", "paper", s, {"time_guide": False}))
    for fam in FAMILIES:
        if fam in LARGE_FAMILIES:  # minutes a run: one scene, as the preset 'large' plans it
            ahead = PRESETS["large"].lookahead
            out.append((f"{fam}-0", f"{fam}:0", 0, {"lookahead": ahead}))
            continue
        for i in range(1 if quick else 3):
            for guide in (True,) if quick else (True, False):
                tag = "" if guide else "-noguide"
                out.append((f"{fam}-{i}{tag}", f"{fam}:{i}", 0, {"time_guide": guide}))
    for fam in () if quick else ("corridor", "doorway", "parked"):
        out.append((f"{fam}-0-limits", f"{fam}:0", 0, dict(LIMITS)))
    return out


def _plain(value):
    """A picklable, comparable copy of a result: dataclasses and pydantic models become dicts of
    their fields (tagged with the class name, not its module, so that dumps made before and
    after a module moves compare)."""
    if hasattr(type(value), "model_fields") and hasattr(value, "model_dump"):  # pydantic
        return {"__type__": type(value).__name__} | _plain(dict(value))
    if dataclasses.is_dataclass(value) and not isinstance(value, type):
        fields = dataclasses.fields(value)
        return {"__type__": type(value).__name__} | {
            f.name: _plain(getattr(value, f.name)) for f in fields
        }
    if isinstance(value, list | tuple):
        return type(value)(_plain(v) for v in value)
    if isinstance(value, dict):
        return {k: _plain(v) for k, v in value.items()}
    if isinstance(value, np.ndarray):
        return value.copy()
    if isinstance(value, np.random.SeedSequence):  # compares by identity otherwise
        return {"__type__": "SeedSequence"} | _plain(value.state)
    return value


def run_case(scene: str, seed: int, overrides: dict):
    """The plain fields of one realtime ``mawdo`` run."""
    from mawdo.planning import get_scenario, plan
    from mawdo.planning.scenes import generate_scene

    if scene == "paper":
        scenario = get_scenario("paper")
    else:
        family, index = scene.split(":")
        scenario = generate_scene(family, int(index), seed=0).scenario
    return _plain(plan(scenario, "mawdo", seed=seed, **overrides))


#: Fields added to results and scenario specs since the first dumps, with their defaults: a dump
#: that lacks them compares equal to one that has them at these values.
ADDED_DEFAULTS = {
    "robot_caused": None, "other_collisions": None, "units": "px", "dt": None, "resolution": None,
    "file_spec": None, "derived_units": None, "crowd": None, "check": None, "comfort": 0.0,
    "comfort_weight": 8.0, "refine_trajectory": True, "guide_lookahead": None, "lookahead": None,
    "first_patience": None, "risk": 0.0, "risk_reach": 40, "uncertainty": None,
}  # fmt: skip


def _added_default(key, value) -> bool:
    return key in ADDED_DEFAULTS and value == ADDED_DEFAULTS[key]


def diff(a, b, path: str = "") -> list[str]:
    """Where two plain values differ (paths of the first differences; NaN equals NaN)."""
    if isinstance(a, np.ndarray) or isinstance(b, np.ndarray):
        a, b = np.asarray(a), np.asarray(b)
        same = a.shape == b.shape and a.dtype == b.dtype
        return [] if same and np.array_equal(a, b, equal_nan=a.dtype.kind in "fc") else [path]
    if isinstance(a, dict) and isinstance(b, dict):
        # a field added since one of the dumps, at its default, changes nothing
        a = {k: v for k, v in a.items() if k in b or not _added_default(k, v)}
        b = {k: v for k, v in b.items() if k in a or not _added_default(k, v)}
        if a.keys() != b.keys():
            return [f"{path} keys {sorted(a.keys() ^ b.keys())}"]
        return [d for k in a if k not in TIMES for d in diff(a[k], b[k], f"{path}.{k}")]
    if isinstance(a, list | tuple) and isinstance(b, list | tuple):
        if len(a) != len(b):
            return [f"{path} length {len(a)} != {len(b)}"]
        pairs = enumerate(zip(a, b, strict=True))
        return [d for i, (x, y) in pairs for d in diff(x, y, f"{path}[{i}]")]
    if isinstance(a, float) and isinstance(b, float) and np.isnan(a) and np.isnan(b):
        return []
    return [] if type(a) is type(b) and a == b else [path]


def dump(out: str, quick: bool) -> None:
    runs = {}
    todo = cases(quick)
    t0 = time.perf_counter()
    for n, (label, scene, seed, overrides) in enumerate(todo, 1):
        runs[label] = run_case(scene, seed, overrides)
        print(f"[{n}/{len(todo)}] {label} ({time.perf_counter() - t0:.0f} s)", flush=True)
    with open(out, "wb") as f:
        pickle.dump(runs, f)


def compare(base: str, new: str) -> int:
    with open(base, "rb") as f:
        a = pickle.load(f)
    with open(new, "rb") as f:
        b = pickle.load(f)
    common = [k for k in a if k in b]
    replans = sum(len(a[k].get("replans", ())) for k in common)
    bad = {k: diff(a[k], b[k]) for k in common}
    bad = {k: v for k, v in bad.items() if v}
    for k, where in bad.items():
        print(f"{k}: {', '.join(where[:5])}{' ...' if len(where) > 5 else ''}")
    lost = sorted(set(a) ^ set(b))
    if lost:
        print(f"in one dump only: {', '.join(lost)}")
    print(f"{len(common)} runs compared ({replans} replans): {len(bad)} differ")
    return 1 if bad or lost else 0


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    sub = parser.add_subparsers(dest="cmd", required=True)
    d = sub.add_parser("dump", help="run the cases and pickle their results")
    d.add_argument("out")
    d.add_argument("--quick", action="store_true", help="paper seeds 0-1, scene 0 per family")
    c = sub.add_parser("compare", help="compare two dumps (exit 1 if any run differs)")
    c.add_argument("base")
    c.add_argument("new")
    args = parser.parse_args(argv)
    if args.cmd == "dump":
        dump(args.out, args.quick)
        return 0
    return compare(args.base, args.new)


if __name__ == "__main__":
    sys.exit(main())
