"""Plan of the crowd-navigation study: settings x policies x seeded episodes.

A *setting* names a CrowdNav scene: ``<scene>-<people>-<visibility>``, e.g.
``circle-5-invisible`` (circle crossing, 5 people who do not see the robot) or
``square-10-visible``. The harness's ``(algorithm, problem, run)`` key is
``(policy, setting, episode)``; episode ``k`` of a setting is a pure function of
``(setting, seed, k)``, the same for every policy (common random numbers), so policies are
compared on the same people.
"""

from __future__ import annotations

import difflib
import re
from typing import Annotated, Any, ClassVar, Literal

from pydantic import Field, field_validator

from mawdo.experiments.plans import PlanError, StudyPlanBase
from mawdo.experiments.protocol import Task, missing_run_tasks
from mawdo.streams import name_word, seed_word

CROWD_SCHEMA = 1
SCENES = ("circle", "square")
_SETTING = re.compile(r"^(circle|square)-(\d+)-(visible|invisible)$")


def parse_setting(name: str) -> tuple[str, int, bool]:
    """``(scene, people, visible)`` of a setting name; ``ValueError`` naming the form."""
    m = _SETTING.match(str(name).strip().lower())
    if m is None or not 0 <= int(m.group(2)) <= 50:
        raise ValueError(
            f"unknown crowd setting {name!r}: write <scene>-<people>-<visibility> with scene "
            f"circle or square, 0-50 people, visible or invisible (e.g. circle-5-invisible)"
        )
    return m.group(1), int(m.group(2)), m.group(3) == "visible"


def _check_policy(name: str) -> str:
    from mawdo.planning.run.policies import POLICIES

    return POLICIES[str(name).strip()].name


class CrowdPlan(StudyPlanBase):
    """Crowd navigation: ``n`` episodes per setting, each run by every policy.

    Parameters
    ----------
    name : str
        Label for reports.
    settings : sequence of str
        Scene settings (:func:`parse_setting`).
    n : int
        Episodes per setting, >= 1.
    policies : sequence of str
        Registered policies (:data:`~mawdo.planning.run.policies.POLICIES`).
    seed : int
        Master seed (people and policy seeds), >= 0.
    planner : {"realtime", "quick", "fast"}
        Preset of our planner's policies.
    overrides : dict
        Fields of :class:`~mawdo.planning.run.config.PlannerConfig` to change.
    sensor_noise : float
        Gaussian s.d. of the sensed positions (metres, >= 0).
    sensor_range : float or None
        How far the sensor sees (metres, > 0); None: unlimited.
    miss_rate : float
        Probability that a person in view is not detected, in [0, 1).
    predictor : str
        Predictor of the observed planners (``constant_velocity``, ``stop``).
    strays : bool
        The observing policies' trackers pair the tracks and detections their first assignment
        left over (:class:`~mawdo.planning.sense.tracker.Tracker`'s ``strays``). Off by
        default; a plan that leaves it off keeps the hash it had before the field existed.
    batch_size : int
        Episodes per task.
    """

    study_kind: ClassVar[str] = "crowd"
    kind: Literal["crowd"] = "crowd"
    name: str = "crowd"
    settings: Annotated[tuple[str, ...], Field(min_length=1)]
    n: Annotated[int, Field(ge=1)] = 100
    policies: Annotated[tuple[str, ...], Field(min_length=1)] = ("mawdo", "orca_robot")
    seed: Annotated[int, Field(strict=True, ge=0)] = 0
    planner: Literal["realtime", "quick", "fast"] = "realtime"
    overrides: dict[str, Any] = Field(default_factory=dict)
    sensor_noise: Annotated[float, Field(ge=0, le=10)] = 0.0
    sensor_range: Annotated[float, Field(gt=0)] | None = None
    miss_rate: Annotated[float, Field(ge=0, lt=1)] = 0.0
    predictor: str = "constant_velocity"
    strays: Annotated[bool, Field(strict=True)] = False
    batch_size: Annotated[int, Field(ge=1)] = 10

    @field_validator("settings")
    @classmethod
    def _settings(cls, names):
        out = []
        for i, n in enumerate(names):
            try:
                scene, people, visible = parse_setting(n)
            except ValueError as exc:
                raise ValueError(f"settings[{i}]: {exc}") from None
            key = f"{scene}-{people}-{'visible' if visible else 'invisible'}"
            if key in out:
                raise ValueError(f"settings[{i}]: {key!r} is listed twice")
            out.append(key)
        return tuple(out)

    @field_validator("policies")
    @classmethod
    def _policies(cls, names):
        out = []
        for i, n in enumerate(names):
            try:
                c = _check_policy(n)
            except KeyError as exc:
                raise ValueError(f"policies[{i}]: {exc}") from None
            if c in out:
                raise ValueError(f"policies[{i}]: {c!r} is listed twice")
            out.append(c)
        return tuple(out)

    def numbers_spec(self) -> dict[str, Any]:
        spec = {**super().numbers_spec(), "schema": CROWD_SCHEMA}
        if not spec["strays"]:  # the field came later: plans without it keep their hash
            del spec["strays"]
        return spec

    def episode_seed(self, setting: str, k: int) -> int:
        """Seed of episode ``k`` of ``setting``: the people and every policy's draws."""
        return seed_word([self.seed, name_word(setting), k])

    @property
    def total_runs(self) -> int:
        return len(self.policies) * len(self.settings) * self.n

    def tasks(self, done=()) -> list[Task]:
        done = set(done)
        out = []
        for s in self.settings:
            for p in self.policies:
                out += missing_run_tasks(p, s, self.n, done, self.batch_size)
        return out

    def task_spec(self, task: Task) -> dict[str, Any]:
        return {
            "kind": self.kind,
            **task.key(),
            "seeds": [self.episode_seed(task.problem, k) for k in task.runs],
            "preset": self.planner,
            "overrides": dict(self.overrides),
            "sensor": {
                "noise": self.sensor_noise,
                "range": self.sensor_range,
                "miss_rate": self.miss_rate,
            },  # fmt: skip
            "predictor": self.predictor,
            "strays": self.strays,
        }

    def describe(self) -> str:
        return (
            f"{self.name}: {len(self.settings)} setting{'s' * (len(self.settings) > 1)} "
            f"({', '.join(self.settings)}) x "
            f"{self.n} episodes x {len(self.policies)} policies ({', '.join(self.policies)}), "
            f"sensor noise {self.sensor_noise} m, seed {self.seed}"
            + (", trackers pairing strays" if self.strays else "")
        )


