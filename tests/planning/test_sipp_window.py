"""The forbidden departures of a move within a window skip the discs no departure of the window
comes near (:func:`~mawdo.planning.guide.sipp.geometry.disc_missed`) and gather the rest in
place: the answers are those of the plain loop over every piece of every mover (a port of it
here, bit for bit), and a disc the test calls missed is farther than its reach from every
position of every departure of the window (dense sampling)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from mawdo.planning.guide.sipp.geometry import cone_start, disc_missed, disc_range
from mawdo.planning.guide.sipp.intervals import Movers, _polygon_piece, forbidden
from tests.planning.test_sipp_index import _moves, _world


def _reference(ux, uy, ex, ey, T, lo, hi, mv):
    """Every mover's forbidden departures, each piece in its time range tested whole (the loop
    before the window test), sorted stably by their start, clipped to ``[lo, hi]`` and
    merged."""
    kind, box, circle, center, thr, verts, nverts, vmax, base, t_base = mv[:10]
    pptr, pt0, pt1, po, pv = mv[10:15]
    rows = []
    rx0, rx1 = min(ux, ux + T * ex), max(ux, ux + T * ex)
    ry0, ry1 = min(uy, uy + T * ey), max(uy, uy + T * ey)
    for m in range(len(kind)):
        if kind[m] == 1:
            c, r = center[m], thr[m]
            tc = cone_start(ux, uy, ex, ey, T, circle[m], c[0], c[1], r, verts, m, nverts[m],
                            base[m, 0], base[m, 1], vmax[m], t_base)  # fmt: skip
            if tc <= hi:
                rows.append((tc, math.inf))
            continue
        for k in range(pptr[m], pptr[m + 1]):
            if pt1[k] < lo or pt0[k] > hi + T:
                continue
            ta, tb, (wx, wy) = pt0[k], pt1[k], pv[k]
            ox = sorted((po[k, 0], po[k, 0] + wx * (tb - ta)))
            oy = sorted((po[k, 1], po[k, 1] + wy * (tb - ta)))
            if (box[m, 0] + ox[0] > rx1 or box[m, 2] + ox[1] < rx0
                    or box[m, 1] + oy[0] > ry1 or box[m, 3] + oy[1] < ry0):  # fmt: skip
                continue
            d0x, d0y = ux - po[k, 0] + wx * ta, uy - po[k, 1] + wy * ta
            if circle[m]:
                f0, f1 = disc_range(d0x - center[m, 0], d0y - center[m, 1], ex, ey, wx, wy, T,
                                    ta, tb, thr[m])  # fmt: skip
                if f0 <= f1:
                    rows.append((f0, f1))
            else:
                buf = np.empty((64, 2))
                n = _polygon_piece(d0x, d0y, ex, ey, wx, wy, T, ta, tb, verts, m, nverts[m],
                                   thr[m], buf, np.int64(0))  # fmt: skip
                rows += [tuple(r) for r in buf[:n]]
    rows = np.array(rows).reshape(-1, 2)
    out = []
    for a, b in rows[np.argsort(rows[:, 0], kind="stable")]:
        a, b = max(a, lo), min(b, hi)
        if a > b:
            continue
        if out and a <= out[-1][1]:
            out[-1][1] = max(out[-1][1], b)
        else:
            out.append([a, b])
    return np.array(out).reshape(-1, 2)


@pytest.mark.parametrize("seed", range(3))
@pytest.mark.parametrize("walkers", ["reachable", "known"])
def test_window_departures_equal_the_plain_loop_bit_for_bit(seed, walkers):
    sc = _world(seed, movers=40)
    mv = Movers.from_scenario(sc, 0.5, 0.0, 150.0, walkers).arrays()
    rng = np.random.default_rng(200 + seed)
    hits = 0
    for u, _, e, T, lo, hi in _moves(rng, 300):
        got = forbidden(u[0], u[1], e[0], e[1], T, lo, hi, mv)
        want = _reference(u[0], u[1], e[0], e[1], T, lo, hi, mv)
        assert got.shape == want.shape and np.array_equal(got, want), (u, e, T, lo, hi)
        hits += len(want) > 0
    assert hits > 40  # crowded enough for the comparison to mean something


def test_a_missed_disc_is_out_of_reach_of_every_departure_of_the_window():
    rng = np.random.default_rng(5)
    missed = 0
    s = np.linspace(0.0, 1.0, 41)[:, None]
    tau_frac = np.linspace(0.0, 1.0, 41)[None, :]
    for _ in range(3000):
        d = rng.uniform(-150, 150, 2)
        e = rng.uniform(-4, 4, 2) * (rng.random() < 0.9)  # some waits
        w = rng.uniform(-3, 3, 2) * (rng.random() < 0.9)  # some still discs
        T = float(rng.choice([0.0, rng.uniform(0, 60)]))
        lo = float(rng.uniform(-20, 100))
        hi = lo + float(rng.choice([0.0, 2.0, 8.0, 30.0]))
        rho = float(rng.uniform(3, 15))
        if not disc_missed(d[0], d[1], e[0], e[1], w[0], w[1], T, lo, hi, rho + 1.0):
            continue
        missed += 1
        S, tau = T * s, lo + (hi - lo) * tau_frac  # q = d + s (e - w) - tau w
        qx = d[0] + S * (e[0] - w[0]) - tau * w[0]
        qy = d[1] + S * (e[1] - w[1]) - tau * w[1]
        assert np.min(np.hypot(qx, qy)) > rho + 1.0 - 1e-9
        # and the exact departures (reach rho) of any piece span lie outside the window
        f0, f1 = disc_range(d[0], d[1], e[0], e[1], w[0], w[1], T, -1e3, 1e3, rho)
        assert f0 > f1 or f1 < lo or f0 > hi
    assert missed > 1000  # it does decide: most random discs are far from a short window


def test_undecidable_windows_are_never_called_missed():
    args = (50.0, 0.0, 1.0, 0.0, 0.0, 0.0, 10.0)
    assert not disc_missed(*args, -math.inf, 5.0, 3.0)
    assert not disc_missed(*args, 0.0, math.inf, 3.0)
    assert not disc_missed(*args, math.nan, 5.0, 3.0)
    # robot and disc moving together (no relative motion along a track): no decision
    assert not disc_missed(50.0, 0.0, 1.0, 0.0, 1.0, 0.0, 10.0, 0.0, 5.0, 3.0)
