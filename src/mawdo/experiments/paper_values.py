"""The paper's own numbers (Tables 3 and 5 of arXiv 2511.20394), for side-by-side reports.

Transcribed from ``paper/mawdo-paper.tex`` (the ``tab:results`` longtable and the
``tab:ablation`` table), cell by cell, in the paper's own notation so each line can be checked
against the source by eye. The paper's ``$\\approx$`` (F11, AWDO) is read as ``=`` (no
significant difference). Values are the paper's raw final objective values.

Comparability (SPEC 2): for F1-F11 the optimum is 0, so the raw value is also the error and our
numbers are comparable. The paper's F12-F16 rows do not fit its own function table (F12 Best
-1.00 is not the camel's -1.0316, F14 Best 3.00 is Goldstein-Price's optimum, F13/F15/F16 look
like errors ``f - f*``), so reports print them as "not comparable".
"""

from __future__ import annotations

from typing import NamedTuple


class PaperEntry(NamedTuple):
    """One algorithm on one function in a paper table.

    Attributes
    ----------
    best, ave, std : float or None
        The paper's Best, Ave and Std rows (None where the paper leaves the cell blank).
    sign : str or None
        The paper's Wilcoxon mark of MAWDO against this algorithm (``+``, ``=``, ``-``);
        None for MAWDO itself and for Table 5, which has no Wilcoxon row.
    """

    best: float | None
    ave: float | None
    std: float | None
    sign: str | None


NOT_COMPARABLE = frozenset({"F12", "F13", "F14", "F15", "F16"})
"""Paper ids whose published rows cannot be compared with our numbers (SPEC 2)."""

TABLE3_ALGORITHMS = ("gwo", "woa", "wdo", "awdo", "mewdo", "mawdo")
TABLE5_ALGORITHMS = ("mawdo1", "mawdo2", "mawdo3", "mawdo4", "mawdo")

