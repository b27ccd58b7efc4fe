"""A CEC study's runs as the competitions' result files, written from its store.

CEC 2017 and CEC 2022 ask each entry for one text file per function and dimension,
``<algorithm>_<function>_<D>.txt``: a matrix with one column per run and one row per
checkpoint, the run's error ``f - f*`` after that many evaluations (CEC 2017: 14 rows, after
0.01, 0.02, 0.03, 0.05, 0.1, 0.2, ..., 1.0 of the budget; CEC 2022: 16 rows, after
``D^(k/5 - 3)`` of it, and a 17th with the evaluations the run used). Errors of at most 1e-8
are written as 0, as in the report's tables (docs/deviations.md#d-cec-protocol). These are
the files the organisers collected and that comparison tools (tacolab, the published entries'
own files) read, so a stored study can be set beside the published ones function by function.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from mawdo.experiments.kinds.suite.competition import competition_errors
from mawdo.experiments.kinds.suite.data import StudyRuns, load_runs, precision_at
from mawdo.suites import SUITES, evaluation_budget

FES_ROW = {"cec2022"}
"""Suites whose files end with a row of each run's evaluations (CEC 2022's FEterm)."""


def cec_matrix(study: StudyRuns, algorithm: str, function_id: int, dim: int) -> np.ndarray:
    """The competition's matrix of one algorithm on one function at ``dim``: rows the
    checkpoints (and CEC 2022's evaluations), columns the stored runs in run order.

    Returns
    -------
    numpy.ndarray
        Shape ``(checkpoints [+ 1], runs)``; empty columns when no run is stored.
    """
    spec = SUITES[study.suite]
    marks = spec.checkpoints(dim, evaluation_budget(study.budget, dim))
    runs = sorted(study.select(algorithm, function_id, dim), key=lambda r: r.run)
    errors = competition_errors(precision_at(runs, marks)).T
    if study.suite in FES_ROW:
        errors = np.vstack([errors, [[float(r.nfev) for r in runs]]])
    return errors


def _text(matrix: np.ndarray, fes_row: bool) -> str:
    lines = [" ".join(f"{v:.8e}" for v in row) for row in matrix[: len(matrix) - fes_row]]
    if fes_row:
        lines.append(" ".join(str(int(v)) for v in matrix[-1]))
    return "\n".join(lines) + "\n"


def export_cec(store_path, folder) -> list[Path]:
    """Write every stored (algorithm, function, dimension) of a CEC study as the
    competition's result file, ``folder/<algorithm>/<algorithm>_<F>_<D>.txt``.

    Parameters
    ----------
    store_path : str or Path
        A store of a CEC 2017 or CEC 2022 suite study (official numbering).
    folder : str or Path
        Output folder (created); existing files of the same names are overwritten.

    Returns
    -------
    list of Path
        The files written.

    Raises
    ------
    ValueError
        The store holds no run, is not a CEC study, or numbers its functions as opfunu does.
    """
    study = load_runs(store_path)
    if not study.runs:
        raise ValueError(f"{store_path} holds no finished run yet; nothing to export")
    spec = SUITES.get(study.suite)
    if spec is None or spec.checkpoints is None:
        raise ValueError(
            f"--format cec writes the CEC competitions' files; {store_path} is a "
            f"{study.suite} study, which has no checkpoints (use --format ioh)"
        )
    if study.numbering:
        raise ValueError(
            f"{store_path} numbers its functions as opfunu does ({study.numbering}); the "
            "competition's files name the official functions: run the study on the official "
            f"suite ({study.suite}) to export them"
        )
    folder = Path(folder)
    written = []
    for algo in study.algorithms:
        for fid in study.functions:
            for dim in study.dims:
                matrix = cec_matrix(study, algo, fid, dim)
                if not matrix.shape[1]:
                    continue
                path = folder / algo / f"{algo}_{fid}_{dim}.txt"
                path.parent.mkdir(parents=True, exist_ok=True)
                path.write_text(_text(matrix, study.suite in FES_ROW), encoding="utf-8")
                written.append(path)
    return written
