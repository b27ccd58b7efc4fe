"""Seeded families of test maps: serpentine mazes, U-traps, rooms with doors, walled-in goals,
a pocket where the only safe action is to wait, and moving obstacles crossing corridors.

Every builder takes a ``numpy.random.Generator`` (or a seed) and returns a validated
:class:`~mawdo.planning.world.scenario.Scenario`; the random choices (gap places and widths, trap
sizes, door places) keep a collision-free route for a robot of radius 4 with margin.
"""

from __future__ import annotations

import numpy as np

from mawdo.planning import scenario_from_dict

SIZE = 366.0


def _box(x0, y0, x1, y1, oid):
    return {
        "id": oid,
        "shape": "polygon",
        "vertices": [[x0, y0], [x1, y0], [x1, y1], [x0, y1]],
    }


def _rng(seed):
    return seed if isinstance(seed, np.random.Generator) else np.random.default_rng(seed)


def _scenario(name, obstacles, start, goal, seed=0):
    return scenario_from_dict(
        {
            "schema_version": 1,
            "name": name,
            "seed": int(seed),
            "width": SIZE,
            "height": SIZE,
            "start": list(map(float, start)),
            "goal": list(map(float, goal)),
            "robot": {"radius": 4.0, "speed": 4.0},
            "obstacles": obstacles,
        }
    )


def _movers(rng, walls_y, count):
    """Circles moving along the corridors between walls (horizontally, bouncing)."""
    out = []
    bands = list(zip(walls_y[:-1], walls_y[1:], strict=True))
    for i in range(count):
        lo, hi = bands[int(rng.integers(len(bands)))]
        y = 0.5 * (lo + hi) + rng.uniform(-3, 3)
        x = rng.uniform(120, 250)
        vx = rng.choice([-1, 1]) * rng.uniform(1.0, 2.5)
        out.append(
            {
                "id": f"mover-{i}",
                "shape": "circle",
                "center": [x, y],
                "radius": float(rng.uniform(6, 9)),
                "motion": {"model": "constant_velocity", "velocity": [vx, 0.0]},
            }
        )
    return out


def serpentine_maze(seed=0, moving: int = 0):
    """3-5 horizontal walls with alternating gaps; start bottom left, goal top right/left."""
    rng = _rng(seed)
    n = int(rng.integers(3, 6))
    ys = np.linspace(0, SIZE, n + 2)[1:-1] + rng.uniform(-8, 8, n)
    obs = []
    for i, y in enumerate(ys):
        gap = rng.uniform(30, 50)
        t = rng.uniform(8, 14)
        x0, x1 = (0.0, SIZE - gap) if i % 2 == 0 else (gap, SIZE)
        obs.append(_box(x0, y - t / 2, x1, y + t / 2, f"wall-{i}"))
    goal_x = 30.0 if n % 2 == 0 else SIZE - 30.0
    walls = [0.0, *ys, SIZE]
    return _scenario(
        "maze", obs + _movers(rng, walls, moving), (30.0, 20.0), (goal_x, SIZE - 20.0), 1
    )


def u_trap(seed=0, moving: int = 0):
    """A U open toward the start; the goal is behind its bottom."""
    rng = _rng(seed)
    cx, cy = rng.uniform(160, 206), rng.uniform(160, 206)
    w, h, t = rng.uniform(110, 170), rng.uniform(100, 160), rng.uniform(10, 16)
    x0, x1, y0, y1 = cx - w / 2, cx + w / 2, cy - h / 2, cy + h / 2
    # U opening toward the lower left start: walls on the right and top, joined
    u = [
        [x0, y1],
        [x1, y1],
        [x1, y0],
        [x1 - t, y0],
        [x1 - t, y1 - t],
        [x0, y1 - t],
    ]
    obs = [{"id": "u", "shape": "polygon", "vertices": u}]
    start = (x0 + rng.uniform(10, 30), y0 + rng.uniform(10, 30))
    goal = (rng.uniform(x1 + 15, SIZE - 10), rng.uniform(y1 + 15, SIZE - 10))
    if moving:
        obs += [
            {
                "id": f"mover-{i}",
                "shape": "circle",
                "center": [float(rng.uniform(30, 330)), float(rng.uniform(20, max(25, y0 - 25)))],
                "radius": 8.0,
                "motion": {"model": "constant_velocity", "velocity": [1.5, 1.0]},
            }
            for i in range(moving)
        ]
    return _scenario("u-trap", obs, start, goal, 2)


def rooms(seed=0, moving: int = 0):
    """3 x 3 rooms; every inner wall has one door (30-45 px) at a random place."""
    rng = _rng(seed)
    cuts = [122.0, 244.0]
    t = 8.0
    obs, k = [], 0
    for c in cuts:
        for horizontal in (True, False):
            edges = [0.0, *cuts, SIZE]
            for a, b in zip(edges[:-1], edges[1:], strict=True):
                door = rng.uniform(30, 45)
                d0 = rng.uniform(a + 12, b - 12 - door)
                for s0, s1 in ((a, d0), (d0 + door, b)):
                    if s1 - s0 < 1:
                        continue
                    if horizontal:
                        obs.append(_box(s0, c - t / 2, s1, c + t / 2, f"w{k}"))
                    else:
                        obs.append(_box(c - t / 2, s0, c + t / 2, s1, f"w{k}"))
                    k += 1
    walls = [0.0, *cuts, SIZE]
    return _scenario("rooms", obs + _movers(rng, walls, moving), (20.0, 20.0), (346.0, 346.0), 3)


def walled_in_goal():
    """The goal sits inside a closed ring of walls: no route exists."""
    ring = [
        _box(250, 250, 340, 258, "s"),
        _box(250, 332, 340, 340, "n"),
        _box(250, 250, 258, 340, "w"),
        _box(332, 250, 340, 340, "e"),
    ]
    return _scenario("walled-in", ring, (20.0, 20.0), (295.0, 295.0))


def waiting_pocket():
    """The robot starts at the closed end of a pocket barely wider than itself; a box blocks the
    pocket's mouth and moves away slowly. Nothing but waiting is safe at first."""
    obs = [
        _box(0, 80, 40, 94, "pocket-south"),
        _box(0, 106, 40, 120, "pocket-north"),
        {
            "id": "door",
            "shape": "polygon",
            "vertices": [[44, 70], [80, 70], [80, 130], [44, 130]],
            "motion": {"model": "constant_velocity", "velocity": [0.0, 2.0]},
        },
    ]
    return _scenario("pocket", obs, (8.0, 100.0), (340.0, 100.0))


FAMILIES = {"maze": serpentine_maze, "u-trap": u_trap, "rooms": rooms}


def around_a_block():
    """A 200 px map, one 40 px block in the middle, start and goal at opposite corners (the
    straight line passes through the block): the kinematic limits' test map."""
    return scenario_from_dict({
        "schema_version": 1, "width": 200.0, "height": 200.0, "start": [20.0, 20.0],
        "goal": [180.0, 180.0], "robot": {"radius": 4.0, "speed": 4.0},
        "obstacles": [{"shape": "polygon", "vertices": [[80, 80], [120, 80], [120, 120],
                                                         [80, 120]]}],
    })  # fmt: skip
