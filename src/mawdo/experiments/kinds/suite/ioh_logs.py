"""IOHanalyzer-readable logs from per-run best-so-far records (ioh's ``logger.Analyzer`` format).

One folder per algorithm holds, per function, ``IOHprofiler_f{id}_{name}.json`` (meta data: one
*scenario* per dimension, one entry per run with its instance, evaluations and best point) and
``data_f{id}_{name}/IOHprofiler_f{id}_DIM{D}.dat``: per run, a header line ``evaluations raw_y``
then one ``evaluation value`` line per improvement of the best-so-far, and a last line at the
run's final evaluation (what ``ioh.logger.Analyzer`` writes with its default improvement trigger;
ioh puts the last *evaluated* value on that line, we put the best-so-far, which IOHanalyzer reads
the same since it takes the running minimum). Like ioh, the logged ``raw_y`` is the precision
``f - f_opt`` (ioh logs its problems' internal value, which for BBOB is ``f - f_opt``), in the
meta data's ``best.y`` too. ioh prints 10 decimals; we print the shortest decimal that reads back
to the same float, so the logs round-trip exactly.

Runs without a finite value at first (NaN and +-inf never improve the best-so-far; CEC or a
user's function can return them) start, as ioh writes them, with ``1 None``: every block opens
at evaluation 1, which is how readers (``iohinspector``) tell one run from the next. A run with
no finite value at all is that one line. ioh 0.4.2 leaves such a run out of the meta data (and
writes no meta file when every run is one), so readers pair the remaining entries with the
wrong blocks; we list every run, a run with no best point as ``{"evals": 0, "y": null, "x":
[null, ...]}`` (D nulls: ``iohinspector``'s own convention for an unknown point), so every
reader keeps every run. ``version`` is the installed ioh's (the format's release when ioh is not
installed, e.g. for a CEC-only study).

We write the files ourselves rather than through ``ioh``'s logger because our runs are batched:
one ``problem(X)`` call holds the candidates of every run, which ioh's per-problem logger would
merge into one run. ``tests/suites`` checks the files against the ones ``ioh`` itself writes.
"""

from __future__ import annotations

import json
import re
from collections.abc import Iterable
from dataclasses import dataclass
from importlib import metadata
from pathlib import Path

import numpy as np

FORMAT_VERSION = "0.4.2"
"""The ioh release whose Analyzer files these follow (``tests/suites`` compares them)."""
HEADER = "evaluations raw_y"
NO_VALUE = "None"  # what ioh writes for a value that is not (yet) a finite number


def ioh_version() -> str:
    """The installed ioh's version, as ioh writes it in ``version``; :data:`FORMAT_VERSION`
    when ioh is not installed."""
    try:
        return metadata.version("ioh")
    except metadata.PackageNotFoundError:
        return FORMAT_VERSION


@dataclass(frozen=True)
class IOHRun:
    """One run as IOHanalyzer sees it.

    Attributes
    ----------
    function_id : int
        Function number in its suite (1-based).
    function_name : str
        The suite's function name (``"Rastrigin"``).
    dim : int
        Dimension D.
    instance : int
        Instance number.
    evals : numpy.ndarray
        Evaluations (1-based) at which the best-so-far improved, increasing, shape ``(k,)``.
    best_y : numpy.ndarray
        Best-so-far raw value from each of those evaluations on, shape ``(k,)``.
    total_evals : int
        Evaluations the run spent, ``>= evals[-1]``.
    best_x : numpy.ndarray, optional
        The best point, shape ``(D,)``.
    f_opt : float
        The problem's optimum value; the logs hold ``best_y - f_opt``.
    """

    function_id: int
    function_name: str
    dim: int
    instance: int
    evals: np.ndarray
    best_y: np.ndarray
    total_evals: int
    best_x: np.ndarray | None = None
    f_opt: float = 0.0


def runs_from_result(problem, result) -> list[IOHRun]:
    """:class:`IOHRun` records of the runs of ``result`` on ``problem``.

    Parameters
    ----------
    problem : SuiteFunction
        The suite problem the runs solved.
    result : OptimizeResult
        From :func:`mawdo.suites.run_problem` (or ``minimize(..., trace_evaluations=True)``).
    """
    if result.evaluation_trace is None:
        raise ValueError("the result holds no evaluation trace: run with trace_evaluations=True")
    return [
        IOHRun(
            problem.function_id,
            problem.function_name,
            problem.dim,
            problem.instance,
            np.asarray(t.evals),
            np.asarray(t.best_y),
            int(result.nfev[i]),
            np.asarray(result.x[i]) if np.isfinite(result.fun[i]) else None,
            float(problem.f_star),
        )
        for i, t in enumerate(result.evaluation_trace)
    ]


def _num(v: float) -> str:
    return np.format_float_positional(float(v), unique=True, trim="-")


def _stem(run: IOHRun) -> str:
    safe = re.sub(r"[^A-Za-z0-9]+", "", run.function_name) or "function"
    return f"f{run.function_id}_{safe}"


def _check(run: IOHRun) -> None:
    e, y = np.asarray(run.evals), np.asarray(run.best_y)
    if e.shape != y.shape or e.ndim != 1:
        raise ValueError(f"run of f{run.function_id}: evals and best_y must be 1-D of one length")
    if e.size and (np.any(np.diff(e) <= 0) or np.any(np.diff(y) >= 0) or e[0] < 1):
        raise ValueError(
            f"run of f{run.function_id}: evals must increase from 1 and best_y strictly decrease"
        )
    if e.size and run.total_evals < e[-1]:
        raise ValueError(f"run of f{run.function_id}: total_evals {run.total_evals} < last eval")


