"""The official input data of CEC 2017 and CEC 2022 (shifts, rotations, shuffles): where it
lives, which files a function needs, and reading them exactly as the official C code does.

The files are the competitions' own ``input_data`` text files. By default they are read from
the copies that ``opfunu`` (the optional extra ``bbob``) installs; those are byte for byte the
official ones once the official files' CRLF line ends are written as LF. The environment
variable ``MAWDO_CEC2017_DATA`` / ``MAWDO_CEC2022_DATA`` names another folder holding them
(e.g. the ``input_data`` folder of the official code). Every file is checked against the
SHA-256 of the official file (line ends ignored; ``mawdo/data/cec_input_data.sha256``) before
it is read, so a damaged or foreign file is refused by name.

Reading follows ``cec17_test_func.cpp`` / ``cec22_test_func.cpp``: a rotation matrix is the first
``D*D`` numbers of ``M_<f>_D<D>.txt`` (row-major; a composition's ``k`` matrices follow one
another), a shift vector the first ``D`` numbers of ``shift_data_<f>.txt`` (a composition's
``k`` vectors are the first ``D`` numbers of its first ``k`` lines), a shuffle the first ``D``
(or ``k*D``) integers of ``shuffle_data_<f>_D<D>.txt``, 1-based.
"""

from __future__ import annotations

import functools
import hashlib
import importlib.util
import os
from dataclasses import dataclass
from importlib import resources
from pathlib import Path

import numpy as np

from mawdo.suites.base import INSTALL_HINT, MissingExtraError

ENV = {2017: "MAWDO_CEC2017_DATA", 2022: "MAWDO_CEC2022_DATA"}
"""Environment variables naming a folder of official input data, per year."""

MANIFEST = "cec_input_data.sha256"


class CECDataError(ValueError):
    """A CEC data file is missing, damaged or not the official one; the message names the
    function, the file and the fix."""


@functools.cache
def manifest() -> dict[tuple[int, str], str]:
    """``{(year, file name): sha256 of the official file with CR bytes removed}``."""
    text = resources.files("mawdo.data").joinpath(MANIFEST).read_text(encoding="ascii")
    out = {}
    for line in text.splitlines():
        year, name, digest = line.split()
        out[int(year), name] = digest
    return out


@dataclass(frozen=True)
class FunctionData:
    """What one function needs from the data: ``k`` shifts, ``k`` rotations, a shuffle.

    Attributes
    ----------
    year, fid : int
        Competition year and official function number.
    n_shift : int
        Shift vectors read (1, or the composition's number of components).
    n_matrix : int
        Rotation matrices read (likewise).
    shuffle : int
        Shuffle length in units of D: 0 (none), 1 (hybrid), ``k`` (composition of hybrids).
    composition : bool
        Shift vectors one per line (composition layout) instead of the file's first D numbers.
    """

    year: int
    fid: int
    n_shift: int = 1
    n_matrix: int = 1
    shuffle: int = 0
    composition: bool = False

    def files(self, dim: int) -> list[str]:
        """The names of the files this function reads in dimension ``dim``."""
        out = [f"M_{self.fid}_D{dim}.txt", f"shift_data_{self.fid}.txt"]
        if self.shuffle:
            out.append(f"shuffle_data_{self.fid}_D{dim}.txt")
        return out

    def dims(self) -> tuple[int, ...]:
        """Dimensions for which every file this function needs is an official file."""
        known = manifest()
        return tuple(
            d
            for d in (2, 10, 20, 30, 50, 100)
            if all((self.year, name) in known for name in self.files(d))
        )


def data_folder(year: int) -> Path:
    """The folder the data of CEC ``year`` is read from (see the module notes).

    Raises
    ------
    MissingExtraError
        No folder named by the environment and ``opfunu`` is not installed.
    CECDataError
        The environment names a folder that does not exist.
    """
    env = os.environ.get(ENV[year])
    if env:
        path = Path(env)
        if not path.is_dir():
            raise CECDataError(
                f"{ENV[year]}={env!r} is not a folder; point it at a folder holding the official "
                f"CEC {year} input_data files, or unset it to use opfunu's copies"
            )
        return path
    spec = importlib.util.find_spec("opfunu")
    folder = None
    if spec is not None and spec.submodule_search_locations:
        folder = Path(spec.submodule_search_locations[0]) / "cec_based" / f"data_{year}"
    if folder is None or not folder.is_dir():
        raise MissingExtraError(
            f"suite 'cec{year}' needs the package 'opfunu' for the official CEC {year} data "
            f"files it ships, which is not installed (it comes with the optional extra 'bbob'): "
            f"{INSTALL_HINT}; or set {ENV[year]} to a folder holding the official input_data "
            "files"
        )
    return folder


