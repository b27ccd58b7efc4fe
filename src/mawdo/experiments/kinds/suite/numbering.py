"""What a suite plan's function ids mean: the official CEC numbers, or (in stores written when
``cec2017`` / ``cec2022`` were computed by opfunu) opfunu's.

A plan of a CEC suite carries ``numbering``: ``"official"`` for every new plan (part of its
hash), ``"opfunu"`` for a plan read back from such an old store (not in its hash, which stays
the one its store holds). docs/bbob.md and docs/deviations.md#d-cec-opfunu say why.
"""

from __future__ import annotations

from mawdo.suites.cec import OPFUNU_NUMBERING, official_id

CEC_SUITES = ("cec2017", "cec2022")
"""Suites whose name meant opfunu's functions (and, for CEC 2017, opfunu's numbers) in stores
written before the batched official suites."""


def default_numbering(suite: str, stored: bool) -> str | None:
    """The numbering of a plan that names none: a store's CEC plan is opfunu's, a new one the
    official; other suites have none."""
    if suite not in CEC_SUITES:
        return None
    return "opfunu" if stored else "official"


def check_numbering(numbering: str | None, suite: str | None, stored: bool) -> None:
    """Refuse a numbering on another suite, and ``"opfunu"`` on a new plan."""
    if numbering is not None and suite is not None and suite not in CEC_SUITES:
        raise ValueError(f"applies to the suites {', '.join(CEC_SUITES)} only, not {suite}")
    if numbering == "opfunu" and not stored:
        raise ValueError(
            "'opfunu' marks stores written when cec2017/cec2022 meant opfunu's functions; "
            "a new plan uses the official suites (cec2017, cec2022) or cec2017-opfunu / "
            "cec2022-opfunu"
        )


def computed_by(suite: str, numbering: str | None, fid: int) -> tuple[str, int]:
    """The registered suite and function id that compute a plan's function ``fid``."""
    if numbering == "opfunu":
        return f"{suite}-opfunu", official_id(int(suite[3:]), fid)
    return suite, fid


def numbering_note(suite: str, numbering: str | None) -> str:
    """How a plan's function ids relate to the official ones ("" for official ids)."""
    if numbering != "opfunu":
        return ""
    how = OPFUNU_NUMBERING + "; " if suite == "cec2017" else ""
    return (
        f"Functions as opfunu 1.0.4 computes them ({how}its values depart from the official "
        f"code's, docs/deviations.md#d-cec-opfunu): this store was made when the suite "
        f"{suite} meant opfunu's functions; the suite {suite} now is the official "
        f"code's, and {suite}-opfunu is opfunu's under the official numbers."
    )
