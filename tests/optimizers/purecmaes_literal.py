"""A literal transcription of ``purecmaes_wdo.m`` (Bayraktar's AWDO code), one run, plain Python.

Written statement by statement from the MATLAB source, 0-based, lists instead of matrices; only
the eigen decomposition of the 4 x 4 covariance is NumPy's (``eig`` of a symmetric matrix). The
source sorts ``'descend'`` in its maximising copy; AWDO minimises, as Hansen's ``purecmaes.m``,
so this sorts ascending. ``rec`` is a dict as the source's struct.
"""

from __future__ import annotations

import math

import numpy as np


def _matvec(M, v):
    return [sum(M[i][j] * v[j] for j in range(len(v))) for i in range(len(M))]


def purecmaes_wdo(counteval, rec, npop, pressure, xmean0, randn):
    """One call. ``xmean0`` stands for ``rand(N, 1)`` at the first call, ``randn(k)`` for the
    k-th sample's ``randn(N, 1)``; ``rec["arx"]`` holds the samples (one list per sample)."""
    if counteval == 2:
        N = rec["N"] = 4
        rec["xmean"] = list(xmean0)
        rec["sigma"] = 0.5
        rec["lambda"] = npop
        mu = npop / 2
        weights = [math.log(mu + 1 / 2) - math.log(k) for k in range(1, math.floor(mu) + 1)]
        rec["mu"] = math.floor(mu)
        total = sum(weights)
        rec["weights"] = [w / total for w in weights]
        rec["mueff"] = sum(rec["weights"]) ** 2 / sum(w * w for w in rec["weights"])
        me = rec["mueff"]
        rec["cc"] = (4 + me / N) / (N + 4 + 2 * me / N)
        rec["cs"] = (me + 2) / (N + me + 5)
        rec["c1"] = 2 / ((N + 1.3) ** 2 + me)
        rec["cmu"] = min(1 - rec["c1"], 2 * (me - 2 + 1 / me) / ((N + 2) ** 2 + me))
        rec["damps"] = 1 + 2 * max(0, math.sqrt((me - 1) / (N + 1)) - 1) + rec["cs"]
        rec["pc"] = [0.0] * N
        rec["ps"] = [0.0] * N
        rec["B"] = [[float(i == j) for j in range(N)] for i in range(N)]
        rec["D"] = [1.0] * N
        rec["C"] = [[float(i == j) for j in range(N)] for i in range(N)]
        rec["invsqrtC"] = [[float(i == j) for j in range(N)] for i in range(N)]
        rec["eigeneval"] = 0
        rec["chiN"] = N**0.5 * (1 - 1 / (4 * N) + 1 / (21 * N**2))
    N, lam, mu, w = rec["N"], rec["lambda"], rec["mu"], rec["weights"]
    cs, cc, c1, cmu, me = rec["cs"], rec["cc"], rec["c1"], rec["cmu"], rec["mueff"]
    arindex = sorted(range(lam), key=lambda k: pressure[k])  # sort(): stable, ascending
    xold = rec["xmean"]
    arx = rec["arx"]
    xmean = [sum(arx[arindex[m]][d] * w[m] for m in range(mu)) for d in range(N)]
    rec["xmean"] = xmean
    diff = [(xmean[d] - xold[d]) / rec["sigma"] for d in range(N)]
    isc = _matvec(rec["invsqrtC"], diff)
    rec["ps"] = [(1 - cs) * rec["ps"][d] + math.sqrt(cs * (2 - cs) * me) * isc[d] for d in range(N)]
    hsig = sum(v * v for v in rec["ps"]) / (1 - (1 - cs) ** (2 * counteval / lam)) / N < 2 + 4 / (
        N + 1
    )
    kc = math.sqrt(cc * (2 - cc) * me)
    rec["pc"] = [(1 - cc) * rec["pc"][d] + hsig * kc * diff[d] for d in range(N)]
    artmp = [[(arx[arindex[m]][d] - xold[d]) / rec["sigma"] for m in range(mu)] for d in range(N)]
    C = rec["C"]
    pc = rec["pc"]
    rec["C"] = [
        [
            (1 - c1 - cmu) * C[i][j]
            + c1 * (pc[i] * pc[j] + (1 - hsig) * cc * (2 - cc) * C[i][j])
            + cmu * sum(artmp[i][m] * w[m] * artmp[j][m] for m in range(mu))
            for j in range(N)
        ]
        for i in range(N)
    ]
    norm_ps = math.sqrt(sum(v * v for v in rec["ps"]))
    rec["sigma"] = rec["sigma"] * math.exp((cs / rec["damps"]) * (norm_ps / rec["chiN"] - 1))
    if counteval - rec["eigeneval"] > lam / (c1 + cmu) / N / 10:
        rec["eigeneval"] = counteval
        C = rec["C"]
        C = [[C[i][j] if j >= i else C[j][i] for j in range(N)] for i in range(N)]  # triu + triu'
        C = [[min(100000, C[i][j]) for j in range(N)] for i in range(N)]
        rec["C"] = C
        vals, vecs = np.linalg.eigh(np.array(C))
        rec["B"] = vecs.tolist()
        rec["D"] = [math.sqrt(v) for v in vals]
        B, D = rec["B"], rec["D"]
        rec["invsqrtC"] = [
            [sum(B[i][k] / D[k] * B[j][k] for k in range(N)) for j in range(N)] for i in range(N)
        ]
    B, D = rec["B"], rec["D"]
    rec["arx"] = []
    for k in range(lam):
        bdz = _matvec(B, [D[d] * randn[k][d] for d in range(N)])
        rec["arx"].append([xmean[i] + rec["sigma"] * bdz[i] for i in range(N)])
    return rec
