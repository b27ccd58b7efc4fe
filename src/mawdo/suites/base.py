"""Standard problem suites as registered sources: the record, the registry and the checks.

A suite (``bbob``, ``cec2017``, ``cec2022``, ``cec2017-opfunu``, ...) turns ``(function,
instance, dimension)`` into a :class:`SuiteFunction`, a :class:`~mawdo.functions.BenchmarkFunction`
whose formula evaluates a whole batch: through the suite's library (``ioh``; ``opfunu`` row by
row) or mawdo's port of the official CEC code. It is therefore accepted as is by
:func:`mawdo.minimize` (bounds and ``f_star`` travel with it). The libraries come with the
optional extra ``bbob``; every entry point says how to install it when it is missing.
"""

from __future__ import annotations

import dataclasses
import importlib
import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from mawdo.functions.base import BenchmarkFunction
from mawdo.registry import Registry, UnknownNameError, unknown_name_message

INSTALL_HINT = 'pip install "mawdo[bbob]" (or pip install -e ".[bbob]" in a clone of mawdo)'


class MissingExtraError(ImportError):
    """A suite's library is not installed; the message names the ``pip install`` that fixes it."""


def require(module: str, suite: str):
    """Import ``module`` for ``suite`` or raise :class:`MissingExtraError` with the fix."""
    try:
        return importlib.import_module(module)
    except ImportError as exc:
        raise MissingExtraError(
            f"suite {suite!r} needs the package {module.split('.')[0]!r}, which is not installed "
            f"(it comes with the optional extra 'bbob'): {INSTALL_HINT}"
        ) from exc


@dataclass(frozen=True, eq=False, repr=False)
class SuiteFunction(BenchmarkFunction):
    """A problem of a standard suite: a :class:`BenchmarkFunction` plus where it comes from.

    Parameters
    ----------
    suite : str
        Registered suite name (``"bbob"``, ``"cec2017"``, ``"cec2022"``).
    function_id : int
        1-based function number within the suite.
    instance : int
        Instance number (BBOB: >= 1; CEC suites define only instance 1).
    function_name : str
        The library's own name of the function (IOHanalyzer shows it).

    Notes
    -----
    ``f_star`` is the library's optimum value; the precision of a value ``f`` is
    ``f - f_star`` (COCO's "f - f_opt"). The formula is a picklable object that rebuilds the
    library's problem in each process.
    """

    suite: str = ""
    function_id: int = 0
    instance: int = 1
    function_name: str = ""

    def __repr__(self) -> str:
        return (
            f"<SuiteFunction {self.suite} f{self.function_id} ({self.function_name}) "
            f"instance {self.instance}: D={self.dim}, [{self.lb[0]:g}, {self.ub[0]:g}]^{self.dim}, "
            f"f*={self.f_star!r}>"
        )


@dataclass(frozen=True)
class CompetitionScore:
    """How a competition scores its entries from their mean final errors (CEC 2017's score).

    Attributes
    ----------
    name : str
        The score's name in reports (``"CEC 2017 score"``).
    weights : dict of int to float
        Weight of each dimension's sums (CEC 2017: 0.1, 0.2, 0.3, 0.4 for D = 10, 30, 50,
        100); a study's other dimensions do not count.
    excluded : tuple of int
        Function ids the score leaves out (CEC 2017: F2).
    source : str
        Where the rule is written, for the report's note.
    """

    name: str
    weights: dict[int, float]
    excluded: tuple[int, ...] = ()
    source: str = ""


