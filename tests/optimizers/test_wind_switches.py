"""Each component switch of the WDO family (issue 29) changes exactly the term it names.

One step of :class:`~mawdo.optimizers.wdo.Wind` on a fixed population with fixed draws, with and
without the switch, against the step worked out here in plain Python (scalar loops over parcels
and dimensions, written from the papers' equations, not from the kernel). Besides matching the
hand step, the velocity change the switch causes must equal the change of the one term it names:
every other term of the velocity is shown to be untouched.
"""

import math

import numpy as np
import pytest

from mawdo import make_optimizer
from mawdo.optimizers.base import Space
from mawdo.optimizers.wdo import WindState
from mawdo.optimizers.wind import partition

from .fixed_streams import FixedStreams

D = 3
SPACE = Space(np.array([-4.0, 0.0, 10.0]), np.array([6.0, 2.0, 30.0]))
P0 = np.array([[[0.5, -0.2, 0.1], [-0.7, 0.6, 0.3], [0.1, 0.9, -0.4], [0.8, -0.5, -0.9]]])
U0 = np.array([[[0.05, -0.04, 0.02], [0.03, 0.06, -0.01], [-0.05, 0.0, 0.04], [0.02, 0.01, -0.06]]])
F0 = np.array([[4.0, 1.0, 9.0, 2.0]])  # current ranks 3, 1, 4, 2
PB = np.array([[[0.4, -0.1, 0.2], [-0.6, 0.5, 0.3], [0.0, 0.8, -0.3], [0.7, -0.4, -0.8]]])
PBF = np.array([[3.0, 0.5, 8.0, 1.5]])  # tbest: parcel 1; group bests (G = 2): 1 and 3
PERM = np.array([[[2, 0, 1], [1, 2, 0], [0, 2, 1], [2, 1, 0]]])
DRAW = np.array([[[0.3, 0.6, 0.5, 0.7]]])  # AWDO's a_t, g_t, RT_t, c_t
SMALL = {"alpha": 0.4, "g": 0.2, "RT": 0.3, "c": 0.4}  # WDO coefficients that never clamp here


def hand_step(cfg, coef):
    """The velocity terms and the new positions and velocities, by the equations.

    ``cfg``: velocity, groups, rank_scope, guidance, gate, gravity_to, pressure, clamp, vmax,
    boundary; ``coef``: (alpha, g, RT, c). Returns ``(terms, p, u)``, ``terms[name]`` of shape
    ``(N, D)`` for friction, gravity, pressure and Coriolis.
    """
    p, u, pb, pbf = P0[0], U0[0], PB[0], PBF[0]
    N = p.shape[0]
    gid = partition(N, cfg["groups"])
    a, g, RT, c = coef
    tb = min(range(N), key=lambda k: (pbf[k], k))
    members = {G: [k for k in range(N) if gid[k] == G] for G in set(gid)}
    gbest = {G: min(ks, key=lambda k: (pbf[k], k)) for G, ks in members.items()}

    def rank(i):
        pool = members[gid[i]] if cfg["rank_scope"] == "group" else range(N)
        return 1 + sum(1 for k in pool if (F0[0, k], k) < (F0[0, i], i))

    names = ("friction", "gravity", "pressure", "coriolis")
    terms = {n: np.zeros((N, D)) for n in names}
    newp, newu = np.zeros((N, D)), np.zeros((N, D))
    for i in range(N):
        r = rank(i)
        lead = pb[tb] if cfg["guidance"] == "global" else pb[gbest[gid[i]]]
        if cfg["guidance"] == "hierarchical":
            w1, w2, w3 = cfg["weights"]
            dist = math.sqrt(sum((pb[gbest[gid[i]]][d] - pb[tb][d]) ** 2 for d in range(D)))
            w3 = w3 * min(1.0, dist / (2 * math.sqrt(D))) if cfg["gate"] else w3
            lead = (w1 * pb[i] + w2 * pb[gbest[gid[i]]] + w3 * pb[tb]) / (w1 + w2 + w3)
        target = {
            "centre": [0.0] * D,
            "mean": [sum(p[k][d] for k in range(N)) / N for d in range(D)],
            "best": list(pb[tb]),
            "none": [0.0] * D,
        }[cfg["gravity_to"]]
        gg = 0.0 if cfg["gravity_to"] == "none" else g
        if cfg["pressure"] == "flat":
            wp, wc = RT, c
        elif cfg["velocity"] == "awdo":
            wp, wc = RT / r, c / r
        else:
            wp, wc = abs(1 - 1 / r) * RT, c / r
        for d in range(D):
            terms["friction"][i, d] = (1 - a) * u[i][d]
            terms["gravity"][i, d] = -gg * (p[i][d] - target[d])
            terms["pressure"][i, d] = wp * (lead[d] - p[i][d])
            terms["coriolis"][i, d] = wc * u[i][PERM[0, i, d]]
            v = sum(terms[n][i, d] for n in names)
            if cfg["clamp"]:
                v = max(-cfg["vmax"], min(cfg["vmax"], v))
            q = p[i][d] + v
            if cfg["boundary"] == "reflect" and abs(q) > 1:
                q, v = math.copysign(2, q) - q, -0.5 * v
            newp[i, d], newu[i, d] = max(-1.0, min(1.0, q)), v
    return terms, newp, newu


