"""People who walk by ORCA (optimal reciprocal collision avoidance, van den Berg et al. 2011)
through ``pyrvo``, the Python binding of the RVO2 library, set up as CrowdNav's ORCA humans.

All people share one simulator stepped with time step 1 (our time step); every parameter is in
pixels and time steps. ORCA commutes with a change of units (lengths times ``1/res``, times
times ``1/dt``): the velocities it picks scale the same way (tested against a simulator run in
metres and seconds). CrowdNav gives each human a simulator of its own in which the others have a
zero preferred velocity; a human's new velocity depends only on its own preferred velocity and
the others' positions, velocities and radii, so one shared simulator picks the same velocities
(tested against a port of CrowdNav's per-human simulators; docs/deviations.md#d-orca-people).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from mawdo.planning.people.base import People

__all__ = ["OrcaParams", "OrcaPeople", "OrcaSim", "require_pyrvo"]


def require_pyrvo():
    """Import ``pyrvo`` or raise an ``ImportError`` that says how to install it."""
    try:
        import pyrvo
    except ImportError as exc:
        raise ImportError(
            "ORCA people and the ORCA robot need the RVO2 binding pyrvo: pip install 'mawdo[crowd]'"
        ) from exc
    return pyrvo


@dataclass(frozen=True)
class OrcaParams:
    """ORCA parameters in pixels and time steps (RVO2's names).

    Parameters
    ----------
    neighbor_dist : float
        Centre distance within which others are considered (pixels), > 0.
    max_neighbors : int
        Most others considered, >= 1.
    time_horizon : float
        Time steps for which velocities are safe from other agents, > 0.
    time_horizon_obst : float
        Time steps for which velocities are safe from walls, > 0.
    safety : float
        Added to every agent's radius inside the simulator (pixels), >= 0.
    """

    neighbor_dist: float
    max_neighbors: int
    time_horizon: float
    time_horizon_obst: float
    safety: float

    def __post_init__(self) -> None:
        for name in ("neighbor_dist", "time_horizon", "time_horizon_obst"):
            v = getattr(self, name)
            if not (np.isfinite(v) and v > 0):
                raise ValueError(f"OrcaParams.{name}={v!r} must be > 0")
        if not (isinstance(self.max_neighbors, int | np.integer) and self.max_neighbors >= 1):
            raise ValueError(f"OrcaParams.max_neighbors={self.max_neighbors!r} must be >= 1")
        if not (np.isfinite(self.safety) and self.safety >= 0):
            raise ValueError(f"OrcaParams.safety={self.safety!r} must be >= 0 pixels")

    @classmethod
    def from_metres(
        cls,
        res: float,
        dt: float,
        *,
        neighbor_dist: float = 10.0,
        max_neighbors: int = 10,
        time_horizon: float = 5.0,
        time_horizon_obst: float = 5.0,
        safety: float = 0.01,
    ) -> OrcaParams:
        """Convert metre/second parameters (defaults: CrowdNav's ORCA humans) at resolution
        ``res`` (metres per pixel, > 0) and time step ``dt`` (seconds, > 0)."""
        if not (res > 0 and dt > 0):
            raise ValueError(f"res={res!r} m/px and dt={dt!r} s must be > 0")
        return cls(
            neighbor_dist / res,
            int(max_neighbors),
            time_horizon / dt,
            time_horizon_obst / dt,
            safety / res,
        )


def _counter_clockwise(poly: np.ndarray) -> np.ndarray:
    x, y = poly[:, 0], poly[:, 1]
    area2 = np.dot(x, np.roll(y, -1)) - np.dot(np.roll(x, -1), y)
    return poly if area2 > 0 else poly[::-1]


class OrcaSim:
    """One RVO2 simulator (time step 1) with static walls, solving one ORCA step for a varying
    set of agents.

    RVO2 cannot remove agents (and ``clear_agents`` leaves its k-d tree pointing at freed
    agents), so the simulator keeps every agent it ever had and parks the unused ones beyond
    ``neighbor_dist`` of everything, where nobody considers them.

    Parameters
    ----------
    params : OrcaParams
    polygons : sequence of numpy.ndarray
        Static walls, each ``(k, 2)`` pixels, either orientation (RVO2 wants them
        counter-clockwise; they are reoriented).
    """

    def __init__(self, params: OrcaParams, polygons=()) -> None:
        pyrvo = require_pyrvo()
        self.params = params
        self.sim = pyrvo.RVOSimulator()
        self.sim.set_time_step(1.0)
        polys = [np.asarray(p, dtype=float) for p in polygons]
        for p in polys:
            self.sim.add_obstacle([tuple(v) for v in _counter_clockwise(p)])
        if polys:
            self.sim.process_obstacles()
        self._far = max((float(np.abs(p).max()) for p in polys), default=0.0)
        self._radius = np.zeros(0)
        self._speed = np.zeros(0)

    def solve(self, positions, velocities, radii, max_speeds, preferred) -> np.ndarray:
        """One ORCA step: every agent's new velocity.

        Parameters
        ----------
        positions, velocities, preferred : numpy.ndarray, shape (k, 2)
            Pixels and pixels per time step.
        radii, max_speeds : numpy.ndarray, shape (k,)
            Pixels (``params.safety`` is added) and pixels per time step.

        Returns
        -------
        numpy.ndarray, shape (k, 2)
            New velocities (pixels per time step), RVO2's single precision.
        """
        sim, p = self.sim, self.params
        k = len(positions)
        radii = np.asarray(radii, float) + p.safety
        while sim.get_num_agents() < k:
            sim.add_agent(
                (0.0, 0.0),
                p.neighbor_dist,
                int(p.max_neighbors),
                p.time_horizon,
                p.time_horizon_obst,
                1.0,
                0.0,
                (0.0, 0.0),
            )
            self._radius = np.append(self._radius, 1.0)
            self._speed = np.append(self._speed, 0.0)
        for i in np.flatnonzero(self._radius[:k] != radii):
            sim.set_agent_radius(int(i), float(radii[i]))
        for i in np.flatnonzero(self._speed[:k] != max_speeds):
            sim.set_agent_max_speed(int(i), float(max_speeds[i]))
        self._radius[:k] = radii
        self._speed[:k] = max_speeds
        for i in range(k):
            sim.set_agent_position(i, positions[i].tolist())
            sim.set_agent_velocity(i, velocities[i].tolist())
            sim.set_agent_pref_velocity(i, preferred[i].tolist())
        self._park(k, positions)
        sim.do_step()
        out = np.empty((k, 2))
        for i in range(k):
            v = sim.get_agent_velocity(i)
            out[i] = v.x, v.y
        return out

    def _park(self, k: int, positions) -> None:
        n = self.sim.get_num_agents()
        if n == k:
            return
        # beyond neighbor_dist of every agent and wall, and of each other
        spacing = self.params.neighbor_dist + 2.0 * float(self._radius.max()) + 1.0
        x0 = max(self._far, float(np.abs(positions).max(initial=0.0))) + spacing
        for j in range(k, n):
            self.sim.set_agent_position(j, (x0 + (j - k) * spacing, 0.0))
            self.sim.set_agent_velocity(j, (0.0, 0.0))
            self.sim.set_agent_pref_velocity(j, (0.0, 0.0))


def cap_speed(velocities: np.ndarray, max_speeds) -> np.ndarray:
    """Scale down velocities (k, 2) longer than ``max_speeds`` (k,) (pixels per time step)."""
    norm = np.hypot(velocities[:, 0], velocities[:, 1])
    scale = np.minimum(1.0, np.asarray(max_speeds, float) / np.where(norm > 0, norm, 1.0))
    return velocities * scale[:, None]


class OrcaPeople(People):
    """People who walk by ORCA as CrowdNav's humans do.

    Each step, each person's preferred velocity points to its goal (see
    :func:`~mawdo.planning.people.base.preferred_velocities`), its maximum speed is its preferred
    speed, every radius is enlarged by ``params.safety``, and a visible robot is one more agent
    whose position and velocity are overwritten with the robot's (it does not yield). Then the
    guard keeps everyone out of the walls and inside the map.

    Parameters
    ----------
    positions, goals, radii, preferred_speed, bounds, obstacles, goal_policy, rng, arrival_time,
    velocities
        See :class:`~mawdo.planning.people.base.People`.
    params : OrcaParams
        ORCA parameters in pixels and time steps (e.g. ``OrcaParams.from_metres(res, dt)``).
    """

    def __init__(self, positions, goals, radii, preferred_speed, *, params: OrcaParams, **kw):
        super().__init__(positions, goals, radii, preferred_speed, **kw)
        if not isinstance(params, OrcaParams):
            raise ValueError("params must be an OrcaParams (e.g. OrcaParams.from_metres(res, dt))")
        self.params = params
        self._orca = OrcaSim(params, self.walls.polygons)

    def _advance(self, robot_position, robot_velocity, robot_radius, visible) -> np.ndarray:
        n = len(self)
        pos, vel, radii, speed = self._pos, self._vel, self.radii, self.preferred_speed
        pref = self.preferred()
        if visible:
            pos = np.vstack([pos, robot_position])
            vel = np.vstack([vel, robot_velocity])
            radii = np.append(radii, robot_radius)
            speed = np.append(speed, np.hypot(*robot_velocity))
            pref = np.vstack([pref, np.zeros(2)])
        v = self._orca.solve(pos, vel, radii, speed, pref)[:n]
        v = cap_speed(v, self.preferred_speed)
        return self.walls.guard(self._pos, v, self.radii)