@dataclass(frozen=True)
class SuiteSpec:
    """A registered suite.

    Attributes
    ----------
    name : str
        Registry name.
    description : str
        One line for listings.
    function_names : tuple of str
        Library names of functions ``1..len``; also accepted (case-insensitive) as ids.
    dims : callable
        ``dims(function_id) -> tuple of int``: the dimensions the suite defines for a function.
    build : callable
        ``build(function_id, instance, dim) -> SuiteFunction``; called after validation.
    library : str
        The module that computes the values (``"ioh"``, ``"opfunu.cec_based.cec2017"``,
        ``"numpy"`` for the official CEC code's port); :meth:`require` imports it. Its top
        package is the pip package.
    label : str
        Display name in reports and exported logs (``"BBOB"``, ``"CEC2017"``).
    max_instance : int or None
        Largest instance (None: unbounded).
    default_instances : tuple of int
        Instances a study runs when none are named (BBOB: COCO's 1-5; CEC: its one).
    groups : dict of str to tuple of int
        Named groups of function ids that reports break results down by (BBOB: COCO's five);
        empty when the suite defines none.
    prepare : callable or None
        ``prepare(function_id, dim)`` reads and checks what the problem needs from files
        (CEC: the official data), raising an error that names the file; None: nothing to read.
    checkpoints : callable or None
        ``checkpoints(dim, max_evals) -> tuple of int``: the evaluations after which the
        suite's competition records errors (CEC), for its result tables; None: none defined.
    score : CompetitionScore or None
        The competition's overall score of algorithms, for its reports; None: none defined.
    """

    name: str
    description: str
    function_names: tuple[str, ...]
    dims: Callable[[int], tuple[int, ...]]
    build: Callable[[int, int, int], SuiteFunction]
    library: str
    label: str
    max_instance: int | None = None
    default_instances: tuple[int, ...] = (1,)
    groups: dict[str, tuple[int, ...]] = dataclasses.field(default_factory=dict)
    prepare: Callable[[int, int], None] | None = None
    checkpoints: Callable[[int, int], tuple[int, ...]] | None = None
    score: CompetitionScore | None = None

    def require(self) -> None:
        """Import the suite's library now; :class:`MissingExtraError` names the ``pip install``
        that fixes a missing one."""
        require(self.library, self.name)

    def check_problems(self, functions, dims) -> None:
        """Import the library and read every data file the ``functions x dims`` problems need
        (those the suite defines), so a missing or damaged file stops a study before it runs.

        Raises
        ------
        MissingExtraError
            The library (or the package holding the data) is not installed.
        ValueError
            A data file is missing or damaged (the message names the function and the file).
        """
        self.require()
        if self.prepare is None:
            return
        for fid in functions:
            for dim in dims:
                if dim in self.dims(fid):
                    self.prepare(fid, dim)

    @property
    def functions(self) -> tuple[int, ...]:
        return tuple(range(1, len(self.function_names) + 1))

    def function_id(self, function) -> int:
        """The 1-based id of ``function`` (an int, ``"f7"``, ``"7"`` or the library's name)."""
        n = len(self.function_names)
        if isinstance(function, bool):
            raise TypeError(f"{self.name} function id must be an int or a name, got a bool")
        if isinstance(function, int | np.integer):
            if 1 <= function <= n:
                return int(function)
            raise UnknownNameError(
                f"unknown {self.name} function {int(function)}: {self.name} defines functions 1-{n}"
            )
        if not isinstance(function, str):
            raise TypeError(
                f"{self.name} function id must be an int or a name, got {type(function).__name__}"
            )
        key = function.strip().lower()
        digits = key[1:] if key.startswith("f") else key
        if digits.isdigit():
            return self.function_id(int(digits))
        names = {nm.lower(): i + 1 for i, nm in enumerate(self.function_names)}
        if key in names:
            return names[key]
        known = list(dict.fromkeys([f"f{i}" for i in self.functions] + list(names)))
        raise UnknownNameError(unknown_name_message(f"{self.name} function", function, known))

    def problem(self, function, instance: int = 1, dim: int = 10) -> SuiteFunction:
        """Validate ``(function, instance, dim)`` and build the problem.

        Raises
        ------
        UnknownNameError
            Unknown function id or name (close names suggested).
        ValueError
            A dimension the suite does not define for this function, or a bad instance.
        MissingExtraError
            The suite's library is not installed.
        """
        fid = self.function_id(function)
        if isinstance(instance, bool) or not isinstance(instance, int | np.integer) or instance < 1:
            raise ValueError(f"instance={instance!r} must be an integer >= 1")
        if self.max_instance is not None and instance > self.max_instance:
            raise ValueError(
                f"{self.name} defines instances 1-{self.max_instance}; got instance={instance}"
            )
        allowed = self.dims(fid)
        if isinstance(dim, bool) or not isinstance(dim, int | np.integer) or dim not in allowed:
            raise ValueError(
                f"{self.name} f{fid} is not defined in dimension {dim!r}; "
                f"its dimensions are {format_dims(allowed)}"
            )
        return self.build(fid, int(instance), int(dim))


def format_dims(dims: tuple[int, ...]) -> str:
    """``(2, 3, ..., 40)`` -> ``"2-40"``; anything else as a comma list."""
    if len(dims) > 2 and dims == tuple(range(dims[0], dims[-1] + 1)):
        return f"{dims[0]}-{dims[-1]}"
    return ", ".join(map(str, dims))


