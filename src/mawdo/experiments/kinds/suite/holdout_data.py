"""The hold-out study's stores read as one kind of table: final errors per function and algorithm.

The hold-out judges WDO+ on CEC 2017 and CEC 2022 (suite stores, this kind) and on the
paper's F1-F16 unshifted and shifted (benchmark stores). To rank them alike, each store becomes a
:class:`HoldoutSuite`: per function, the final errors ``f - f_opt`` of each algorithm's runs.
Benchmark stores are read through the harness's :class:`~mawdo.experiments.store.Store` and
their rows' ``error`` field only, so this kind does not import the benchmark kind.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np

from mawdo.experiments.kinds.suite.data import load_runs
from mawdo.experiments.kinds.suite.measures import RANK_FLOOR
from mawdo.experiments.store import Store
from mawdo.functions import FUNCTIONS

CEC_NAMES = {"cec2017": "CEC 2017", "cec2022": "CEC 2022"}


@dataclass(frozen=True)
class HoldoutSuite:
    """One hold-out suite: who ran what, at which protocol, and the final errors.

    Attributes
    ----------
    key : str
        Short name: ``cec2017``, ``cec2022``, ``paper`` or ``paper-shifted``.
    title : str
        ``"CEC 2017 F1-F29, D = 10"``, ``"F1-F16 shifted"``.
    protocol : str
        Budget and runs in words (``"1e+04 evaluations per run (1000 x D), 2 runs"``).
    algorithms : tuple of str
        Column order (the plan's).
    functions : tuple of str
        Function labels (``F1`` ...), row order.
    finals : dict
        ``(algorithm, function label) -> numpy array`` of the runs' final errors
        ``f - f_opt`` (>= 0 up to rounding), successful runs only.
    runs, dims : int, tuple of int
        Runs per (algorithm, function) the plan asks; dimensions (CEC only, else ``()``).
    evals : int
        Evaluations per run (at the first dimension for CEC).
    store : str
        The store's file name.
    random_us : float or None
        Wall time per evaluation of uniform random search in this store, in microseconds
        (load of the machine included): the cost of the suite's objective itself, random
        search's own being negligible. None for F1-F16 stores.
    """

    key: str
    title: str
    protocol: str
    algorithms: tuple[str, ...]
    functions: tuple[str, ...]
    finals: dict[tuple[str, str], np.ndarray]
    runs: int
    dims: tuple[int, ...]
    evals: int
    store: str
    random_us: float | None = None

    def median_errors(self) -> np.ndarray:
        """``(functions, algorithms)`` median final error over runs, floored at
        :data:`RANK_FLOOR` (1e-8, COCO's final target) so that solved functions tie; NaN where
        an algorithm has no run yet."""
        out = np.full((len(self.functions), len(self.algorithms)), np.nan)
        for i, f in enumerate(self.functions):
            for j, a in enumerate(self.algorithms):
                v = self.finals.get((a, f))
                if v is not None and v.size:
                    out[i, j] = np.median(np.maximum(v, RANK_FLOOR))
        return out


def load_holdout(path: str | Path) -> HoldoutSuite:
    """Read one hold-out store (a suite store of CEC, or a benchmark store of F1-F16).

    Raises
    ------
    StoreError
        Not a results store.
    ValueError
        A store of another kind or suite (BBOB, a planning study).
    """
    with Store.read(path) as store:
        kind, plan = store.meta["study_kind"], store.plan
        if kind == "benchmark":
            rows = store.rows(skip=("curve", "curve_nfev", "params"))
        elif kind not in ("suite", "bbob") or getattr(plan, "suite", None) not in CEC_NAMES:
            raise ValueError(
                f"{path}: not a hold-out store (kind {kind!r}); give the CEC 2017 / 2022 suite "
                "stores and the F1-F16 benchmark stores of the hold-out study"
            )
    if kind == "benchmark":
        return _benchmark(Path(path), plan, rows)
    return _cec(Path(path))


def _cec(path: Path) -> HoldoutSuite:
    study = load_runs(path)
    funcs = tuple(f"F{f}" for f in study.functions)
    finals = {}
    for a in study.algorithms:
        for fid in study.functions:
            runs = [r for d in study.dims for r in study.select(a, fid, d) if r.evals.size]
            if runs:
                finals[a, f"F{fid}"] = np.array([r.precision[-1] for r in runs])
    first = study.functions[0], study.functions[-1]
    dims = ", ".join(map(str, study.dims))
    with Store.read(path) as store:
        runs = store.plan.runs
        timed = store.rows("random", skip=("evals", "best_so_far", "best_x", "params"))
    nfev = sum(r.nfev for _, _, r in timed if not r.failed)
    wall = sum(r.wall_time for _, _, r in timed if not r.failed)
    evals = int(round(study.budget * study.dims[0]))
    return HoldoutSuite(
        key=study.suite,
        title=f"{CEC_NAMES[study.suite]} F{first[0]}-F{first[1]}, D = {dims}",
        protocol=f"{evals} evaluations per run ({study.budget:g} x D), {runs} runs",
        algorithms=study.algorithms,
        functions=funcs,
        finals=finals,
        runs=runs,
        dims=study.dims,
        evals=evals,
        store=path.name,
        random_us=1e6 * wall / nfev if nfev else None,
    )


def _benchmark(path: Path, plan, rows) -> HoldoutSuite:
    labels = {f: FUNCTIONS[f].paper_id or f for f in plan.functions}
    acc: dict[tuple[str, str], list[float]] = {}
    for a, f, r in rows:
        if not r.failed:
            acc.setdefault((a, labels[f]), []).append(float(r.error))
    evals = plan.pop_size * plan.max_iter
    shifted = "shifted" if plan.shifted else "unshifted"
    return HoldoutSuite(
        key="paper-shifted" if plan.shifted else "paper",
        title=f"F1-F16 {shifted}",
        protocol=f"{evals} evaluations per run ({plan.pop_size} x {plan.max_iter}), "
        f"{plan.runs} runs",
        algorithms=tuple(plan.algorithms),
        functions=tuple(labels[f] for f in plan.functions),
        finals={k: np.array(v) for k, v in acc.items()},
        runs=plan.runs,
        dims=(),
        evals=evals,
        store=path.name,
    )
