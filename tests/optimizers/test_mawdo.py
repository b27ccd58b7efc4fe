"""MAWDO's mechanisms, one at a time, on hand-set populations (paper Section 3)."""

import numpy as np
import pytest

from mawdo import OPTIMIZERS, make_optimizer, minimize
from mawdo.optimizers import wind
from mawdo.optimizers.base import Space
from mawdo.optimizers.boundary import reflect_damped
from mawdo.optimizers.wdo import WindState
from mawdo.streams import RunStreams

from .fixed_streams import FixedStreams


def test_schedule_weights_at_the_ends_and_middle():
    assert wind.schedule_weights(1, 500) == pytest.approx((0.6, 0.3, 0.1))
    assert wind.schedule_weights(500, 500) == pytest.approx((0.2, 0.3, 0.5))
    w = wind.schedule_weights(3, 5)  # lambda = 0.5
    assert w == pytest.approx((0.4, 0.3, 0.3))
    assert sum(w) == pytest.approx(1.0)


def test_distance_gate_values():
    D = 4
    d_max = 2 * np.sqrt(D)  # diagonal of [-1,1]^4 = 4
    tbest = np.zeros((1, D))
    gbest = np.array([[[0, 0, 0, 0], [2, 0, 0, 0], [1, 1, 1, 1], [1, 1, 1, 1.0]]])
    gbest[0, 3] = [2, 2, 2, 2]  # farther than d_max is impossible in the box; clip at 1 anyway
    gate = wind.distance_gate(gbest, tbest, d_max)
    np.testing.assert_allclose(gate, [[0.0, 0.5, 0.5, 1.0]])
    gate2 = wind.distance_gate(gbest * 10, tbest, d_max)
    assert gate2[0, 3] == 1.0  # min(1, .)


def test_hierarchical_guidance_is_renormalised():
    pbest = np.array([[[1.0, 0.0]]])
    gbest = np.array([[[0.0, 1.0]]])
    tbest = np.array([[-1.0, -1.0]])
    B = wind.hierarchical_guidance(pbest, gbest, tbest, 0.6, 0.3, np.array([[0.05]]))
    expect = (0.6 * np.array([1, 0]) + 0.3 * np.array([0, 1]) + 0.05 * np.array([-1, -1])) / 0.95
    np.testing.assert_allclose(B[0, 0], expect)
    # identical leaders give B equal to them whatever the weights (no shrink toward 0)
    same = np.array([[[0.7, -0.4]]])
    B = wind.hierarchical_guidance(same, same, same[:, 0], 0.2, 0.3, np.array([[0.0]]))
    np.testing.assert_allclose(B[0, 0], [0.7, -0.4])


def test_reflection_past_each_bound():
    p = np.array([1.2, -1.3, 0.5, 3.5])
    u = np.array([0.4, -0.6, 0.1, 3.0])
    q, v = reflect_damped(p, u, -1.0, 1.0, eta=0.5)
    np.testing.assert_allclose(q, [0.8, -0.7, 0.5, -1.0])  # 2*1-3.5 = -1.5 -> clipped to -1
    np.testing.assert_allclose(v, [-0.2, 0.3, 0.1, -1.5])


def test_partition_and_group_ranks():
    gid = wind.partition(50, 8)
    np.testing.assert_array_equal(np.bincount(gid), [7, 7, 6, 6, 6, 6, 6, 6])
    assert np.all(np.diff(gid) >= 0)  # contiguous
    F = np.array([[5.0, 1.0, 3.0, 9.0, 2.0, 2.5, 0.1]])
    g = wind.partition(7, 2)  # groups 0..3 and 4..6
    np.testing.assert_array_equal(wind.group_ranks(F, g, 2), [[3, 1, 2, 4, 2, 3, 1]])
    np.testing.assert_array_equal(wind.group_argmin(F, g, 2), [[1, 6]])
    with pytest.raises(ValueError, match="groups"):
        wind.partition(5, 6)


def test_group_centroid():
    p = np.arange(12.0).reshape(1, 6, 2)
    c = wind.group_centroid(p, wind.partition(6, 2), 2)
    np.testing.assert_allclose(c[0], [[2.0, 3.0], [8.0, 9.0]])


def make_state(opt, R=1, N=10, D=4, t=1, T=100, seed=0):
    space = Space(np.full(D, -1.0), np.full(D, 1.0))
    st = opt.init(space, RunStreams.from_seed_sequences(np.random.SeedSequence(seed).spawn(R)), T)
    st.t = t
    rng = np.random.default_rng(seed)
    st.f = rng.permutation(N)[None, :].astype(float).repeat(R, 0)
    st.pbest_f = st.f.copy()
    return st


