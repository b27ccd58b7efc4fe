"""The observing planner told the future: what prediction costs, measured apart from the loop.

An observing :class:`~mawdo.planning.run.policy.PlannerPolicy` differs from the planner told
every agent's future (``knowledge="oracle"``, planned once and replayed) in two ways: it guesses
the future from tracks (a predictor with an uncertainty margin), and it decides one step at a
time from where it stands (a fresh search each step, a first step spent watching). A
:class:`ToldFuturePolicy` keeps the second and removes the first: it is the observing planner,
step by step, whose predictor is the ``oracle`` one, fed the agents' true future. Beside the
two, it splits their gap into the cost of the loop (told-in-the-loop against told-once) and the
cost of the guess (observed against told-in-the-loop).

The true future comes with the scenario the policy is reset with: the world's scenario plus
every agent's future as a scripted mover, as the crowd study hands it to every policy registered
with ``oracle`` knowledge (exact when the people do not see the robot; see
:func:`~mawdo.planning.world.stepped.people_future`). Each step the tracks are matched to those
movers; a track with no mover under it at the first decision means the policy was not told the
future (reset with the world's own scenario), and the step raises rather than plan around nobody.
"""

from __future__ import annotations

import numpy as np

from mawdo.planning.run.policy import PlannerPolicy
from mawdo.planning.sense.predict import match_agents, oracle

__all__ = ["ToldFuturePolicy"]


class ToldFuturePolicy(PlannerPolicy):
    """The observing planner with its predictor told the true future.

    Parameters
    ----------
    algorithm : str
        Optimizer name or ``guide_only``, as :class:`PlannerPolicy`.
    config : str or PlannerConfig, optional
        Planner preset or settings.
    tracker : Tracker, optional
        The tracker whose tracks are matched to the told movers (default: noise-free).
    horizon : int
        Prediction horizon (time steps), >= 1.
    look_first : int
        Steps to stand and watch first (default 0: a told future needs no second reading).
    **overrides
        Fields of :class:`~mawdo.planning.run.config.PlannerConfig`.
    """

    def __init__(self, algorithm: str = "mawdo", config=None, tracker=None, horizon: int = 200,
                 look_first: int = 0, **overrides):  # fmt: skip
        super().__init__(algorithm, config, "observed", tracker=tracker, horizon=horizon,
                         look_first=look_first, **overrides)  # fmt: skip
        self.predictor, self.predict = "oracle", self._told
        self.name = f"{algorithm}-told"

    def reset(self, scenario, seed) -> None:
        """Start an episode told ``scenario``: its moving circles are the agents' futures."""
        super().reset(scenario, seed)
        movers = [scenario.obstacles[i] for i in scenario.moving_indices]
        movers = [o for o in movers if o.is_circle]
        self._centres = np.array([o.shape.center for o in movers], dtype=float).reshape(-1, 2)
        self._movers, self._now = movers, 0.0

    def prediction(self, reading):
        self._now = float(reading.step)  # the predictor's times run from 0 = this step
        return super().prediction(reading)

    def truth(self, times) -> np.ndarray:
        """The told movers' centres (pixels), shape ``(len(times), n_movers, 2)``, at
        absolute ``times`` (time steps)."""
        t = np.asarray(times, dtype=float).reshape(-1)
        out = np.empty((len(t), len(self._movers), 2))
        for j, o in enumerate(self._movers):
            out[:, j] = self._centres[j] + o.offset(t)
        return out

    def _told(self, tracks, now, horizon, bounds, **options):
        def ahead(times):
            return self.truth(np.asarray(times, dtype=float) + self._now)

        truth = ahead([now])[0]
        agents = match_agents(tracks, truth)
        if len(tracks) and self.last is None:
            # told at all? Checked at the first decision only: people who see the robot leave
            # the future recorded without it (then it is an estimate, as for mawdo_oracle), and
            # a track left over later is a ghost (the tracker coasting a track whose agent
            # turned sharply, beside the new track it started for it) that the oracle drops
            gap = np.hypot(*(tracks.centers - truth[np.maximum(agents, 0)]).T) if len(truth) else 0
            far = np.flatnonzero((agents < 0) | (gap > tracks.radii))
            if len(far):
                raise ValueError(
                    f"{self.name}: the track at {tracks.centers[far[0]].round(2).tolist()} px "
                    f"has no told mover within its radius at step {self._now:g}; reset the "
                    "policy with the scenario that holds every agent's future (the crowd "
                    "study does so for policies of 'oracle' knowledge)"
                )
        return oracle(tracks, now, horizon, bounds, truth=ahead, agents=agents, **options)
