"""AWDO-CMA's first iterations against a literal transcription of ``AWDO_v03.m`` (Bayraktar).

``AWDO_v03.m`` sets ``rec.arx = rand(4, popsize)`` before the loop, moves the parcels once with
those coefficients, evaluates them and only then calls ``purecmaes_wdo`` for the first time: it
initialises ``xmean = rand(4, 1)`` and immediately recombines the ``mu`` best *uniform* samples
into the new mean. The transcription below is written from the MATLAB source, 0-based, with the
one recorded deviation (``docs/deviations.md``): the true rank replaces ``rank_ind(i)``.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from mawdo.optimizers.base import Space
from mawdo.optimizers.registry import make_optimizer
from tests.optimizers.fixed_streams import FixedStreams
from tests.optimizers.purecmaes_literal import purecmaes_wdo

N, D = 6, 3
LB, UB = -100.0, 100.0  # AWDO_v03.m's dimMin, dimMax
MAXV = 0.3


def fsphere(x):
    return float(sum(v * v for v in x))


def to_problem(pos):
    return [(UB - LB) * ((v + 1) / 2) + LB for v in pos]


def true_ranks(pres):
    order = sorted(range(len(pres)), key=lambda k: (pres[k], k))
    rank = [0] * len(pres)
    for r, k in enumerate(order):
        rank[k] = r + 1
    return rank


def literal_first_move(pos, vel, arx, perm):
    """``AWDO_v03.m``: initial evaluation, then the first ``for ij = 2`` move with ``rec.arx``."""
    pres = [fsphere(to_problem(p)) for p in pos]
    indx = min(range(N), key=lambda k: pres[k])
    globalpos = list(pos[indx])
    rank = true_ranks(pres)  # the reference's rank_ind(i) is the sort permutation (deviation)
    new_pos, new_vel = [], []
    for i in range(N):
        velot = [vel[i][perm[i][j]] for j in range(D)]  # vel(i, a), a = randperm(npar)
        v = [
            (1 - arx[i][0]) * vel[i][j]
            - arx[i][1] * pos[i][j]
            + abs(1 - 1 / rank[i]) * ((globalpos[j] - pos[i][j]) * arx[i][2])
            + arx[i][3] * velot[j] / rank[i]
            for j in range(D)
        ]
        v = [max(min(x, MAXV), -MAXV) for x in v]
        p = [max(min(pos[i][j] + v[j], 1.0), -1.0) for j in range(D)]
        new_vel.append(v)
        new_pos.append(p)
    return new_pos, new_vel, [fsphere(to_problem(p)) for p in new_pos]


def purecmaes_first_mean(arx, pres):
    """``purecmaes_wdo`` at ``counteval == 2``: the new mean from the ``mu`` best samples."""
    lam = len(pres)
    mu = lam / 2
    weights = [math.log(mu + 0.5) - math.log(k) for k in range(1, int(mu) + 1)]  # 1:mu
    mu = math.floor(mu)
    total = sum(weights)
    weights = [w / total for w in weights]
    order = sorted(range(lam), key=lambda k: pres[k])
    return [sum(weights[m] * arx[order[m]][d] for m in range(mu)) for d in range(4)]


@pytest.fixture
def case():
    rng = np.random.default_rng(3)
    pos0 = rng.uniform(-1, 1, (1, N, D))
    vel0 = rng.uniform(-MAXV, MAXV, (1, N, D))
    arx = rng.random((1, N, 4))
    mean0 = rng.random((1, 4))
    perm = np.stack([rng.permutation(D) for _ in range(N)])[None]
    z = rng.normal(size=(1, N, 4))  # randn(4, 1) of each of the first CMA-ES samples
    streams = FixedStreams(
        runs=1,
        random=[(pos0 + 1) / 2, (vel0 + MAXV) / (2 * MAXV), arx, mean0],
        permutations=[perm],
        normal=[z],
    )
    opt = make_optimizer("awdo_cmaes", pop_size=N)
    space = Space(lb=np.full(D, LB), ub=np.full(D, UB))
    st = opt.init(space, streams, max_iter=10)
    return opt, st, pos0[0], vel0[0], arx[0], perm[0], mean0[0], z[0]


def evaluate(X):
    return np.array([[fsphere(x) for x in run] for run in X])


def test_first_move_uses_the_uniform_coefficients_of_awdo_v03(case):
    opt, st, pos0, vel0, arx, perm, mean0, z = case
    X0 = opt.ask(st)
    st = opt.tell(st, X0, evaluate(X0))
    X1 = opt.ask(st)
    ref_pos, ref_vel, ref_pres = literal_first_move(pos0.tolist(), vel0.tolist(), arx, perm)
    np.testing.assert_allclose(st.u[0], ref_vel, rtol=0, atol=1e-15)
    np.testing.assert_allclose(st.p[0], ref_pos, rtol=0, atol=1e-15)
    np.testing.assert_allclose(evaluate(X1)[0], ref_pres, rtol=1e-12)
    # every draw but the CMA-ES's first samples (drawn after the next evaluation) is spent
    assert {k: len(q) for k, q in st.streams.queues.items()} == {
        "random": 0,
        "permutations": 0,
        "normal": 1,
    }


def test_first_cmaes_update_recombines_the_uniform_samples(case):
    opt, st, pos0, vel0, arx, perm, mean0, z = case
    X0 = opt.ask(st)
    st = opt.tell(st, X0, evaluate(X0))
    assert np.array_equal(st.arx[0], arx)  # nothing sampled before the first move
    X1 = opt.ask(st)
    F1 = evaluate(X1)
    st = opt.tell(st, X1, F1)
    expect = purecmaes_first_mean(arx.tolist(), F1[0].tolist())
    np.testing.assert_allclose(st.es.xmean[0], expect, rtol=1e-12, atol=1e-15)
    # the second move's coefficients: the source's samples from the same randn draws
    rec = purecmaes_wdo(2, {"arx": arx.tolist()}, N, F1[0].tolist(), mean0, z.tolist())
    np.testing.assert_allclose(st.arx[0], rec["arx"], rtol=1e-12, atol=1e-14)
    assert st.streams.exhausted()
