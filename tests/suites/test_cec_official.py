"""The batched CEC 2017 / CEC 2022 suites give the official C code's values (tests/data/cec)
on random points, near the optimum and at the box's corners, in every function and dimension
the official data cover; bad input is named."""

import pickle

import numpy as np
import pytest

from mawdo.suites import SUITES, get_problem
from mawdo.suites.cec_tables import TABLES
from tests.suites.cec_reference import OfficialCEC, compiler

RTOL = 1e-12


@pytest.fixture(scope="module")
def official(tmp_path_factory):
    if compiler() is None:
        pytest.skip("no C++ compiler (g++, c++ or clang++) on PATH to build the official code")
    build = tmp_path_factory.mktemp("cec_official")
    return {year: OfficialCEC(year, build) for year in (2017, 2022)}


def cases(big: bool):
    for year, table in TABLES.items():
        for fn in table:
            for dim in fn.data.dims():
                if (dim > 30) == big:
                    yield pytest.param(year, fn.fid, dim, id=f"{year}-F{fn.fid}-D{dim}")


def probe_points(f, seed):
    """Uniform points, the optimum and points within 1e-6 / 1e-2 of it, corners."""
    rng = np.random.default_rng(seed)
    d = f.dim
    corners = [np.full(d, 100.0), np.full(d, -100.0), np.where(rng.random(d) < 0.5, -100.0, 100.0)]
    near = f.x_star + rng.normal(0, 1, (4, d)) * np.array([[1e-6], [1e-6], [1e-2], [1e-2]])
    return np.vstack([rng.uniform(-100, 100, (24, d)), f.x_star, near, *corners])


def check_against_c(official, year, fid, dim):
    f = get_problem(f"cec{year}", fid, dim=dim)
    X = probe_points(f, year * 1000 + fid * 10 + dim)
    want = official[year](fid, X)
    np.testing.assert_allclose(f(X), want, rtol=RTOL, atol=0)
    np.testing.assert_allclose(f(X[24]), f.f_star, rtol=RTOL, atol=0)  # optimum value = bias


@pytest.mark.parametrize(("year", "fid", "dim"), list(cases(big=False)))
def test_values_equal_the_official_code(official, year, fid, dim):
    check_against_c(official, year, fid, dim)


@pytest.mark.slow
@pytest.mark.parametrize(("year", "fid", "dim"), list(cases(big=True)))
def test_values_equal_the_official_code_in_d50_and_d100(official, year, fid, dim):
    check_against_c(official, year, fid, dim)


def test_the_official_numbering_and_optima():
    s17, s22 = SUITES["cec2017"], SUITES["cec2022"]
    assert s17.functions == tuple(range(1, 31)) and s22.functions == tuple(range(1, 13))
    assert get_problem("cec2017", 2, dim=10).function_name == "SumDiffPow"
    assert get_problem("cec2017", "zakharov", dim=10).function_id == 3
    assert [get_problem("cec2017", k, dim=10).f_star for k in (1, 17, 30)] == [100, 1700, 3000]
    assert [get_problem("cec2022", k, dim=10).f_star for k in (1, 6, 12)] == [300, 1800, 2700]
    # the dimensions are those the official files cover: F20 (hybrid 10) has D=20 data
    assert s17.dims(20) == (10, 20, 30, 50, 100) and s17.dims(11) == (10, 30, 50, 100)
    assert s17.dims(21) == (2, 10, 20, 30, 50, 100) and s22.dims(6) == (10, 20)


@pytest.mark.parametrize("year", [2017, 2022])
def test_a_point_has_one_value_whatever_its_batch_and_problems_pickle(year):
    # a run's numbers must not depend on the other runs of its block: batches cut across the
    # kernel's blocks of 128 points and below its 8 points of a full vector pass
    X = np.random.default_rng(0).uniform(-100, 100, (300, 10))
    cuts = [0, 1, 8, 15, 143, 300]
    for fn in TABLES[year]:
        f = get_problem(f"cec{year}", fn.fid, dim=10)
        whole = f(X)
        parts = [f(X[a:b]) for a, b in zip(cuts[:-1], cuts[1:], strict=True)]
        np.testing.assert_array_equal(np.concatenate(parts), whole)
        np.testing.assert_array_equal([f(x[None])[0] for x in X[:20]], whole[:20])
        np.testing.assert_array_equal(pickle.loads(pickle.dumps(f))(X), whole)
        np.testing.assert_array_equal(f(np.asfortranarray(X)), whole)  # any memory layout