@pytest.mark.parametrize("t", [1, 2, 4, 5, 8, 10])
def test_restart_only_every_K_and_only_the_worst(t):
    opt = make_optimizer("mawdo3", pop_size=10, restart_every=4, restart_frac=0.3)
    st = make_state(opt, t=t)
    f = st.f.copy()
    X = opt.ask(st)
    if t % 4:
        assert st.restarted is None and X.shape == (1, 10, 4)
        return
    worst = np.sort(np.argsort(f[0])[-3:])
    np.testing.assert_array_equal(np.sort(st.restarted[0]), worst)
    assert X.shape == (1, 13, 4)  # 3 opposites appended (OBL)
    np.testing.assert_allclose(X[0, 10:], -X[0, st.restarted[0]])
    assert np.all(st.u[0, st.restarted[0]] == 0.0)
    others = np.setdiff1d(np.arange(10), worst)
    assert np.all(st.u[0, others] != 0.0)


def test_restart_samples_around_tbest_with_decaying_sigma():
    opt = make_optimizer(
        "mawdo3", pop_size=10, restart_every=1, restart_frac=0.2, sigma0=0.5, sigma_end=0.05
    )
    st = make_state(opt, t=50, T=100)
    tb = st.pbest[0, np.argmin(st.pbest_f[0])].copy()
    z = np.full((1, 2, 4), 0.1)
    st.streams = _Delegate(st.streams, normal=z)
    opt.ask(st)
    sigma = 0.5 - (0.5 - 0.05) * 50 / 100
    expect = np.tile(np.clip(tb + sigma * 0.1, -1, 1), (2, 1))
    np.testing.assert_allclose(st.p[0, st.restarted[0]], expect)


class _Delegate:
    """Real streams, except for one prescribed draw."""

    def __init__(self, inner, **fixed):
        self.inner, self.fixed = inner, fixed
        self.runs = inner.runs

    def __getattr__(self, name):
        if name in self.fixed:
            val = self.fixed.pop(name)
            return lambda *a, **k: val
        return getattr(self.inner, name)


def test_obl_keeps_the_better_of_each_pair():
    opt = make_optimizer("mawdo3", pop_size=6, restart_every=1, restart_frac=0.34)  # m = 2
    st = make_state(opt, N=6, D=2, t=1)
    X = opt.ask(st)
    r0, r1 = st.restarted[0]
    P = st.p.copy()
    F = np.arange(8.0)[None, :] + 10
    F[0, r0], F[0, 6] = 5.0, 1.0  # opposite better -> take it
    F[0, r1], F[0, 7] = 2.0, 3.0  # original better -> keep it
    opt.tell(st, X, F)
    np.testing.assert_allclose(st.p[0, r0], -P[0, r0])
    np.testing.assert_allclose(st.p[0, r1], P[0, r1])
    assert st.f[0, r0] == 1.0 and st.f[0, r1] == 2.0
    assert st.f.shape == (1, 6)


def test_obl_evaluations_are_counted():
    res = minimize(
        lambda X: (X**2).sum(1),
        [(-3, 3)] * 5,
        algorithm="mawdo3",
        runs=2,
        seed=0,
        max_iter=101,
        pop_size=20,
        restart_every=10,
        restart_frac=0.1,
    )
    # restarts after iterations 10, 20, ..., 100: 10 restarts x 2 opposites
    assert np.all(res.nfev == 20 * 101 + 10 * 2)


@pytest.mark.parametrize(
    "D,low_dim,active", [(2, 3, True), (3, 3, True), (4, 3, False), (4, 5, True), (1, 0, False)]
)
def test_low_dim_switches_exactly_at_threshold(D, low_dim, active):
    opt = make_optimizer("mawdo", pop_size=16, low_dim=low_dim)
    st = opt.init(
        Space(np.full(D, -2.0), np.full(D, 2.0)),
        RunStreams([np.random.default_rng(1), np.random.default_rng(2)]),
        50,
    )
    assert st.low_dim is active
    assert st.vmax == pytest.approx(0.075 if active else 0.3)
    assert np.all(np.abs(st.u) <= st.vmax)
    if active:
        assert st.coef.shape == (2, 8, 4)
        lo, hi = np.array([0.15, 0.15, 0.9, 0.1]), np.array([0.45, 0.45, 1.5, 0.5])
        assert np.all(st.coef >= lo) and np.all(st.coef <= hi)
        assert len(np.unique(st.coef[0, :, 2])) == 8  # heterogeneous across groups
    else:
        assert st.coef is None


