"""Exports of a suite study, written from its store: IOHanalyzer logs (one folder per
algorithm) and, for CEC studies, the competitions' result files (:mod:`.cec_export`);
:data:`EXPORT_FORMATS` names them for the command line."""

from __future__ import annotations

from pathlib import Path

from mawdo.experiments.kinds.suite.cec_export import export_cec
from mawdo.experiments.kinds.suite.data import load_runs
from mawdo.experiments.kinds.suite.ioh_logs import IOHRun, write_analyzer_logs
from mawdo.suites import SUITES


def export_ioh(store_path, folder) -> list[Path]:
    """Write every stored run as IOHanalyzer data: ``folder/<algorithm>/IOHprofiler_f*.json``
    and ``data_f*/IOHprofiler_f*_DIM*.dat`` (ioh's ``Analyzer`` format, see
    :mod:`mawdo.experiments.kinds.suite.ioh_logs`). Zip ``folder`` (or one algorithm's folder)
    and upload it to IOHanalyzer.

    Parameters
    ----------
    store_path : str or Path
        A store of a suite study.
    folder : str or Path
        Output folder (created); existing files of the same functions are overwritten.

    Returns
    -------
    list of Path
        The meta-data files written.
    """
    study = load_runs(store_path)
    if not study.runs:
        raise ValueError(f"{store_path} holds no finished run yet; nothing to export")
    folder = Path(folder)
    written = []
    for algo in study.algorithms:
        runs = [
            IOHRun(
                r.function_id,
                r.function_name,
                r.dim,
                r.instance,
                r.evals,
                r.best_y,
                r.nfev,
                None if r.best_x.size != r.dim else r.best_x,
                r.f_star,
            )
            for r in study.select(algo)
        ]
        if runs:
            setup = study.setups.get(algo, algo)
            info = f"mawdo {setup}, budget {study.budget:g} x D evaluations"
            label = SUITES[study.suite].label
            written += write_analyzer_logs(folder / algo, runs, algo, info, suite=label)
    return written


EXPORT_FORMATS = {
    "ioh": (export_ioh, "IOHanalyzer logs"),
    "cec": (export_cec, "the CEC competitions' result files"),
}
"""``--format`` name -> (``export(store_path, folder) -> list of Path``, what it writes)."""