_SETTINGS_ALL = [f"{s}-{n}-{v}" for s in SCENES for n in (5, 10, 20)
                 for v in ("invisible", "visible")]  # fmt: skip

# ours observing, ours without the optimizer, ours told the future, then the baselines
_POLICIES_ALL = ("mawdo", "guide_only", "mawdo_oracle", "orca_robot", "social_force_robot",
                 "dwa", "straight")  # fmt: skip

CROWD_PRESETS: dict[str, dict[str, Any]] = {
    # CrowdNav's benchmark: circle and square crossing, 5/10/20 people, robot unseen or seen
    "crowdnav": {
        "name": "crowdnav",
        "settings": _SETTINGS_ALL,
        "n": 500,
        "policies": list(_POLICIES_ALL),
    },
    # the headline setting in full: circle crossing, 5 people who do not see the robot
    "crowdnav-circle5": {
        "name": "crowdnav-circle5",
        "settings": ["circle-5-invisible"],
        "n": 500,
        "policies": list(_POLICIES_ALL),
        "batch_size": 25,
    },
    # 10 people in every scene, robot unseen and seen, in full: where the crowd gets dense
    "crowdnav-10": {
        "name": "crowdnav-10",
        "settings": [f"{s}-10-{v}" for s in SCENES for v in ("invisible", "visible")],
        "n": 500,
        # and ours in its step-by-step loop told the future: the loop's cost apart from the guess
        "policies": [*_POLICIES_ALL[:3], "mawdo_told", *_POLICIES_ALL[3:]],
        "batch_size": 25,
    },
    # a noisy sensor (0.05 m per axis): the observing planner with and without its optimizer
    "crowdnav-noise": {
        "name": "crowdnav-noise",
        "settings": ["circle-5-invisible", "circle-10-invisible"],
        "n": 200,
        "policies": ["mawdo", "guide_only"],
        "sensor_noise": 0.05,
        "strays": True,  # as Tracker.for_sensor builds a tracker for an imperfect sensor
        "batch_size": 25,
    },
    # every setting, 50 episodes each
    "crowdnav-50": {
        "name": "crowdnav-50",
        "settings": _SETTINGS_ALL,
        "n": 50,
        "policies": list(_POLICIES_ALL),
        "batch_size": 25,
    },
    # which swarm refines best: MAWDO and the other swarms in its place against guide_only
    "crowdnav-refiners": {
        "name": "crowdnav-refiners",
        "settings": ["circle-5-invisible", "circle-10-invisible"],
        "n": 100,
        "policies": ["mawdo", "woa", "gwo", "wdo_plus", "guide_only"],
        "batch_size": 25,
    },
    # the headline setting only, fewer episodes: minutes, not hours
    "crowdnav-quick": {
        "name": "crowdnav-quick",
        "settings": ["circle-5-invisible"],
        "n": 20,
        "policies": ["mawdo", "orca_robot", "straight"],
        "batch_size": 5,
    },
}


def crowd_preset(name: str) -> CrowdPlan:
    """The named crowd preset; an unknown name raises :class:`PlanError` listing them."""
    if name not in CROWD_PRESETS:
        close = difflib.get_close_matches(name, list(CROWD_PRESETS), n=2)
        hint = f" Did you mean {', '.join(map(repr, close))}?" if close else ""
        raise PlanError(f"preset: unknown crowd preset {name!r}.{hint} "
                        f"Presets: {', '.join(CROWD_PRESETS)}")  # fmt: skip
    return CrowdPlan.from_dict(CROWD_PRESETS[name])