def test_low_dim_step_uses_group_coefficients_and_centroid_gravity():
    opt = make_optimizer("mawdo4", pop_size=4, groups=2)  # guidance global, population ranks
    D = 2
    space = Space(np.full(D, -1.0), np.full(D, 1.0))
    p = np.array([[[0.2, 0.4], [-0.4, 0.0], [0.6, -0.6], [0.0, 0.2]]])
    u = np.zeros_like(p) + 0.01
    coef = np.array([[[0.2, 0.3, 1.0, 0.4], [0.4, 0.2, 1.2, 0.1]]])
    f = np.array([[3.0, 1.0, 4.0, 2.0]])
    perm = np.array([[[1, 0], [0, 1], [0, 1], [1, 0]]])
    st = WindState(
        p=p.copy(),
        u=u.copy(),
        f=f,
        pbest=p.copy(),
        pbest_f=f.copy(),
        gid=wind.partition(4, 2),
        coef=coef,
        vmax=0.075,
        low_dim=True,
        t=2,
        T=10,
        space=space,
        streams=FixedStreams(permutations=[perm]),
    )
    opt.ask(st)
    rank = [3, 1, 4, 2]
    B = p[0, 1]  # global best
    for i in range(4):
        g_ = i // 2
        a, g, RT, c = coef[0, g_]
        centre = p[0, 2 * g_ : 2 * g_ + 2].mean(axis=0)
        for d in range(2):
            v = (
                (1 - a) * u[0, i, d]
                - g * (p[0, i, d] - centre[d])
                + RT * (B[d] - p[0, i, d]) / rank[i]
                + c * u[0, i, perm[0, i, d]] / rank[i]
            )
            assert st.u[0, i, d] == pytest.approx(max(-0.075, min(0.075, v)), abs=1e-15)


def test_mawdo_hierarchical_step_by_hand():
    opt = make_optimizer("mawdo2", pop_size=4, groups=2)
    D = 2
    space = Space(np.full(D, -1.0), np.full(D, 1.0))
    p = np.array([[[0.2, 0.4], [-0.4, 0.0], [0.6, -0.6], [0.0, 0.2]]])
    u = np.zeros_like(p)
    pbest = np.array([[[0.1, 0.4], [-0.5, 0.1], [0.6, -0.5], [0.3, 0.3]]])
    pbest_f = np.array([[2.0, 1.5, 0.5, 4.0]])  # group bests: 1 (g0), 2 (g1); tbest = 2
    f = np.array([[3.0, 1.6, 0.7, 4.0]])
    coef = np.array([[[0.5, 0.1, 0.8, 0.2]]])
    perm = np.array([[[0, 1]] * 4])
    st = WindState(
        p=p.copy(),
        u=u.copy(),
        f=f,
        pbest=pbest,
        pbest_f=pbest_f,
        gid=wind.partition(4, 2),
        coef=None,
        vmax=0.3,
        low_dim=False,
        t=5,
        T=9,
        space=space,
        streams=FixedStreams(permutations=[perm], random=[coef]),
    )
    opt.ask(st)
    lam = (5 - 1) / (9 - 1)
    w1, w2, w3 = 0.6 - 0.4 * lam, 0.3, 0.1 + 0.4 * lam
    tb = pbest[0, 2]
    gb = {0: pbest[0, 1], 1: pbest[0, 2]}
    rank = [2, 1, 1, 2]  # within groups by current f
    a, g, RT, c = coef[0, 0]
    for i in range(4):
        grp = i // 2
        gate = min(1.0, np.linalg.norm(gb[grp] - tb) / (2 * np.sqrt(2)))
        w3e = w3 * gate
        B = (w1 * pbest[0, i] + w2 * gb[grp] + w3e * tb) / (w1 + w2 + w3e)
        for d in range(2):
            v = (1 - a) * 0 - g * p[0, i, d] + RT * (B[d] - p[0, i, d]) / rank[i] + 0
            assert st.u[0, i, d] == pytest.approx(max(-0.3, min(0.3, v)), abs=1e-15)


def test_ablation_presets_match_paper_table_5():
    P = {
        n: make_optimizer(n).params
        for n in ("awdo", "mawdo1", "mawdo2", "mawdo3", "mawdo4", "mawdo")
    }
    assert all(p.velocity == "awdo" for p in P.values())
    assert (P["awdo"].groups, P["awdo"].guidance, P["awdo"].restart) == (1, "global", False)
    assert (P["mawdo1"].groups, P["mawdo1"].guidance) == (8, "group")
    assert (P["mawdo2"].guidance, P["mawdo2"].schedule, P["mawdo2"].gate) == (
        "hierarchical",
        True,
        True,
    )
    assert P["mawdo3"].restart and P["mawdo3"].obl and P["mawdo3"].guidance == "global"
    assert P["mawdo4"].low_dim_stabilization and not P["mawdo4"].restart
    m = P["mawdo"]
    assert (m.groups, m.guidance, m.restart, m.obl, m.low_dim_stabilization, m.boundary) == (
        8,
        "hierarchical",
        True,
        True,
        True,
        "reflect",
    )
    assert OPTIMIZERS["mewdo"].reconstructed and "reconstructed" in OPTIMIZERS["mewdo"].display


def test_bad_wind_options_are_named():
    with pytest.raises(ValueError, match="obl=True acts on restarted"):
        make_optimizer("awdo", obl=True)
    with pytest.raises(ValueError, match="groups"):
        make_optimizer("mawdo", pop_size=4)
    with pytest.raises(ValueError, match="mawdo has no option .grups..*.groups."):
        make_optimizer("mawdo", grups=4)
    with pytest.raises(ValueError, match="boundary"):
        make_optimizer("mawdo", boundary="wrap")