def kernel_step(name, options):
    """One ask of the registered ``name`` with ``options`` on the fixed population."""
    opt = make_optimizer(name, pop_size=4, **options)
    P = opt.params
    draws = {"random": [DRAW]} if P.velocity == "awdo" and P.coef_draw != "fixed" else {}
    streams = FixedStreams(permutations=[PERM], **draws)
    st = WindState(
        p=P0.copy(), u=U0.copy(), f=F0.copy(), pbest=PB.copy(), pbest_f=PBF.copy(),
        gid=partition(4, P.groups), coef=None, vmax=P.vmax, low_dim=False, t=5, T=9,
        space=SPACE, streams=streams,
    )  # fmt: skip
    X = opt.ask(st)
    assert streams.exhausted()  # every fixed draw was used, and no other was made
    np.testing.assert_allclose(X, SPACE.from_unit(st.p), rtol=0, atol=1e-12)
    fields = ("velocity", "groups", "rank_scope", "guidance", "gate", "gravity_to", "pressure",
              "clamp", "vmax", "boundary")  # fmt: skip
    cfg = {f: getattr(P, f) for f in fields}
    cfg["weights"] = (0.6 - 0.4 * 0.5, 0.3, 0.1 + 0.4 * 0.5)  # Eqs. 6-9 at t = 5 of T = 9
    coef = tuple(DRAW[0, 0]) if P.velocity == "awdo" and P.coef_draw != "fixed" else (
        P.alpha, P.g, P.RT, P.c)  # fmt: skip
    return st, cfg, coef


# (base algorithm, base options, switch options, the one term that changes)
SWITCHES = [
    ("wdo", SMALL, {"gravity_to": "none"}, "gravity"),
    ("wdo", SMALL, {"gravity_to": "mean"}, "gravity"),
    ("wdo", SMALL, {"gravity_to": "best"}, "gravity"),
    ("awdo", {}, {"gravity_to": "mean"}, "gravity"),
    ("awdo", {}, {"gravity_to": "none"}, "gravity"),
    ("mawdo2", {"groups": 2}, {"gravity_to": "best"}, "gravity"),
    ("mawdo2", {"groups": 2}, {"gravity_to": "mean"}, "gravity"),  # all groups, not one
    ("wdo", SMALL, {"pressure": "flat"}, ("pressure", "coriolis")),
    ("awdo", {}, {"pressure": "flat"}, ("pressure", "coriolis")),
    ("mawdo2", {"groups": 2, "guidance": "group"}, {"guidance": "global"}, "pressure"),
    ("mawdo2", {"groups": 2}, {"gate": False}, "pressure"),
    ("mawdo2", {"groups": 2}, {"guidance": "global"}, "pressure"),
    # groups off: one group (its best is tbest) and ranks over the whole population
    ("mawdo2", {"groups": 2}, {"groups": 1, "rank_scope": "population"}, ("pressure", "coriolis")),
]


