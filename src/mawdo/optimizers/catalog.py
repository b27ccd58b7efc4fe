"""Every registered algorithm: references and the preset options of each variant.

MAWDO's ablations (paper Table 5) are configurations of :class:`~mawdo.optimizers.wdo.Wind`.
"""

from __future__ import annotations

from mawdo.optimizers.awdo_cmaes import AWDOCMA
from mawdo.optimizers.gwo import GWO
from mawdo.optimizers.mewdo import MEWDO
from mawdo.optimizers.registry import AlgorithmSpec, register
from mawdo.optimizers.wdo import Wind
from mawdo.optimizers.woa import WOA

WDO_REF = "Bayraktar, Komurcu, Bossard & Werner, IEEE TAP 61(5):2745-2757, 2013; authors' WDO.m"
AWDO_REF = "MAWDO paper Eq. 4 (Liu, Mohd Zain & Mao, arXiv 2511.20394), after Bayraktar 2015"
MAWDO_REF = "Liu, Mohd Zain & Mao, 'Improved adaptive WDO for real-time path planning', 2025"

AWDO = {"velocity": "awdo"}
GROUPS = {"groups": 8, "rank_scope": "group"}
HIER = {"guidance": "hierarchical", "schedule": True, "gate": True}
PGR = {"restart": True, "obl": True}
LOWD = {"low_dim_stabilization": True, "groups": 8}

register(AlgorithmSpec("wdo", Wind, {}, WDO_REF, "Wind Driven Optimization", label="WDO"))
register(
    AlgorithmSpec(
        "awdo",
        Wind,
        AWDO,
        AWDO_REF,
        "Adaptive WDO: coefficients ~ U[0,1] each iteration, rank-divided pressure",
        label="AWDO",
    )
)
register(
    AlgorithmSpec(
        "awdo_cmaes",
        AWDOCMA,
        {},
        "Bayraktar & Komurcu, 'Adaptive WDO', 2015; authors' AWDO_v03.m",
        "AWDO with per-parcel coefficients adapted by CMA-ES (no extra evaluations)",
        label="AWDO-CMA",
    )
)
register(
    AlgorithmSpec(
        "mawdo1",
        Wind,
        {**AWDO, **GROUPS, "guidance": "group"},
        MAWDO_REF,
        "ablation: AWDO + 8 groups (B = group best)",
        label="MAWDO-1",
    )
)
register(
    AlgorithmSpec(
        "mawdo2",
        Wind,
        {**AWDO, **GROUPS, **HIER},
        MAWDO_REF,
        "ablation: AWDO + scheduled triple guidance + distance gate (G = 8)",
        label="MAWDO-2",
    )
)
register(
    AlgorithmSpec(
        "mawdo3",
        Wind,
        {**AWDO, **PGR},
        MAWDO_REF,
        "ablation: AWDO + periodic guided restart + opposition-based learning",
        label="MAWDO-3",
    )
)
register(
    AlgorithmSpec(
        "mawdo4",
        Wind,
        {**AWDO, **LOWD},
        MAWDO_REF,
        "ablation: AWDO + low-dimensional stabilisation (D <= 3)",
        label="MAWDO-4",
    )
)
register(
    AlgorithmSpec(
        "mawdo",
        Wind,
        {**AWDO, **GROUPS, **HIER, **PGR, **LOWD, "boundary": "reflect"},
        MAWDO_REF,
        "MAWDO: all components (groups, guidance, gate, PGR+OBL, reflection, low-D)",
        label="MAWDO",
    )
)
register(
    AlgorithmSpec(
        "mewdo",
        MEWDO,
        {},
        "Zhang, Yang & Chen, Math. Comput. Simul. 231, 2025 (text unavailable)",
        "multi-strategy ensemble WDO with success-adaptive shares",
        reconstructed=True,
        label="MEWDO",
    )
)
register(
    AlgorithmSpec(
        "gwo",
        GWO,
        {},
        "Mirjalili, Mirjalili & Lewis, Adv. Eng. Softw. 69:46-61, 2014; GWO.m",
        "Grey Wolf Optimizer",
        label="GWO",
    )
)
register(
    AlgorithmSpec(
        "woa",
        WOA,
        {},
        "Mirjalili & Lewis, Adv. Eng. Softw. 95:51-67, 2016; WOA.m",
        "Whale Optimization Algorithm as WOA.m (random whale per coordinate, in-place moves)",
        label="WOA",
    )
)

