"""L-SHADE, jSO and NL-SHADE-RSP against literal transcriptions of the authors' C++ codes.

The batched optimizers run on real per-run streams wrapped in :class:`RecordingStreams`; the
literal ports (``shade_literal.py``, one run, individual by individual) then take the same
numbers and must produce every generation's population, values and memories (to 1e-12: the
batched sums add in another order). A second check shows the comparison can fail.
"""

from __future__ import annotations

import numpy as np
import pytest

from mawdo.optimizers.base import Space
from mawdo.optimizers.registry import make_optimizer
from mawdo.streams import RunStreams
from tests.optimizers import shade_literal as lit

LSHADE_NAMES = ("u_mem", "u_f", "u_pb", "u_r1", "u_r2", "u_j", "u_cr", "u_slot")
NL_NAMES = ("u_exp", "u_mem", "u_f", "u_pb", "u_r1", "u_arc", "u_r2", "u_j", "u_start",
            "u_cr", "u_box", "u_slot")  # fmt: skip


class RecordingStreams(RunStreams):
    """Real per-run streams that keep every draw they hand out, in order."""

    def __init__(self, seed, runs):
        super().__init__(
            [np.random.default_rng(s) for s in np.random.SeedSequence(seed).spawn(runs)]
        )
        self.calls = []

    def random_parts(self, *shapes):
        out = super().random_parts(*shapes)
        self.calls.append(("parts", [a.copy() for a in out]))
        return out

    def normal(self, shape=()):
        out = super().normal(shape)
        self.calls.append(("normal", out.copy()))
        return out


def objective(x):
    """A shifted, rotated-free bowl with ripples: no ties, optimum near a face of the box."""
    x = np.asarray(x, float)
    y = x - np.array([3.9, -2.0, 1.0, 4.5])[: x.shape[-1]]
    total = np.zeros(x.shape[:-1])
    for j in range(x.shape[-1]):  # one order of additions for a point alone or in a batch
        total = total + (y[..., j] * y[..., j] + 0.5 * (1.0 - np.cos(3.0 * y[..., j])))
    return total


def drive(name, R, N, D, max_evals, seed, **options):
    """Run the batched optimizer by ask/tell; returns the initial population, each
    generation's (X, F, MF, MCR), and the recorded draws."""
    opt = make_optimizer(name, pop_size=N, **options)
    streams = RecordingStreams(seed, R)
    space = Space(np.full(D, -5.0), np.full(D, 5.0))
    st = opt.init(space, streams, max_evals)
    X0 = st.X.copy()
    steps = []
    while st.nfes < max_evals:
        X = opt.ask(st)
        st = opt.tell(st, X, objective(X))
        if st.nfes > N:  # after each generation (not the initial population)
            steps.append((st.X.copy(), st.F.copy(), st.MF.copy(), st.MCR.copy()))
    return X0, steps, streams.calls


def generation_draws(calls, names, r):
    """Run ``r``'s draws, one dict per generation (a ``parts`` call, then a ``normal``)."""
    gens = []
    for k in range(0, len(calls), 2):
        (_, parts), (_, z) = calls[k], calls[k + 1]
        g = {n: a[r].tolist() for n, a in zip(names, parts, strict=True)}
        g["z"] = z[r].tolist()
        gens.append(g)
    return gens


def compare(ours, ref, r):
    assert len(ours) == len(ref)
    for t, ((X, F, MF, MCR), (pop, fit, mf, mcr)) in enumerate(zip(ours, ref, strict=True)):
        msg = f"generation {t + 1}"
        np.testing.assert_allclose(X[r], np.array(pop), rtol=1e-12, atol=1e-12, err_msg=msg)
        np.testing.assert_allclose(F[r], np.array(fit), rtol=1e-12, atol=1e-12, err_msg=msg)
        np.testing.assert_allclose(MF[r], mf, rtol=1e-12, atol=1e-12, err_msg=msg)
        np.testing.assert_allclose(MCR[r], mcr, rtol=1e-12, atol=1e-12, err_msg=msg)


LSHADE_SETTINGS = {
    "lshade": dict(p_best_rate=0.11, arc_rate=2.6, memory_size=6, memory_init=(0.5, 0.5)),
    "jso": dict(p_best_rate=0.25, arc_rate=1.0, memory_size=5, memory_init=(0.3, 0.8), jso=True),
}


@pytest.mark.parametrize("name", ["lshade", "jso"])
@pytest.mark.parametrize("seed", [0, 1])
def test_lshade_and_jso_follow_the_literal_lshade_cc(name, seed):
    R, N, D, M = 3, 24, 4, 1500
    X0, ours, calls = drive(name, R, N, D, M, seed)
    assert [X.shape[1] for X, *_ in ours][-1] == 4, "the population must shrink to 4"
    lo, hi = [-5.0] * D, [5.0] * D
    for r in range(R):
        g = generation_draws(calls, LSHADE_NAMES, r)
        ref = lit.lshade_cc(X0[r].tolist(), objective, lo, hi, M, g, **LSHADE_SETTINGS[name])
        compare(ours, ref, r)


@pytest.mark.parametrize("seed, M", [(0, 1500), (1, 1500), (2, 400), (3, 400)])
def test_nlshade_rsp_follows_the_literal_nl_shade_rsp_cpp(seed, M):
    R, N, D = 3, 30, 4
    X0, ours, calls = drive("nlshade_rsp", R, N, D, M, seed)
    assert [X.shape[1] for X, *_ in ours][-1] == 4
    lo, hi = [-5.0] * D, [5.0] * D
    for r in range(R):
        g = generation_draws(calls, NL_NAMES, r)
        ref = lit.nl_shade_rsp_cpp(X0[r].tolist(), objective, lo, hi, M, g, memory_size=20 * D)
        compare(ours, ref, r)


def test_the_comparison_can_fail():
    """The ports are sensitive to what they check: jSO's rules and NL-SHADE-RSP's F
    bookkeeping each change the trajectory for the same draws (the removal loop: see
    test_shade_units)."""
    R, N, D, M = 2, 24, 4, 1500
    lo, hi = [-5.0] * D, [5.0] * D
    X0, ours, calls = drive("jso", R, N, D, M, 0)
    g = generation_draws(calls, LSHADE_NAMES, 0)
    with pytest.raises(AssertionError):
        compare(ours, lit.lshade_cc(X0[0].tolist(), objective, lo, hi, M, g,
                                    **{**LSHADE_SETTINGS["jso"], "jso": False}), 0)  # fmt: skip
    for option, budget in (({"success_f": "own"}, M),):
        X0, ours, calls = drive("nlshade_rsp", 4, 30, D, budget, 0, **option)
        differs = []
        for r in range(4):
            g = generation_draws(calls, NL_NAMES, r)
            ref = lit.nl_shade_rsp_cpp(X0[r].tolist(), objective, lo, hi, budget, g,
                                       memory_size=4 * 20)  # fmt: skip
            try:
                compare(ours, ref, r)
            except AssertionError:
                differs.append(r)
        assert differs, option