def test_each_basic_function_code_runs_the_function_of_that_name():
    from mawdo.suites import cec_basic as B
    from mawdo.suites.cec_kernels import basic

    z = np.random.default_rng(1).uniform(-3, 3, (7, 16))
    for code, name in enumerate(B.NAMES[:-1]):  # the bi-Rastrigin has its own path
        t, got, want = B.constants(code, 7), np.empty(16), np.empty(16)
        basic(code, z, 7, 16, t, got)
        if name.startswith("levy"):
            B.levy(z, 7, 16, 1.0 if name == "levy2017" else 0.0, want)
        elif name in ("happycat", "hgbat"):
            B.cat(z, 7, 16, name == "hgbat", want)
        else:
            getattr(B, name)(z, 7, 16, t, want)
        np.testing.assert_array_equal(got, want, err_msg=name)
    out = np.empty(16)
    basic(B.BI_RASTRIGIN, z, 7, 16, np.zeros(B.WIDTH), out)
    assert np.isnan(out).all()


def test_unknown_function_and_uncovered_dimension_are_named():
    with pytest.raises(ValueError, match="cec2017 defines functions 1-30"):
        get_problem("cec2017", 31, dim=10)
    with pytest.raises(ValueError, match=r"cec2017 f11 is not defined in dimension 20; .* 10, 30"):
        get_problem("cec2017", 11, dim=20)
    with pytest.raises(ValueError, match=r"cec2022 f12 is not defined in dimension 30; .*20"):
        get_problem("cec2022", 12, dim=30)
    with pytest.raises(ValueError, match=r"takes points of shape \(n, 10\)"):
        get_problem("cec2022", 1, dim=10).func(np.zeros((3, 11)))


@pytest.fixture
def data_copy(tmp_path, monkeypatch):
    """A copy of the CEC 2022 data named by MAWDO_CEC2022_DATA (reads are cached per folder)."""
    import shutil

    from mawdo.suites.cec_data import data_folder

    folder = tmp_path / "input_data"
    shutil.copytree(data_folder(2022), folder)
    monkeypatch.setenv("MAWDO_CEC2022_DATA", str(folder))
    return folder


def test_a_missing_or_damaged_data_file_is_named_with_its_function(data_copy):
    from mawdo.suites.cec_data import CECDataError

    assert get_problem("cec2022", 7, dim=10).func.data.shuffle.shape == (1, 10)  # the copy works
    (data_copy / "shuffle_data_8_D20.txt").unlink()
    with pytest.raises(CECDataError, match=r"CEC 2022 F8 needs .*shuffle_data_8_D20\.txt, which "
                       r"does not exist; reinstall opfunu .* MAWDO_CEC2022_DATA"):  # fmt: skip
        get_problem("cec2022", 8, dim=20)
    text = (data_copy / "shift_data_3.txt").read_text()
    (data_copy / "shift_data_3.txt").write_text(text[:-40])  # a truncated file
    with pytest.raises(CECDataError, match=r"CEC 2022 F3 needs .*shift_data_3\.txt, which is "
                       r"damaged: it is not the official file"):  # fmt: skip
        get_problem("cec2022", 3, dim=2)


def test_the_check_before_a_study_reads_every_file_it_needs(data_copy):
    from mawdo.suites.cec_data import CECDataError

    (data_copy / "M_12_D20.txt").write_text("0 " * 2400)  # enough numbers, not the official
    SUITES["cec2022"].check_problems([1, 12], [10])  # D = 20 is not asked: fine
    with pytest.raises(CECDataError, match=r"CEC 2022 F12 needs .*M_12_D20\.txt.*damaged"):
        SUITES["cec2022"].check_problems([1, 12], [10, 20])