# Sets the experiment presets and reports use.
PAPER_ALGORITHMS = ("gwo", "woa", "wdo", "awdo", "mewdo", "mawdo")
ABLATION_ALGORITHMS = ("mawdo1", "mawdo2", "mawdo3", "mawdo4", "mawdo")

# Reference algorithms for standard black-box benchmarking (BBOB, CEC).
from mawdo.optimizers.cmaes_ref import CMAES  # noqa: E402
from mawdo.optimizers.random_search import RandomSearch  # noqa: E402

register(
    AlgorithmSpec(
        "cmaes",
        CMAES,
        {},
        "Hansen & Ostermeier, Evol. Comput. 9(2), 2001; the 'cmaes' library (CyberAgentAILab)",
        "CMA-ES, one cmaes.CMA per run, restarts with the same lambda when it stalls",
        label="CMA-ES",
    )
)
register(
    AlgorithmSpec(
        "random",
        RandomSearch,
        {},
        "uniform random search (baseline)",
        "uniform random sampling in the box",
        label="Random",
    )
)

from mawdo.optimizers.scipy_de import ScipyDE  # noqa: E402

register(
    AlgorithmSpec(
        "scipy_de",
        ScipyDE,
        {},
        "Storn & Price, J. Global Optim. 11, 1997; scipy.optimize.differential_evolution",
        "scipy's differential evolution (its defaults), one call per run, restarted when it ends",
        label="DE (scipy)",
    )
)

from mawdo.optimizers.wdo_plus import WDOPlus  # noqa: E402

register(
    AlgorithmSpec(
        "wdo_plus",
        WDOPlus,
        {},
        "this library, after Bayraktar et al. 2013's WDO; docs/algorithms.md#wdo-plus",
        "WDO+: gravity toward the personal bests' mean, success-adapted noise, restarts, "
        "midpoint bounds",
        label="WDO+",
    )
)

# The hold-out field: the references, the paper's algorithms and the variant.
HOLDOUT_ALGORITHMS = ("cmaes", "scipy_de", "random", *PAPER_ALGORITHMS, "wdo_plus")

# The success-history DE family that wins the CEC competitions (docs/algorithms.md#lshade).
from mawdo.optimizers.lshade import LShade  # noqa: E402

JSO = {
    "size_rule": "25sqrtDlnD",
    "memory_size": 5,
    "arc_rate": 1.0,
    "p_best": 0.25,
    "memory_f": 0.3,
    "memory_cr": 0.8,
    "rules": "jso",
}

register(
    AlgorithmSpec(
        "lshade",
        LShade,
        {},
        "Tanabe & Fukunaga, IEEE CEC 2014, pp. 1658-1665; Tanabe's lshade.cc 1.1",
        "L-SHADE: success-history DE, current-to-pbest/1 with archive, linear size reduction",
        label="L-SHADE",
    )
)
register(
    AlgorithmSpec(
        "jso",
        LShade,
        JSO,
        "Brest, Maucec & Boskovic, IEEE CEC 2017, pp. 1311-1318; the authors' jSO C++ code",
        "jSO: L-SHADE with current-to-pBest-w/1, phase limits on F and CR, falling p",
        label="jSO",
    )
)

from mawdo.optimizers.nlshade_rsp import NLShadeRSP  # noqa: E402

register(
    AlgorithmSpec(
        "nlshade_rsp",
        NLShadeRSP,
        {},
        "Stanovov, Akhmedova & Semenkin, IEEE CEC 2021, pp. 809-816; the authors' C++ code",
        "NL-SHADE-RSP: non-linear size reduction, rank-based r2, adaptive archive use",
        label="NL-SHADE-RSP",
    )
)

from mawdo.optimizers.ea4eig import EA4eig  # noqa: E402

register(
    AlgorithmSpec(
        "ea4eig",
        EA4eig,
        {},
        "Bujok & Kolenovsky, IEEE CEC 2022, pp. 1-8; the authors' MATLAB code (Kudela's "
        "alg_EA4eig.m)",
        "EA4eig: CoBiDE, IDE, CMA-ES and jSO chosen by a success roulette, eigen crossover",
        label="EA4eig",
    )
)

# The competitions' own protocols rank a method against those who won them: the hold-out field
# and four winners.
CEC_WINNERS = ("lshade", "jso", "nlshade_rsp", "ea4eig")
OFFICIAL_ALGORITHMS = (*HOLDOUT_ALGORITHMS, *CEC_WINNERS)