TABLE3: dict[str, dict[str, PaperEntry]] = {
    "F1": {
        "gwo": PaperEntry(1.23E-72, 2.78E-63, 1.01E-62, '+'),
        "woa": PaperEntry(1.77E-85, 8.79E-74, 4.67E-73, '+'),
        "wdo": PaperEntry(0.0, 0.0, 0.0, '='),
        "awdo": PaperEntry(0.0, 0.0, 0.0, '='),
        "mewdo": PaperEntry(0.0, 0.0, 0.0, '='),
        "mawdo": PaperEntry(0.0, 0.0, 0.0, None),
    },
    "F2": {
        "gwo": PaperEntry(8.35E-43, 7.52E-39, 3.15E-38, '+'),
        "woa": PaperEntry(5.01E-55, 6.36E-48, 3.20E-47, '+'),
        "wdo": PaperEntry(0.0, 0.0, 0.0, '='),
        "awdo": PaperEntry(0.0, 0.0, 0.0, '='),
        "mewdo": PaperEntry(0.0, 0.0, 0.0, '='),
        "mawdo": PaperEntry(0.0, 0.0, 0.0, None),
    },
    "F3": {
        "gwo": PaperEntry(1.91E-16, 3.34E-05, 9.78E-05, '+'),
        "woa": PaperEntry(1.80E-06, 6275.444, 12012.167, '+'),
        "wdo": PaperEntry(0.0, 0.0, 0.0, '='),
        "awdo": PaperEntry(0.0, 0.0, 0.0, '='),
        "mewdo": PaperEntry(0.0, 0.0, 0.0, '='),
        "mawdo": PaperEntry(0.0, 0.0, 0.0, None),
    },
    "F4": {
        "gwo": PaperEntry(2.18E-24, 5.15E-18, 2.39E-17, '+'),
        "woa": PaperEntry(1.87E-17, 4.93E-08, 2.07E-07, '+'),
        "wdo": PaperEntry(0.0, 0.0, 0.0, '='),
        "awdo": PaperEntry(0.0, 0.0, 0.0, '='),
        "mewdo": PaperEntry(0.0, 0.0, 0.0, '='),
        "mawdo": PaperEntry(0.0, 0.0, 0.0, None),
    },
    "F5": {
        "gwo": PaperEntry(2.87E+01, 2.88E+01, 3.53E-02, '+'),
        "woa": PaperEntry(7.55E-02, 1.91E+01, 1.27E+01, '+'),
        "wdo": PaperEntry(2.87E+01, 2.87E+01, 8.49E-03, '+'),
        "awdo": PaperEntry(4.12E-04, 2.49E+01, 9.75E+00, '-'),
        "mewdo": PaperEntry(2.87E+01, 2.87E+01, 6.64E-03, '+'),
        "mawdo": PaperEntry(1.37E-02, 1.93E+01, 1.32E+01, None),
    },
    "F6": {
        "gwo": PaperEntry(2.06E-05, 9.29E-04, 8.60E-04, '+'),
        "woa": PaperEntry(5.35E-06, 1.09E-03, 1.51E-03, '+'),
        "wdo": PaperEntry(7.54E-06, 1.17E-04, 1.18E-04, '+'),
        "awdo": PaperEntry(5.73E-06, 1.05E-04, 9.16E-05, '+'),
        "mewdo": PaperEntry(4.46E-06, 8.15E-05, 7.97E-05, '='),
        "mawdo": PaperEntry(6.06E-07, 1.43E-05, 1.22E-05, None),
    },
    "F7": {
        "gwo": PaperEntry(0.0, 0.0, 0.0, '='),
        "woa": PaperEntry(0.0, 0.0, 0.0, '='),
        "wdo": PaperEntry(1.60E+00, 4.16E+00, 7.69E-01, '+'),
        "awdo": PaperEntry(0.0, 0.0, 0.0, '='),
        "mewdo": PaperEntry(0.0, 3.94E+00, 8.63E-01, '+'),
        "mawdo": PaperEntry(0.0, 0.0, 0.0, None),
    },
    "F8": {
        "gwo": PaperEntry(3.76E-43, 5.89E-04, 3.15E-03, '+'),
        "woa": PaperEntry(7.72E-54, 2.17E-01, 7.48E-01, '+'),
        "wdo": PaperEntry(3.64E-17, 1.07E-01, 4.33E-01, '+'),
        "awdo": PaperEntry(2.18E-21, 7.56E-17, 1.80E-16, '='),
        "mewdo": PaperEntry(8.44E-58, 6.52E-05, 1.63E-04, '+'),
        "mawdo": PaperEntry(4.94E-25, 7.05E-19, 1.54E-18, None),
    },
    "F9": {
        "gwo": PaperEntry(3.48E-02, 1.85E-01, 1.18E-01, '+'),
        "woa": PaperEntry(3.40E-04, 6.57E-03, 6.14E-03, '+'),
        "wdo": PaperEntry(5.96E-04, 2.91E-02, 4.86E-02, '+'),
        "awdo": PaperEntry(5.10E-08, 6.42E-06, 7.86E-06, '-'),
        "mewdo": PaperEntry(2.19E-03, 1.91E-02, 2.12E-02, '+'),
        "mawdo": PaperEntry(2.38E-07, 1.80E-06, 1.42E-06, None),
    },
    "F10": {
        "gwo": PaperEntry(1.81E+00, 2.80E+00, 3.53E-01, '+'),
        "woa": PaperEntry(6.85E-04, 4.07E-01, 6.33E-01, '+'),
        "wdo": PaperEntry(1.03E-02, 6.38E-01, 6.68E-01, '+'),
        "awdo": PaperEntry(8.23E-06, 9.05E-05, 1.15E-04, '+'),
        "mewdo": PaperEntry(6.63E-03, 4.30E-01, 4.54E-01, '+'),
        "mawdo": PaperEntry(8.60E-08, 1.33E-05, 1.48E-05, None),
    },
    "F11": {
        "gwo": PaperEntry(3.33E-45, 2.38E-40, 1.07E-39, '+'),
        "woa": PaperEntry(3.21E-59, 3.65E-05, 1.97E-04, '+'),
        "wdo": PaperEntry(1.28E-149, 4.73E-03, 1.10E-02, '+'),
        "awdo": PaperEntry(3.32E-59, 2.85E-48, 1.53E-47, '='),
        "mewdo": PaperEntry(9.69E-150, 2.58E-03, 9.72E-03, '+'),
        "mawdo": PaperEntry(7.41E-59, 1.39E-46, 6.80E-46, None),
    },
    "F12": {
        "gwo": PaperEntry(-1.00E+00, -7.38E-01, 4.17E-01, '+'),
        "woa": PaperEntry(-1.00E+00, -8.80E-01, 2.98E-01, '+'),
        "wdo": PaperEntry(-9.96E-01, -8.42E-01, 1.67E-01, '+'),
        "awdo": PaperEntry(-1.00E+00, -1.00E+00, 1.42E-04, '+'),
        "mewdo": PaperEntry(-1.00E+00, -8.74E-01, 1.45E-01, '+'),
        "mawdo": PaperEntry(-1.00E+00, -9.99E-01, 9.97E-04, None),
    },
    "F13": {
        "gwo": PaperEntry(6.09E-07, 7.10E-01, 1.45E+00, '='),
        "woa": PaperEntry(1.26E-05, 9.30E-02, 2.45E-01, '+'),
        "wdo": PaperEntry(4.33E-03, 2.91E-01, 3.60E-01, '+'),
        "awdo": PaperEntry(2.93E-05, 5.36E-02, 2.29E-01, '='),
        "mewdo": PaperEntry(1.15E-02, 3.61E-01, 3.73E-01, '+'),
        "mawdo": PaperEntry(2.28E-05, 3.10E-04, 3.28E-04, None),
    },
    "F14": {
        "gwo": PaperEntry(3.00E+00, 7.21E+00, 9.24E+00, '+'),
        "woa": PaperEntry(3.00E+00, 7.61E+00, 1.03E+01, '+'),
        "wdo": PaperEntry(3.12E+00, 1.62E+01, 1.01E+01, '+'),
        "awdo": PaperEntry(3.00E+00, 4.81E+00, 6.74E+00, '+'),
        "mewdo": PaperEntry(3.21E+00, 1.60E+01, 1.06E+01, '+'),
        "mawdo": PaperEntry(3.00E+00, 3.01E+00, 9.37E-03, None),
    },
    "F15": {
        "gwo": PaperEntry(2.42E-01, 8.50E+00, 7.25E+00, '+'),
        "woa": PaperEntry(3.29E-03, 2.26E+00, 4.09E+00, '+'),
        "wdo": PaperEntry(2.47E-01, 1.53E+01, 8.45E+00, '+'),
        "awdo": PaperEntry(2.88E-05, 2.96E-01, 1.10E+00, '+'),
        "mewdo": PaperEntry(3.93E-01, 1.36E+01, 9.40E+00, '+'),
        "mawdo": PaperEntry(9.84E-06, 2.98E-04, 2.58E-04, None),
    },
    "F16": {
        "gwo": PaperEntry(1.89E-01, 6.67E+00, 8.58E+00, '+'),
        "woa": PaperEntry(6.43E-06, 2.18E+00, 5.24E+00, '+'),
        "wdo": PaperEntry(1.65E-01, 8.97E+00, 8.34E+00, '+'),
        "awdo": PaperEntry(1.81E-05, 1.05E+00, 2.90E+00, '+'),
        "mewdo": PaperEntry(9.02E-02, 7.80E+00, 6.79E+00, '+'),
        "mawdo": PaperEntry(2.54E-05, 3.81E-04, 4.33E-04, None),
    },
}
"""Paper Table 3 (label ``tab:results``): function id -> algorithm -> entry."""