def _dat_block(run: IOHRun) -> list[str]:
    lines = [HEADER]
    if not run.evals.size or run.evals[0] > 1:
        # Readers start a run at evaluation 1; ioh writes its unknown first value as None.
        lines.append(f"1 {NO_VALUE}")
    prec = np.asarray(run.best_y, dtype=float) - run.f_opt
    lines += [f"{int(e)} {_num(y)}" for e, y in zip(run.evals, prec, strict=True)]
    if run.evals.size and run.total_evals > run.evals[-1]:
        lines.append(f"{int(run.total_evals)} {_num(prec[-1])}")
    return lines


def _run_meta(run: IOHRun) -> dict:
    # Every key of ioh's entry, always: a reader that misses one (iohinspector: best.x)
    # drops the whole file.
    best = {"evals": 0, "y": None, "x": [None] * run.dim}
    if run.evals.size:
        best = {"evals": int(run.evals[-1]), "y": float(run.best_y[-1] - run.f_opt)}
        best["x"] = [None] * run.dim if run.best_x is None else [float(v) for v in run.best_x]
    return {"instance": int(run.instance), "evals": int(run.total_evals), "best": best}


def write_analyzer_logs(
    folder, runs: Iterable[IOHRun], algorithm: str, algorithm_info: str = "", suite: str = "BBOB"
) -> list[Path]:
    """Write one algorithm's runs as an IOHanalyzer data folder.

    Parameters
    ----------
    folder : str or Path
        Output folder (created; zip it or point IOHanalyzer at it). Existing files of the same
        functions are overwritten.
    runs : iterable of IOHRun
        Any mix of functions, dimensions and instances of one algorithm.
    algorithm, algorithm_info : str
        Shown by IOHanalyzer as the algorithm's name and description.
    suite : str
        Suite name written in the meta data (``"BBOB"``, ``"CEC2017"``).

    Returns
    -------
    list of Path
        The ``.json`` files written, one per function.
    """
    folder = Path(folder)
    by_fn: dict[tuple[int, str], dict[int, list[IOHRun]]] = {}
    for run in runs:
        run = IOHRun(**{**run.__dict__, "evals": np.asarray(run.evals, np.int64)})
        _check(run)
        by_fn.setdefault((run.function_id, run.function_name), {}).setdefault(run.dim, [])
        by_fn[(run.function_id, run.function_name)][run.dim].append(run)
    written, version = [], ioh_version()
    for (fid, fname), dims in sorted(by_fn.items()):
        stem = _stem(dims[next(iter(dims))][0])
        (folder / f"data_{stem}").mkdir(parents=True, exist_ok=True)
        scenarios = []
        for dim in sorted(dims):
            rel = f"data_{stem}/IOHprofiler_f{fid}_DIM{dim}.dat"
            lines = [ln for run in dims[dim] for ln in _dat_block(run)]
            (folder / rel).write_text("\n".join(lines) + "\n")
            scenarios.append(
                {"dimension": dim, "path": rel, "runs": [_run_meta(r) for r in dims[dim]]}
            )
        meta = {
            "version": version,
            "suite": suite,
            "function_id": fid,
            "function_name": fname,
            "maximization": False,
            "algorithm": {"name": algorithm, "info": algorithm_info},
            "attributes": ["evaluations", "raw_y"],
            "scenarios": scenarios,
        }
        path = folder / f"IOHprofiler_{stem}.json"
        path.write_text(json.dumps(meta, indent=1))
        written.append(path)
    return written


def read_analyzer_logs(folder) -> list[dict]:
    """Read an IOHanalyzer data folder (ours or ``ioh``'s) back into per-run records.

    Returns
    -------
    list of dict
        One per run, in file order: ``algorithm``, ``function_id``, ``function_name``, ``dim``,
        ``instance``, ``total_evals`` (from the meta data), ``evals`` and ``precision`` (the
        improvements of the running minimum of the ``.dat`` block's finite ``raw_y``, i.e.
        ``f - f_opt``; ``None``, NaN and inf lines never improve it), ``last_eval`` (the
        block's last evaluation), ``best`` (the meta data's best entry).
    """
    out = []
    for meta_path in sorted(Path(folder).glob("IOHprofiler_*.json")):
        meta = json.loads(meta_path.read_text())
        for sc in meta["scenarios"]:
            blocks = _dat_blocks(Path(folder) / sc["path"])
            if len(blocks) != len(sc["runs"]):
                n_meta = len(sc["runs"])
                raise ValueError(f"{sc['path']}: {len(blocks)} runs in data, {n_meta} in meta")
            for block, info in zip(blocks, sc["runs"], strict=True):
                finite = np.isfinite(block[:, 1])
                e, y = block[finite, 0], block[finite, 1]
                run_min = np.minimum.accumulate(y)
                imp = np.concatenate([[True], run_min[1:] < run_min[:-1]]) if y.size else []
                out.append(
                    {
                        "algorithm": meta["algorithm"]["name"],
                        "function_id": meta["function_id"],
                        "function_name": meta["function_name"],
                        "dim": sc["dimension"],
                        "instance": info["instance"],
                        "total_evals": info["evals"],
                        "evals": e[imp].astype(np.int64),
                        "precision": run_min[imp],
                        "last_eval": int(block[-1, 0]) if block.size else 0,
                        "best": info["best"],
                    }
                )
    return out


def _dat_blocks(path: Path) -> list[np.ndarray]:
    blocks: list[list[tuple[float, float]]] = []
    for line in path.read_text().splitlines():
        if not line.strip():
            continue
        if line.startswith("evaluations"):
            blocks.append([])
            continue
        ev, val = line.split()[:2]
        blocks[-1].append((float(ev), np.nan if val == NO_VALUE else float(val)))
    return [np.array(b, dtype=float).reshape(-1, 2) for b in blocks]