SUITES: Registry[SuiteSpec] = Registry("suite")


def register_suite(spec: SuiteSpec) -> SuiteSpec:
    return SUITES.register(spec.name, spec)


def get_problem(suite: str, function, instance: int = 1, dim: int = 10) -> SuiteFunction:
    """A problem of a registered suite, ready for :func:`mawdo.minimize`.

    Parameters
    ----------
    suite : str
        ``"bbob"``, ``"cec2017"``, ``"cec2022"``, ``"cec2017-opfunu"`` or ``"cec2022-opfunu"``
        (close names are suggested on a miss).
    function : int or str
        Function id ``1..n`` (``3``, ``"f3"``) or the library's name (``"rastrigin"``).
    instance : int
        Instance, >= 1 (BBOB instances change the optimum's place and value; CEC has one).
    dim : int
        Dimension D: BBOB 2-40; CEC 2017 {2, 10, 20, 30, 50, 100}, but {10, 30, 50, 100} for
        its hybrid functions F11-F19 and compositions F29-F30 and {10, 20, 30, 50, 100} for F20
        (opfunu: not 20 for F20); CEC 2022 {2, 10, 20}, but {10, 20} for its hybrids F6-F8.

    Examples
    --------
    >>> from mawdo import minimize
    >>> f = get_problem("bbob", 3, instance=1, dim=5)  # doctest: +SKIP
    >>> minimize(f, algorithm="cmaes", runs=5, max_evals=500 * f.dim)  # doctest: +SKIP
    """
    return SUITES[suite].problem(function, instance, dim)


def evaluation_budget(budget: float, dim: int) -> int:
    """Evaluations per run for a budget given in evaluations per dimension (COCO's convention).

    Parameters
    ----------
    budget : float
        Evaluations per dimension, > 0 (``1e4`` -> ``1e4 * D`` evaluations).
    dim : int
        Dimension D >= 1.

    Returns
    -------
    int
        ``ceil(budget * D)``, >= 1.
    """
    if isinstance(budget, bool) or not isinstance(budget, int | float | np.integer | np.floating):
        raise TypeError(f"budget must be a number of evaluations per dimension, got {budget!r}")
    if not (math.isfinite(budget) and budget > 0):
        raise ValueError(
            f"budget={budget!r} must be a finite number of evaluations per dimension > 0 "
            "(e.g. 1e4 for 10^4 * D evaluations per run)"
        )
    if isinstance(dim, bool) or not isinstance(dim, int | np.integer) or dim < 1:
        raise ValueError(f"dim={dim!r} must be an integer >= 1")
    return max(1, math.ceil(budget * dim - 1e-9))


def run_problem(
    problem: SuiteFunction,
    algorithm="mawdo",
    *,
    runs: int,
    budget: float,
    seed=0,
    first_run: int = 0,
    final_target: float | None = 1e-8,
    **options,
):
    """Run ``algorithm`` on a suite problem under COCO's protocol, recording every run's
    best-so-far against evaluations.

    Parameters
    ----------
    problem : SuiteFunction
        From :func:`get_problem`.
    algorithm : str or Optimizer
        Any registered optimizer (``cmaes``, ``random``, ``mawdo``, ...).
    runs : int
        Independent runs, >= 1 (in blocks of runs, see :func:`mawdo.minimize`).
    budget : float
        Evaluations per dimension, > 0; each run gets exactly ``ceil(budget * D)`` evaluations
        (OBL's extra evaluations count), fewer if it reaches the final target.
    seed, first_run
        As in :func:`mawdo.minimize`; run ``k`` is the same alone or in any batch.
    final_target : float or None
        Precision ``f - f_star`` at which a run stops (COCO's last target, 1e-8); None runs
        the whole budget.
    **options
        The algorithm's coefficients.

    Returns
    -------
    OptimizeResult
        The driver's result; ``evaluation_trace`` holds one
        :class:`~mawdo.result.EvaluationTrace` per run.
    """
    from mawdo.minimize import minimize

    return minimize(
        problem,
        algorithm=algorithm,
        runs=runs,
        seed=seed,
        first_run=first_run,
        max_evals=evaluation_budget(budget, problem.dim),
        target=None if final_target is None else problem.f_star + final_target,
        trace_evaluations=True,
        **options,
    )