TABLE5: dict[str, dict[str, PaperEntry]] = {
    "F1": {
        "mawdo1": PaperEntry(0.0, 0.0, 0.0, None),
        "mawdo2": PaperEntry(0.0, 0.0, 0.0, None),
        "mawdo3": PaperEntry(0.0, 0.0, 0.0, None),
        "mawdo4": PaperEntry(0.0, 0.0, 0.0, None),
        "mawdo": PaperEntry(0.0, 0.0, 0.0, None),
    },
    "F2": {
        "mawdo1": PaperEntry(0.0, 0.0, 0.0, None),
        "mawdo2": PaperEntry(0.0, 0.0, 0.0, None),
        "mawdo3": PaperEntry(0.0, 0.0, 0.0, None),
        "mawdo4": PaperEntry(0.0, 0.0, 0.0, None),
        "mawdo": PaperEntry(0.0, 0.0, 0.0, None),
    },
    "F3": {
        "mawdo1": PaperEntry(0.0, 0.0, 0.0, None),
        "mawdo2": PaperEntry(0.0, 0.0, 0.0, None),
        "mawdo3": PaperEntry(0.0, 0.0, 0.0, None),
        "mawdo4": PaperEntry(0.0, 0.0, 0.0, None),
        "mawdo": PaperEntry(0.0, 0.0, 0.0, None),
    },
    "F4": {
        "mawdo1": PaperEntry(0.0, 0.0, 0.0, None),
        "mawdo2": PaperEntry(0.0, 0.0, 0.0, None),
        "mawdo3": PaperEntry(0.0, 0.0, 0.0, None),
        "mawdo4": PaperEntry(0.0, 0.0, 0.0, None),
        "mawdo": PaperEntry(0.0, 0.0, 0.0, None),
    },
    "F5": {
        "mawdo1": PaperEntry(4.68E-02, 1.91E+01, 1.27E+01, None),
        "mawdo2": PaperEntry(2.87E+01, 2.87E+01, 1.82E-03, None),
        "mawdo3": PaperEntry(9.97E-01, 2.64E+01, 7.14E+00, None),
        "mawdo4": PaperEntry(4.69E-01, 2.64E+01, 7.28E+00, None),
        "mawdo": PaperEntry(1.37E-02, 1.93E+01, 1.32E+01, None),
    },
    "F6": {
        "mawdo1": PaperEntry(1.23E-06, 1.78E-05, 1.72E-05, None),
        "mawdo2": PaperEntry(5.16E-06, 1.02E-04, 9.18E-05, None),
        "mawdo3": PaperEntry(1.83E-05, 1.14E-04, 9.42E-05, None),
        "mawdo4": PaperEntry(5.16E-06, 1.11E-04, 9.54E-05, None),
        "mawdo": PaperEntry(6.06E-07, 1.43E-05, 1.22E-05, None),
    },
    "F7": {
        "mawdo1": PaperEntry(0.0, 0.0, 0.0, None),
        "mawdo2": PaperEntry(0.0, 0.0, 0.0, None),
        "mawdo3": PaperEntry(0.0, 0.0, 0.0, None),
        "mawdo4": PaperEntry(0.0, 0.0, 0.0, None),
        "mawdo": PaperEntry(0.0, 0.0, 0.0, None),
    },
    "F8": {
        "mawdo1": PaperEntry(1.30E-23, 3.39E-19, 8.12E-19, None),
        "mawdo2": PaperEntry(6.41E-24, 6.28E-17, 1.39E-16, None),
        "mawdo3": PaperEntry(4.16E-20, 3.81E-16, 8.43E-16, None),
        "mawdo4": PaperEntry(9.41E-21, 2.55E-16, 6.18E-16, None),
        "mawdo": PaperEntry(4.94E-25, 7.05E-19, 1.54E-18, None),
    },
    "F9": {
        "mawdo1": PaperEntry(4.71E-08, 2.23E-06, 2.62E-06, None),
        "mawdo2": PaperEntry(5.68E-07, 1.67E-05, 1.89E-05, None),
        "mawdo3": PaperEntry(5.08E-07, 3.34E-05, 5.76E-05, None),
        "mawdo4": PaperEntry(7.47E-08, 2.94E-05, 3.44E-05, None),
        "mawdo": PaperEntry(2.38E-07, 1.80E-06, 1.42E-06, None),
    },
    "F10": {
        "mawdo1": PaperEntry(1.08E-06, 4.81E-05, 5.33E-05, None),
        "mawdo2": PaperEntry(1.16E-05, 1.00E-01, 5.38E-01, None),
        "mawdo3": PaperEntry(5.62E-06, 1.60E-01, 6.15E-01, None),
        "mawdo4": PaperEntry(1.56E-05, 2.01E-01, 7.47E-01, None),
        "mawdo": PaperEntry(8.60E-08, 1.33E-05, 1.48E-05, None),
    },
    "F11": {
        "mawdo1": PaperEntry(1.05E-62, 1.06E-49, 5.56E-49, None),
        "mawdo2": PaperEntry(4.57E-60, 5.57E-48, 2.43E-47, None),
        "mawdo3": PaperEntry(1.24E-57, 7.98E-47, 3.25E-46, None),
        "mawdo4": PaperEntry(4.60E-63, 2.53E-50, 9.42E-50, None),
        "mawdo": PaperEntry(7.41E-59, 1.39E-46, 6.80E-46, None),
    },
    "F12": {
        "mawdo1": PaperEntry(-1.00E+00, -1.00E+00, 5.88E-05, None),
        "mawdo2": PaperEntry(-1.00E+00, -1.00E+00, 1.18E-04, None),
        "mawdo3": PaperEntry(-1.00E+00, -1.00E+00, 8.21E-04, None),
        "mawdo4": PaperEntry(-9.98E-01, -2.02E-01, 3.65E-01, None),
        "mawdo": PaperEntry(-1.00E+00, -9.99E-01, 9.97E-04, None),
    },
    "F13": {
        "mawdo1": PaperEntry(8.49E-06, 1.68E-03, 2.37E-03, None),
        "mawdo2": PaperEntry(1.02E-03, 8.87E-02, 1.59E-01, None),
        "mawdo3": PaperEntry(1.08E-04, 1.23E-02, 1.74E-02, None),
        "mawdo4": PaperEntry(1.15E-12, 8.41E-02, 3.47E-01, None),
        "mawdo": PaperEntry(2.28E-05, 3.10E-04, 3.28E-04, None),
    },
    "F14": {
        "mawdo1": PaperEntry(3.00E+00, 3.03E+00, 2.47E-02, None),
        "mawdo2": PaperEntry(3.00E+00, 6.35E+00, 7.92E+00, None),
        "mawdo3": PaperEntry(3.00E+00, 3.12E+00, 2.08E-01, None),
        "mawdo4": PaperEntry(3.02E+00, 9.41E+00, 7.54E+00, None),
        "mawdo": PaperEntry(3.00E+00, 3.01E+00, 9.37E-03, None),
    },
    "F15": {
        "mawdo1": PaperEntry(9.68E-06, 6.55E-04, 9.51E-04, None),
        "mawdo2": PaperEntry(4.38E-05, 1.36E-01, 7.05E-01, None),
        "mawdo3": PaperEntry(1.20E-04, 1.47E-02, 2.24E-02, None),
        "mawdo4": PaperEntry(4.32E-04, 1.39E-02, 1.23E-02, None),
        "mawdo": PaperEntry(9.84E-06, 2.98E-04, 2.58E-04, None),
    },
    "F16": {
        "mawdo1": PaperEntry(6.76E-06, 4.00E-04, 5.12E-04, None),
        "mawdo2": PaperEntry(6.86E-05, 7.99E-03, 1.29E-02, None),
        "mawdo3": PaperEntry(5.38E-05, 1.56E-02, 1.59E-02, None),
        "mawdo4": PaperEntry(1.03E-04, 8.67E-03, 1.18E-02, None),
        "mawdo": PaperEntry(2.54E-05, 3.81E-04, None, None),
    },
}
"""Paper Table 5 (label ``tab:ablation``): no Wilcoxon row; F16 MAWDO Std is blank in the paper."""


def paper_entry(algorithm: str, paper_id: str | None) -> tuple[str, PaperEntry] | None:
    """The paper's entry for ``algorithm`` on function ``paper_id`` and the table it is from.

    Table 3 is preferred (it holds MAWDO's Wilcoxon context); the ablation variants come from
    Table 5. Returns None when the paper has no such cell.
    """
    if paper_id is None:
        return None
    for label, table in (("Table 3", TABLE3), ("Table 5", TABLE5)):
        entry = table.get(paper_id, {}).get(algorithm)
        if entry is not None:
            return label, entry
    return None
