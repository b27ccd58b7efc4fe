"""One update step of WDO, AWDO and GWO on tiny hand-set populations with fixed draws (WOA:
test_woa_reference.py), compared with the update worked out independently here (scalar loops)."""

import numpy as np
import pytest

from mawdo import make_optimizer
from mawdo.optimizers.base import Space
from mawdo.optimizers.gwo import GWOState, update_leaders_demoting, update_leaders_reference
from mawdo.optimizers.wdo import WindState

from .fixed_streams import FixedStreams

SPACE = Space(np.array([-10.0, 0.0]), np.array([10.0, 4.0]))  # D = 2, anisotropic box


def wind_state(opt, p, u, f, pbest, pbest_f, streams, t=3, T=10):
    N = p.shape[1]
    from mawdo.optimizers.wind import partition

    return WindState(
        p=p,
        u=u,
        f=f,
        pbest=pbest,
        pbest_f=pbest_f,
        gid=partition(N, opt.params.groups),
        coef=None,
        vmax=opt.params.vmax,
        low_dim=False,
        t=t,
        T=T,
        space=SPACE,
        streams=streams,
    )


P0 = np.array([[[0.5, -0.2], [-0.9, 0.8], [0.1, 0.95]]])
U0 = np.array([[[0.1, -0.05], [0.2, 0.25], [-0.3, 0.0]]])
F0 = np.array([[4.0, 1.0, 9.0]])  # ranks: parcel1 = 1, parcel0 = 2, parcel2 = 3
PB = np.array([[[0.4, -0.1], [-0.9, 0.8], [0.0, 0.9]]])
PBF = np.array([[3.0, 1.0, 8.0]])  # global best-so-far = parcel 1's pbest
PERM = np.array([[[1, 0], [0, 1], [1, 0]]])


def test_wdo_step_by_hand():
    opt = make_optimizer("wdo", pop_size=3)
    st = wind_state(opt, P0.copy(), U0.copy(), F0, PB, PBF, FixedStreams(permutations=[PERM]))
    X = opt.ask(st)
    alpha, g, RT, c, vmax = 0.4, 0.2, 3.0, 0.4, 0.3
    rank = {0: 2, 1: 1, 2: 3}
    gbest = [-0.9, 0.8]
    for i in range(3):
        for d in range(2):
            up = U0[0, i, PERM[0, i, d]]
            v = (
                (1 - alpha) * U0[0, i, d]
                - g * P0[0, i, d]
                + abs(1 - 1 / rank[i]) * RT * (gbest[d] - P0[0, i, d])
                + c * up / rank[i]
            )
            v = max(-vmax, min(vmax, v))
            p = max(-1.0, min(1.0, P0[0, i, d] + v))
            lo, hi = SPACE.lb[d], SPACE.ub[d]
            assert st.u[0, i, d] == pytest.approx(v, abs=1e-15)
            assert X[0, i, d] == pytest.approx(lo + (p + 1) / 2 * (hi - lo), abs=1e-12)
    # the best parcel feels no pressure: its move is friction + gravity + Coriolis only
    assert st.u[0, 1, 1] == pytest.approx(0.6 * 0.25 - 0.2 * 0.8 + 0.4 * 0.25, abs=1e-15)


def test_awdo_step_by_hand():
    opt = make_optimizer("awdo", pop_size=3)
    coef = np.array([[[0.3, 0.6, 0.8, 0.5]]])  # a_t, g_t, RT_t, c_t drawn once per iteration
    st = wind_state(
        opt, P0.copy(), U0.copy(), F0, PB, PBF, FixedStreams(permutations=[PERM], random=[coef])
    )
    opt.ask(st)
    a, g, RT, c = coef[0, 0]
    rank = {0: 2, 1: 1, 2: 3}
    for i in range(3):
        for d in range(2):
            up = U0[0, i, PERM[0, i, d]]
            v = (
                (1 - a) * U0[0, i, d]
                - g * P0[0, i, d]
                + RT * ([-0.9, 0.8][d] - P0[0, i, d]) / rank[i]
                + c * up / rank[i]
            )
            assert st.u[0, i, d] == pytest.approx(max(-0.3, min(0.3, v)), abs=1e-15)


def literal_gwo_leaders(lead_f, lead_x, F, X):
    """GWO.m's leader update, transcribed literally (sequential, strict comparisons)."""
    a, b, d = lead_f
    ax, bx, dx = lead_x
    for f, x in zip(F, X, strict=True):
        if f < a:
            a, ax = f, x
        if a < f < b:
            b, bx = f, x
        if f > a and f > b and f < d:
            d, dx = f, x
    return np.array([a, b, d]), np.array([ax, bx, dx])


@pytest.mark.parametrize("seed", range(30))
def test_gwo_vectorised_leaders_equal_the_literal_loop(seed):
    rng = np.random.default_rng(seed)
    R, N, D = 4, 9, 2
    F = rng.integers(0, 6, (R, N)).astype(float)  # many ties on purpose
    X = rng.normal(size=(R, N, D))
    lead_f = np.sort(rng.integers(0, 8, (R, 3)).astype(float), axis=1)
    lead_f[0] = np.inf  # first iteration
    lead_x = rng.normal(size=(R, 3, D))
    got_f, got_x = update_leaders_reference(lead_f, lead_x, F, X)
    for r in range(R):
        ef, ex = literal_gwo_leaders(lead_f[r], lead_x[r], F[r], X[r])
        np.testing.assert_array_equal(got_f[r], ef)
        np.testing.assert_array_equal(got_x[r], ex)


def test_gwo_reference_does_not_demote_but_option_does():
    F = np.array([[5.0, 3.0, 1.0]])  # each wolf beats the last: GWO.m only moves alpha
    X = np.arange(6.0).reshape(1, 3, 2)
    f_ref, _ = update_leaders_reference(np.full((1, 3), np.inf), np.zeros((1, 3, 2)), F, X)
    f_dem, x_dem = update_leaders_demoting(np.full((1, 3), np.inf), np.zeros((1, 3, 2)), F, X)
    np.testing.assert_array_equal(f_ref[0], [1.0, np.inf, np.inf])
    np.testing.assert_array_equal(f_dem[0], [1.0, 3.0, 5.0])
    np.testing.assert_array_equal(x_dem[0, 1], [2.0, 3.0])


def test_gwo_step_by_hand():
    opt = make_optimizer("gwo", pop_size=2)
    X0 = np.array([[[1.0, 2.0], [-3.0, 0.5]]])
    lead = np.array([[[0.5, 1.0], [2.0, 3.0], [-1.0, 0.2]]])
    r = np.random.default_rng(0).random((1, 2, 3, 2, 2))
    st = GWOState(
        X=X0.copy(),
        lead_f=np.array([[1.0, 2.0, 3.0]]),
        lead_x=lead,
        t=4,
        T=10,
        space=SPACE,
        streams=FixedStreams(random=[r]),
    )
    X = opt.ask(st)
    a = 2 - 2 * (4 - 1) / 10
    for i in range(2):
        for d in range(2):
            acc = 0.0
            for k in range(3):
                r1, r2 = r[0, 0, k, i, d], r[0, 1, k, i, d]
                A, C = 2 * a * r1 - a, 2 * r2
                acc += lead[0, k, d] - A * abs(C * lead[0, k, d] - X0[0, i, d])
            expect = min(max(acc / 3, SPACE.lb[d]), SPACE.ub[d])
            assert X[0, i, d] == pytest.approx(expect, abs=1e-12)