def read_checked(year: int, fid: int, name: str, folder: Path | None = None) -> str:
    """The text of the official data file ``name`` of CEC ``year`` F``fid``, checked.

    Raises
    ------
    CECDataError
        The file is missing, unreadable, or differs from the official file.
    """
    path = (folder or data_folder(year)) / name
    where = f"CEC {year} F{fid} needs {path}"
    try:
        raw = path.read_bytes()
    except FileNotFoundError:
        raise CECDataError(
            f"{where}, which does not exist; reinstall opfunu (pip install --force-reinstall "
            f"opfunu) or point {ENV[year]} at a folder holding the official input_data files"
        ) from None
    except OSError as exc:
        raise CECDataError(f"{where}, which cannot be read: {exc.strerror or exc}") from None
    want = manifest().get((year, name))
    got = hashlib.sha256(raw.replace(b"\r", b"")).hexdigest()
    if got != want:
        raise CECDataError(
            f"{where}, which is damaged: it is not the official file (SHA-256 {got[:16]}..., "
            f"the official file's is {str(want)[:16]}...); reinstall opfunu or restore the file "
            f"from the official input_data"
        )
    return raw.decode("ascii")


def _numbers(text: str, count: int, what: str, dtype=float) -> np.ndarray:
    tokens = text.split()
    if len(tokens) < count:
        raise CECDataError(f"{what} holds {len(tokens)} numbers, fewer than the {count} needed")
    return np.array([dtype(t) for t in tokens[:count]], dtype=dtype)


@dataclass(frozen=True)
class Data:
    """The arrays of one function in one dimension.

    Attributes
    ----------
    shift : numpy.ndarray
        ``(k, D)`` shift vectors (``k = 1`` unless a composition).
    matrix : numpy.ndarray
        ``(k, D, D)`` rotation matrices ``M``, applied as ``z = M @ y``.
    shuffle : numpy.ndarray or None
        ``(k, D)`` 0-based permutations (the files hold them 1-based); None if unused.
    """

    shift: np.ndarray
    matrix: np.ndarray
    shuffle: np.ndarray | None


def load(need: FunctionData, dim: int) -> Data:
    """The data of ``need`` in dimension ``dim`` from :func:`data_folder`, read once per
    process and folder (cached)."""
    return _load(need, dim, data_folder(need.year))


@functools.lru_cache(maxsize=32)
def _load(need: FunctionData, dim: int, folder: Path) -> Data:
    if dim not in need.dims():
        raise CECDataError(
            f"CEC {need.year} F{need.fid}: the official data do not cover D={dim} "
            f"(they cover D in {need.dims()})"
        )
    m_name, s_name, *rest = need.files(dim)
    text = read_checked(need.year, need.fid, m_name, folder)
    matrix = _numbers(text, need.n_matrix * dim * dim, m_name)
    text = read_checked(need.year, need.fid, s_name, folder)
    if need.composition:
        lines = [ln for ln in text.splitlines() if ln.strip()]
        if len(lines) < need.n_shift:
            raise CECDataError(f"{s_name} holds {len(lines)} lines, fewer than {need.n_shift}")
        shift = np.stack([_numbers(ln, dim, s_name) for ln in lines[: need.n_shift]])
    else:
        shift = _numbers(text, dim, s_name)[None]
    shuffle = None
    if rest:
        text = read_checked(need.year, need.fid, rest[0], folder)
        shuffle = _numbers(text, need.shuffle * dim, rest[0], dtype=int).reshape(-1, dim) - 1
    matrix = matrix.reshape(need.n_matrix, dim, dim)
    for arr in (matrix, shift):
        arr.flags.writeable = False
    return Data(shift=shift, matrix=matrix, shuffle=shuffle)
