"""A literal one-run transcription of the authors' EA4eig MATLAB code (``alg_EA4eig.m``).

Plain Python loops, statement by statement, individual by individual, 0-based. Where the code
calls ``rand`` or ``randn`` this takes the next number of the draws the batched optimizer made
for this run (``state.gen``) and turns it into the value with the law of the code's call,
written out here on its own:

* ``nahvyb_expt(N, k, expt)`` / ``nahvyb``: each pick ``1 + fix(rand * length(support))`` from
  what is left, removed from the support (:func:`pick_from`);
* ``while F < 0`` around CoBiDE's coin and Cauchy draw: the coin's odds given an accepted value,
  and the Cauchy's distribution function inverted above 0 (:func:`cobide_f`);
* ``while Fo <= 0 || Fo > 1`` (IDE): the normal's distribution function inverted on the
  interval (:func:`normal_in`);
* ``while F <= 0`` (jSO's Cauchy): as CoBiDE's, one centre.

The boundary reflection is the code's commented original ``zrcad`` (the while loop).
"""

from __future__ import annotations

import math

import numpy as np
from scipy.special import ndtr, ndtri


def c_round(x):
    t = math.trunc(x)
    return int(t + math.copysign(1, x)) if abs(x - t) >= 0.5 else int(t)


def pick_from(support, u):
    """``index = 1 + fix(rand * length(support)); x = support(index); support(index) = []``."""
    index = min(int(u * len(support)), len(support) - 1)
    return support.pop(index)


def positive_cauchy(mu, u):
    """``do F = mu + 0.1 tan(pi (rand - 1/2)) while F <= 0``, by inversion above 0."""
    p0 = 0.5 + math.atan(-mu / 0.1) / math.pi
    w = p0 + (1.0 - p0) * (1.0 - u)
    F = mu + 0.1 * math.tan(math.pi * (w - 0.5))
    return F if F > 0 else np.nextafter(0.0, 1.0)


def cobide_f(u_coin, u_value):
    """``if rand < 0.5: cauchy(0.65, 0.1) else cauchy(1, 0.1)``, both again while < 0; cap 1."""
    p = [0.5 + math.atan(c / 0.1) / math.pi for c in (0.65, 1.0)]
    mu = 0.65 if u_coin < p[0] / (p[0] + p[1]) else 1.0
    return min(positive_cauchy(mu, u_value), 1.0)


def cobide_cr(u_coin, u_value):
    mu = 0.1 if u_coin < 0.5 else 0.95
    return min(max(mu + 0.1 * math.tan(math.pi * (u_value - 0.5)), 0.0), 1.0)


def normal_in(mean, u, lo, hi):
    """``mean + 0.1 randn`` drawn again until inside ``[lo, hi]`` (ends aside), by inversion."""
    a, b = ndtr((lo - mean) / 0.1), ndtr((hi - mean) / 0.1)
    x = min(max(mean + 0.1 * float(ndtri(a + u * (b - a))), lo), hi)
    return x


def zrcad(y, a, b):
    y = y.copy()
    for i in np.flatnonzero((y < a) | (y > b)):
        while y[i] < a[i] or y[i] > b[i]:
            if y[i] > b[i]:
                y[i] = 2 * b[i] - y[i]
            elif y[i] < a[i]:
                y[i] = 2 * a[i] - y[i]
    return y


def sortrows(P, *carried):
    order = sorted(range(len(P)), key=lambda i: P[i][-1])  # stable, as MATLAB's sortrows
    return [P[i].copy() for i in order], [[c[i] for i in order] for c in carried]


def change_set(u_row, limit, u_j, D, strict=True):
    """``change = find(rand(1, D) < limit)``, or ``1 + fix(D rand)`` when empty."""
    change = [j for j in range(D) if (u_row[j] < limit if strict else u_row[j] <= limit)]
    return change or [min(int(u_j * D), D - 1)]


