"""Seeded scene families for planning benchmarks, each scene validated and with its exact ``L*``.

>>> from mawdo.planning.scenes import generate_scenes
>>> scenes = generate_scenes("forest", 3, seed=7, params={"n": 12})  # doctest: +SKIP
>>> scenes[0].l_star, scenes[0].write("out/scenes")                   # doctest: +SKIP

Families (:data:`FAMILIES`): ``open``, ``forest``, ``rooms``, ``maze``, ``u_trap``, ``narrow``
(static), ``crossing``, ``dense``, ``movingai`` (with moving obstacles), and the families
where time decides (each scene has its earliest arrival ``T*``): ``corridor``,
``doorway``, ``chaser``, ``crowd``, ``parked``, ``slalom``, and at scale (1000-2000 px,
100-500 movers) ``crowd-large`` and ``warehouse-large``. ``describe_family``
lists a family's parameters with their ranges. A scene is a pure function of
``(family, params, seed, index)`` (see :mod:`mawdo.planning.scenes.base`).
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

from mawdo.planning.scenes.base import (
    MAX_ATTEMPTS,
    Family,
    Param,
    Scene,
    SceneRejected,
    build_scene,
)
from mawdo.planning.scenes.lanes import CORRIDOR, DOORWAY, PARKED, SLALOM
from mawdo.planning.scenes.large import CROWD_LARGE, WAREHOUSE_LARGE
from mawdo.planning.scenes.movingai import MOVINGAI
from mawdo.planning.scenes.pursuit import CHASER, CROWD
from mawdo.planning.scenes.static import FOREST, MAZE, OPEN, ROOMS
from mawdo.planning.scenes.toml import scenario_to_toml, write_scenario
from mawdo.planning.scenes.traffic import CROSSING, DENSE
from mawdo.planning.scenes.traps import NARROW, U_TRAP
from mawdo.registry import Registry

__all__ = [
    "FAMILIES",
    "MAX_ATTEMPTS",
    "Family",
    "Param",
    "Scene",
    "SceneRejected",
    "TIMED_FAMILIES",
    "describe_family",
    "generate_scene",
    "generate_scenes",
    "scenario_to_toml",
    "write_scenario",
]

#: Registered scene families by name.
FAMILIES: Registry[Family] = Registry("scene family")
#: Families where time decides: each scene stores its earliest arrival ``T*``.
TIMED_FAMILIES = (
    *("corridor", "doorway", "chaser", "crowd", "parked", "slalom"),
    *("crowd-large", "warehouse-large"),
)
for _f in (
    *(OPEN, FOREST, ROOMS, MAZE, U_TRAP, NARROW, CROSSING, DENSE, MOVINGAI),
    *(CORRIDOR, DOORWAY, CHASER, CROWD, PARKED, SLALOM, CROWD_LARGE, WAREHOUSE_LARGE),
):
    FAMILIES.register(_f.name, _f)


def _check_int(name: str, value, low: int) -> int:
    if isinstance(value, bool) or not isinstance(value, int) and not hasattr(value, "__index__"):
        raise TypeError(f"{name} must be an integer, got {value!r}")
    value = int(value)
    if value < low:
        raise ValueError(f"{name} must be >= {low}, got {value}")
    return value


def generate_scene(
    family: str, index: int = 0, seed: int = 0, params: Mapping[str, Any] | None = None
) -> Scene:
    """Scene ``index`` of a family for a master ``seed``.

    Parameters
    ----------
    family : str
        A name in :data:`FAMILIES` (unknown names get close-name suggestions).
    index : int
        Scene number, >= 0; the scene does not depend on any other index.
    seed : int
        Master seed, >= 0.
    params : mapping, optional
        Family parameters overriding the defaults (see :func:`describe_family`).

    Returns
    -------
    Scene
        Validated: start and goal free, a static route exists, ``l_star`` its exact length.

    Raises
    ------
    mawdo.registry.UnknownNameError
        Unknown family.
    ValueError
        Unknown parameter, a value out of its range, or parameters that cannot work together.
    SceneRejected
        No valid scene in ``MAX_ATTEMPTS`` draws (a ``ValueError`` listing the reasons).
    """
    fam = FAMILIES[family]
    p = fam.resolve(params)
    return build_scene(fam, p, _check_int("seed", seed, 0), _check_int("index", index, 0))


def generate_scenes(
    family: str,
    n: int,
    seed: int = 0,
    params: Mapping[str, Any] | None = None,
    first: int = 0,
) -> list[Scene]:
    """Scenes ``first .. first + n - 1`` of a family (see :func:`generate_scene`).

    Parameters
    ----------
    n : int
        Number of scenes, >= 1.
    first : int
        Index of the first scene, >= 0.
    """
    fam = FAMILIES[family]
    p = fam.resolve(params)
    n = _check_int("n", n, 1)
    first = _check_int("first", first, 0)
    seed = _check_int("seed", seed, 0)
    return [build_scene(fam, p, seed, i) for i in range(first, first + n)]


def describe_family(family: str) -> str:
    """A family's description and its parameters with defaults and ranges, one per line."""
    fam = FAMILIES[family]
    lines = [f"{fam.name}: {fam.description}"]
    for p in fam.all_params:
        rng = f"one of {list(p.choices)}" if p.choices else f"[{p.low:g}, {p.high:g}]"
        lines.append(f"  {p.name} = {p.default!r}  {rng}  {p.doc}")
    return "\n".join(lines)
