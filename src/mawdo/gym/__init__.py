"""Gymnasium environments on mawdo's stepped world (the ``rl`` extra: ``gymnasium``).

Importing this package registers

- ``mawdo/Crowd-v0`` (:class:`~mawdo.gym.env.CrowdEnv`): CrowdNav scenes by setting name,
- ``mawdo/Scenario-v0`` (:class:`~mawdo.gym.env.ScenarioEnv`): a scenario, with its people,

and gives the adapters between learned policies and mawdo's
(:class:`~mawdo.gym.adapter.CallablePolicy`, :func:`~mawdo.gym.adapter.policy_action`,
:func:`~mawdo.gym.adapter.register_policy`). See docs/how-to/gymnasium.md.
"""

from __future__ import annotations

import gymnasium

from mawdo.gym.adapter import CallablePolicy, policy_action, register_policy
from mawdo.gym.env import CrowdEnv, MawdoEnv, ScenarioEnv
from mawdo.gym.observation import Observer

__all__ = [
    "ENV_IDS",
    "CallablePolicy",
    "CrowdEnv",
    "MawdoEnv",
    "Observer",
    "ScenarioEnv",
    "policy_action",
    "register_policy",
]

#: The registered environment ids and their classes' entry points.
ENV_IDS = {
    "mawdo/Crowd-v0": "mawdo.gym.env:CrowdEnv",
    "mawdo/Scenario-v0": "mawdo.gym.env:ScenarioEnv",
}

for _id, _entry in ENV_IDS.items():
    if _id not in gymnasium.registry:  # a reload must not register twice
        gymnasium.register(id=_id, entry_point=_entry)