class Literal:
    """One run of EA4eig, from the batched run's initial population and first CoBiDE draws."""

    def __init__(self, X0, F0, CBF, CBCR, lb, ub, max_fes):
        N, D = X0.shape
        self.a, self.b = np.asarray(lb, float), np.asarray(ub, float)
        self.D, self.maxFES = D, max_fes
        self.P = [np.append(X0[i], F0[i]) for i in range(N)]
        self.N_init, self.N, self.FES = N, N, N
        self.CBF, self.CBCR = list(CBF), list(CBCR)
        self.ni = [2.0] * 4
        self.gmax = c_round(max_fes / N)
        self.T, self.gt, self.g, self.Tcurr = self.gmax / 10, math.trunc(self.gmax / 2), 0, 0
        self.sigma = (self.b[0] - self.a[0]) / 2
        self.oldPop = X0.T.copy()
        mu = N / 2
        self._weights(mu)
        D_ = D
        mueff = self.mueff
        self.cc = (4 + mueff / D_) / (D_ + 4 + 2 * mueff / D_)
        self.cs = (mueff + 2) / (D_ + mueff + 5)
        self.c1 = 2 / ((D_ + 1.3) ** 2 + mueff)
        self.cmu = min(1 - self.c1, 2 * (mueff - 2 + 1 / mueff) / ((D_ + 2) ** 2 + mueff))
        self.damps = 1 + 2 * max(0, math.sqrt((mueff - 1) / (D_ + 1)) - 1) + self.cs
        self.pc, self.ps = np.zeros(D), np.zeros(D)
        self.B, self.Dv = np.eye(D), np.ones(D)
        self.CC, self.invsqrtC = np.eye(D), np.eye(D)
        self.eigeneval = 0
        self.chiN = D**0.5 * (1 - 1 / (4 * D) + 1 / (21 * D**2))
        self.Asize_max, self.H = c_round(N * 2.6), 5
        self.MF, self.MCR = [0.3] * 4 + [0.9], [0.8] * 4 + [0.9]
        self.k, self.A = 0, []

    def sync(self, s, r):
        """Take run ``r``'s state from the batched state ``s`` (a copy made before a
        generation): each generation is then compared from the same start, so the rounding of
        the batched sums (another order of additions) cannot build up over generations."""
        N = s.X.shape[1]
        self.N, self.FES = N, s.nfes
        self.P = [np.append(s.X[r, i], s.F[r, i]) for i in range(N)]
        self.CBF, self.CBCR, self.ni = list(s.CBF[r]), list(s.CBCR[r]), list(s.ni[r])
        self.g, self.gt, self.Tcurr = int(s.g[r]), int(s.gt[r]), int(s.t_fail[r])
        self.sigma, self.B, self.Dv = float(s.sigma[r]), s.B[r].copy(), s.Dd[r].copy()
        self.CC, self.invsqrtC = s.C[r].copy(), s.inv_sqrt_c[r].copy()
        self.pc, self.ps, self.eigeneval = s.pc[r].copy(), s.ps[r].copy(), float(s.eigeneval[r])
        self.oldPop = s.old_pop[r].T.copy()
        self.MF, self.MCR, self.k = list(s.MF[r]), list(s.MCR[r]), int(s.k[r])
        self.A = [x.copy() for x in s.archive[r, : int(s.n_arc[r])]]
        self.Asize_max = s.arc_size
        self.mu, self.weights, self.mueff = s.mu, s.weights.copy(), s.mueff

    def _weights(self, mu):
        self.weights = math.log(mu + 0.5) - np.log(np.arange(1, math.floor(mu) + 1))
        self.mu = math.floor(mu)
        self.weights = self.weights / self.weights.sum()
        self.mueff = self.weights.sum() ** 2 / (self.weights**2).sum()

    def eig_vectors(self):
        Popeig, _ = sortrows(self.P)
        keep = c_round(self.N * 0.5 + 1) - 1
        top = np.array([row[: self.D] for row in Popeig[:keep]])
        return np.linalg.eigh(np.cov(top, rowvar=False))[1]

    def generation(self, gen, r, fhd):
        """One pass of the main loop for run ``r`` of the batch's draws ``gen``."""
        cp = np.cumsum(self.ni) / sum(self.ni)
        hh = int(sum(c < gen["u_roulette"][r] for c in cp))
        if min(self.ni) / sum(self.ni) < 1 / 20:
            self.ni = [2.0] * 4
        name = ("cobide", "ide", "cmaes", "jso")[hh]
        rows = list(gen[name]["rows"])
        d = {k: v[rows.index(r)] for k, v in gen[name].items() if k != "rows" and k != "xmean"}
        getattr(self, name)(d, fhd)
        # population size reduction
        optN = c_round((((10 - self.N_init) / self.maxFES) * self.FES) + self.N_init)
        if self.N > optN:
            diff = self.N - optN
            if self.N - diff < 10:
                diff = self.N - 10
            self.N -= diff
            self.P, (self.CBF, self.CBCR) = sortrows(self.P, self.CBF, self.CBCR)
            self.P, self.CBF, self.CBCR = self.P[: self.N], self.CBF[: self.N], self.CBCR[: self.N]
            self.Asize_max = c_round(self.N * 2.6)
            draws = list(gen.get("trim", {}).get(r, []))
            while len(self.A) > self.Asize_max:
                self.A.pop(min(int(draws.pop(0) * len(self.A)), len(self.A) - 1))
            self._weights(math.floor(self.N / 2))
        return hh

    def cobide(self, d, fhd):
        N, D, a, b = self.N, self.D, self.a, self.b
        Q = []
        eig = d["u_eig"] < 0.4
        if eig:
            E = self.eig_vectors()
        for i in range(N):
            support = [j for j in range(N) if j != i]
            r1, r2, r3 = (pick_from(support, d["u_r"][i][m]) for m in range(3))
            v = self.P[r1][:D] + self.CBF[i] * (self.P[r2][:D] - self.P[r3][:D])
            v = zrcad(v, a, b)
            y = self.P[i][:D].copy()
            change = change_set(d["u_cr"][i], self.CBCR[i], d["u_j"][i], D)
            if eig:
                yeig, veig = E.T @ y, E.T @ v
                yeig[change] = veig[change]
                y = E @ yeig
            else:
                y[change] = v[change]
            y = zrcad(y, a, b)
            Q.append(np.append(y, fhd(y)))
        self.FES += N
        for i in range(N):
            if Q[i][-1] <= self.P[i][-1]:
                self.P[i] = Q[i]
                self.ni[0] += 1
            else:
                self.CBF[i] = cobide_f(d["u_fc"][i], d["u_fv"][i])
                self.CBCR[i] = cobide_cr(d["u_cc"][i], d["u_cv"][i])

    def ide(self, d, fhd):
        N, D, a, b, g, gt = self.N, self.D, self.a, self.b, self.g, self.gt
        self.P, (self.CBF, self.CBCR) = sortrows(self.P, self.CBF, self.CBCR)
        P = self.P
        Q = [row.copy() for row in P]
        IDEps = 0.1 + 0.9 * 10 ** (5 * (g / self.gmax - 1))
        pd = 0.1 * IDEps
        for i in range(N):
            support = [j for j in range(N) if j != i]
            vyb = [pick_from(support, d["u_r"][i][m]) for m in range(4)]
            o = i if g <= gt else vyb[0]
            r1, r2, r3 = vyb[1:]
            xo, xr1, xr2, xr3 = (P[j][:D].copy() for j in (o, r1, r2, r3))
            pom = a + d["u_pt"][i] * (b - a)
            for j in range(D):
                if d["u_pd"][i][j] < pd:
                    xr3[j] = pom[j]
            Fo = normal_in((o + 1) / N, d["u_fo"][i], 0.0, 1.0)
            high = math.trunc(IDEps * N)
            if o + 1 > high and r1 + 1 > high:
                candidates = [c for c in range(high) if c not in vyb and c != i]
                r1 = min(int(d["u_sup"][i] * len(candidates)), max(len(candidates) - 1, 0))
                xr1 = P[r1][:D]
            if g > gt and d["u_half"][i] < 0.5:
                Q[i][:D] = P[i][:D] + Fo * (xr1 - xo) + Fo * (xr2 - xr3)
            else:
                Q[i][:D] = xo + Fo * (xr1 - xo) + Fo * (xr2 - xr3)
        if d["u_eig"] < 0.4:
            E = self.eig_vectors()
            for i in range(N):
                y, v = P[i][:D].copy(), Q[i][:D].copy()
                yeig, veig = E.T @ y, E.T @ v
                change = change_set(d["u_cr"][i], self.CBCR[i], d["u_j"][i], D)
                yeig[change] = veig[change]
                Q[i][:D] = zrcad(E @ yeig, a, b)
        else:
            for i in range(N):
                CR = normal_in((i + 1) / N, d["u_crv"][i], 0.0, 1.0)
                jrand = min(int(d["u_j"][i] * D), D - 1)
                for j in range(D):
                    if not (d["u_cr"][i][j] <= CR or j == jrand):
                        Q[i][j] = P[i][j]
                    if Q[i][j] < a[j] or Q[i][j] > b[j]:
                        Q[i][j] = a[j] + d["u_box"][i][j] * (b[j] - a[j])
        for row in Q:
            row[-1] = fhd(row[:D])
        self.FES += N
        succ = [i for i in range(N) if Q[i][-1] <= P[i][-1]]
        self.ni[1] += len(succ)
        SR = len(succ) / N
        if g < gt:
            SRT = 0 if g < gt else 0.1
            self.Tcurr = self.Tcurr + 1 if SR <= SRT else 0
            if self.Tcurr >= self.T:
                self.gt = g
        for i in succ:
            P[i] = Q[i]
        self.P, (self.CBF, self.CBCR) = sortrows(P, self.CBF, self.CBCR)
        self.g += 1

    def cmaes(self, d, fhd):
        N, D, a, b = self.N, self.D, self.a, self.b
        self.P, (self.CBF, self.CBCR) = sortrows(self.P, self.CBF, self.CBCR)
        P = self.P
        xmean = np.array([row[:D] for row in P[: self.mu]]).T @ self.weights
        Pop, PopFit = np.zeros((D, N)), np.zeros(N)
        for kk in range(N):
            Pop[:, kk] = xmean + (self.sigma * self.B) @ (self.Dv * d["z"][kk])
            for j in range(D):
                if Pop[j, kk] < a[j]:
                    Pop[j, kk] = (self.oldPop[j, kk] + a[j]) / 2
            for j in range(D):
                if Pop[j, kk] > b[j]:
                    Pop[j, kk] = (self.oldPop[j, kk] + b[j]) / 2
            PopFit[kk] = fhd(Pop[:, kk])
            self.FES += 1
            fits = [row[-1] for row in P]
            maxind = int(np.argmax(fits))
            if PopFit[kk] < fits[maxind]:
                P[maxind] = np.append(Pop[:, kk], PopFit[kk])
                self.ni[2] += 1
        FitInd = sorted(range(N), key=lambda i: PopFit[i])
        xold = xmean
        xmean = Pop[:, FitInd[: self.mu]] @ self.weights
        self.oldPop = Pop
        cs, cc, c1, cmu, mueff = self.cs, self.cc, self.c1, self.cmu, self.mueff
        self.ps = (1 - cs) * self.ps + (math.sqrt(cs * (2 - cs) * mueff) * self.invsqrtC) @ (
            xmean - xold
        ) / self.sigma
        hsig = float(
            np.sum(self.ps**2) / (1 - (1 - cs) ** (2 * self.FES / N)) / D < 2 + 4 / (D + 1)
        )
        self.pc = (1 - cc) * self.pc + hsig * math.sqrt(cc * (2 - cc) * mueff) * (
            xmean - xold
        ) / self.sigma
        artmp = (1 / self.sigma) * (Pop[:, FitInd[: self.mu]] - xold[:, None])
        self.CC = (
            (1 - c1 - cmu) * self.CC
            + c1 * (np.outer(self.pc, self.pc) + (1 - hsig) * cc * (2 - cc) * self.CC)
            + cmu * artmp @ np.diag(self.weights) @ artmp.T
        )
        step = (cs / self.damps) * (np.linalg.norm(self.ps) / self.chiN - 1)
        self.sigma = self.sigma * math.exp(step)
        if self.sigma > 1e300 or self.sigma < 1e-300 or math.isnan(self.sigma):
            self.sigma = (b[0] - a[0]) / 2
        if self.FES - self.eigeneval > N / (c1 + cmu) / D / 10:
            self.eigeneval = self.FES
            self.CC = np.triu(self.CC) + np.triu(self.CC, 1).T
            vals, self.B = np.linalg.eigh(self.CC)
            self.Dv = np.sqrt(np.maximum(vals, np.finfo(float).tiny))
            self.invsqrtC = self.B @ np.diag(self.Dv**-1) @ self.B.T

    def jso(self, d, fhd):
        N, D, a, b, FES, M = self.N, self.D, self.a, self.b, self.FES, self.maxFES
        P = self.P
        pp = 0.25 - ((0.25 - 0.125) * (FES / M))
        eig = d["u_eig"] < 0.4
        if eig:
            E = self.eig_vectors()
        Fpole, CRpole, Q = [], [], []
        for i in range(N):
            rr = min(int(d["u_mem"][i] * self.H), self.H - 1)
            CR = min(max(self.MCR[rr] + math.sqrt(0.1) * d["z"][i], 0.0), 1.0)
            if FES < 0.25 * M:
                CR = max(CR, 0.7)
            elif FES < 0.5 * M:
                CR = max(CR, 0.6)
            F = min(positive_cauchy(self.MF[rr], d["u_f"][i]), 1.0)
            if FES < 0.6 * M and F > 0.7:
                F = 0.7
            Fpole.append(F)
            CRpole.append(CR)
            p = max(2, math.ceil(pp * N))
            pom, _ = sortrows(P)
            xpbest = pom[min(int(p * d["u_pb"][i]), p - 1)][:D]
            xi = P[i][:D]
            support = [j for j in range(N) if j != i]
            vyb = pick_from(support, d["u_r1"][i])
            r1 = P[vyb][:D]
            support = [j for j in range(N + len(self.A)) if j not in (i, vyb)]
            sjed = [row[:D] for row in P] + self.A
            r2 = sjed[pick_from(support, d["u_r2"][i])]
            Fw = 0.7 * F if FES < 0.2 * M else 0.8 * F if FES < 0.4 * M else 1.2 * F
            v = xi + Fw * (xpbest - xi) + F * (r1 - r2)
            y = xi.copy()
            if eig:
                yeig, veig = E.T @ y, E.T @ v
                change = change_set(d["u_cr"][i], self.CBCR[i], d["u_j"][i], D)
                yeig[change] = veig[change]
                y = E @ yeig
            else:
                change = change_set(d["u_cr"][i], CR, d["u_j"][i], D)
                y[change] = v[change]
                y = zrcad(y, a, b)
            Q.append(np.append(y, fhd(y)))
        SCR, SF, delta, suc = [], [], [], 0
        for i in range(N):
            if Q[i][-1] < P[i][-1]:
                delta.append(P[i][-1] - Q[i][-1])
                suc += 1
                if len(self.A) < self.Asize_max:
                    self.A.append(P[i][:D].copy())
                else:
                    slot = min(int(d["u_slot"][i] * len(self.A)), len(self.A) - 1)
                    self.A[slot] = P[i][:D].copy()
                SCR.append(CRpole[i])
                SF.append(Fpole[i])
            if Q[i][-1] <= P[i][-1]:
                P[i] = Q[i]
        if suc > 0:
            k = self.k
            MCR_old, MF_old = self.MCR[k], self.MF[k]
            s = 0.0
            for x in delta:
                s += x
            w = [(1 / s) * x for x in delta]
            if self.MCR[k] == -1 or max(SCR) == 0:
                self.MCR[k] = -1
            else:
                jm = [w[m] * SCR[m] for m in range(suc)]
                self.MCR[k] = _seq(jm[m] * SCR[m] for m in range(suc)) / _seq(jm)
            jm = [w[m] * SF[m] for m in range(suc)]
            self.MF[k] = _seq(jm[m] * SF[m] for m in range(suc)) / _seq(jm)
            self.MCR[k] = (self.MCR[k] + MCR_old) / 2
            self.MF[k] = (self.MF[k] + MF_old) / 2
            self.k = k + 1
            if self.k + 1 >= self.H:
                self.k = 0
        self.FES += N
        self.ni[3] += suc


def _seq(values):
    total = 0.0
    for x in values:
        total += x
    return total
