"""Problem keys of the suite study (``"f03_i02_d20"``) and the command line's id lists."""

from __future__ import annotations

import re

__all__ = ["parse_ids", "parse_key", "problem_key"]


def problem_key(fid: int, iid: int, dim: int) -> str:
    """The canonical name of one problem: ``"f03_i02_d20"`` (sorts by function, then instance)."""
    return f"f{fid:02d}_i{iid:02d}_d{dim:02d}"


def parse_key(key: str) -> tuple[int, int, int]:
    """``"f03_i02_d20"`` -> ``(3, 2, 20)``."""
    m = re.fullmatch(r"f(\d+)_i(\d+)_d(\d+)", key)
    if m is None:
        raise ValueError(f"{key!r} is not a problem key of the form f03_i02_d20")
    return int(m[1]), int(m[2]), int(m[3])


def parse_ids(text: str, what: str = "ids") -> list[int | str]:
    """Command-line id lists: ``"1-24"``, ``"1,3,5-7"``; non-numeric items stay names.

    Raises
    ------
    ValueError
        An empty list or a reversed range, naming ``what``.
    """
    out: list[int | str] = []
    for item in (t.strip() for t in str(text).split(",")):
        if not item:
            continue
        m = re.fullmatch(r"(\d+)\s*-\s*(\d+)", item)
        if m:
            lo, hi = int(m[1]), int(m[2])
            if lo > hi:
                raise ValueError(f"{what}: range {item!r} runs backwards; write {hi}-{lo}")
            out.extend(range(lo, hi + 1))
        elif item.isdigit():
            out.append(int(item))
        else:
            out.append(item)
    if not out:
        raise ValueError(f"{what}: give at least one (e.g. 1-24 or 1,3,5)")
    return out