@pytest.mark.parametrize("base,opts,switch,term", SWITCHES)
def test_switch_changes_only_its_term(base, opts, switch, term):
    opts = {**opts, "vmax": 3.0}  # wide enough that no clamp acts (the clamp has its own test)
    st0, cfg0, coef0 = kernel_step(base, opts)
    st1, cfg1, coef1 = kernel_step(base, {**opts, **switch})
    assert coef0 == coef1
    terms0, p0, u0 = hand_step(cfg0, coef0)
    terms1, p1, u1 = hand_step(cfg1, coef1)
    for st, p, u in ((st0, p0, u0), (st1, p1, u1)):
        np.testing.assert_allclose(st.u[0], u, rtol=0, atol=1e-14)
        np.testing.assert_allclose(st.p[0], p, rtol=0, atol=1e-14)
    changed = (term,) if isinstance(term, str) else term
    # no clamp acted in either step, so the velocities differ by the named terms alone
    assert np.abs(u0).max() < cfg0["vmax"] and np.abs(u1).max() < cfg1["vmax"]
    expect = sum(terms1[n] - terms0[n] for n in changed)
    np.testing.assert_allclose(st1.u[0] - st0.u[0], expect, rtol=0, atol=1e-14)
    assert np.abs(expect).max() > 1e-3  # the switch did change the term on this population
    for n in set(terms0) - set(changed):
        np.testing.assert_array_equal(terms0[n], terms1[n])


def test_coefficient_means_replace_awdos_draws():
    """``coef_draw="fixed"``: AWDO's equation with the given coefficients and no draw."""
    means = {"coef_draw": "fixed", "alpha": 0.5, "g": 0.5, "RT": 0.5, "c": 0.5}
    st, cfg, coef = kernel_step("awdo", means)
    assert coef == (0.5, 0.5, 0.5, 0.5)
    _, p, u = hand_step(cfg, coef)
    np.testing.assert_allclose(st.u[0], u, rtol=0, atol=1e-14)
    np.testing.assert_allclose(st.p[0], p, rtol=0, atol=1e-14)
    drawn, _, _ = kernel_step("awdo", {})
    assert not np.allclose(drawn.u, st.u)  # with the draws the step differs


def test_clamp_off_keeps_the_raw_velocity():
    """``clamp=False``: velocities beyond ``vmax`` stay as computed; the rest of the step (and
    every unclamped coordinate) is the clamped step's."""
    big = {**SMALL, "RT": 3.0}  # WDO's own RT: pressure steps beyond vmax = 0.3
    on, cfg_on, coef = kernel_step("wdo", big)
    off, cfg_off, _ = kernel_step("wdo", {**big, "clamp": False})
    terms, p_on, u_on = hand_step(cfg_on, coef)
    _, p_off, u_off = hand_step(cfg_off, coef)
    np.testing.assert_allclose(on.u[0], u_on, rtol=0, atol=1e-14)
    np.testing.assert_allclose(off.u[0], u_off, rtol=0, atol=1e-14)
    np.testing.assert_allclose(off.p[0], p_off, rtol=0, atol=1e-14)
    raw = sum(terms.values())
    clamped = np.abs(raw) > 0.3
    assert clamped.any() and (~clamped).any()
    np.testing.assert_allclose(off.u[0], raw, rtol=0, atol=1e-14)
    np.testing.assert_array_equal(off.u[0][~clamped], on.u[0][~clamped])


def test_boundary_switch_changes_only_coordinates_that_leave_the_box():
    big = {**SMALL, "RT": 3.0, "clamp": False}
    clip, cfg_c, coef = kernel_step("wdo", big)
    refl, cfg_r, _ = kernel_step("wdo", {**big, "boundary": "reflect"})
    for st, cfg in ((clip, cfg_c), (refl, cfg_r)):
        _, p, u = hand_step(cfg, coef)
        np.testing.assert_allclose(st.p[0], p, rtol=0, atol=1e-14)
        np.testing.assert_allclose(st.u[0], u, rtol=0, atol=1e-14)
    out = np.abs(P0[0] + clip.u[0]) > 1
    assert out.any() and (~out).any()
    np.testing.assert_array_equal(refl.p[0][~out], clip.p[0][~out])
    np.testing.assert_array_equal(refl.u[0][~out], clip.u[0][~out])
    assert not np.any(refl.p[0][out] == clip.p[0][out])


def test_default_switches_are_the_papers():
    opt = make_optimizer("mawdo")
    P = opt.params
    assert (P.gravity_to, P.pressure, P.clamp) == ("centre", "rank", True)
    assert P.coef_draw == "iteration"


@pytest.mark.parametrize(
    "option,value", [("gravity_to", "up"), ("pressure", "none"), ("coef_draw", "never")]
)
def test_bad_switch_values_are_named(option, value):
    with pytest.raises(ValueError, match=option):
        make_optimizer("wdo", **{option: value})
