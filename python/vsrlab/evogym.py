"""EvoGym's robot helpers under the names EvoGym scripts call (``evogym.utils``), so that a script
written for EvoGym can sample and check robots after changing its imports; its tasks are the
Gymnasium ids ``vsrlab-evogym/<id>`` (``vsrlab.evogym_tasks()``). What EvoGym offers and vsrlab
does not yet (``EvoWorld``, ``EvoSim``, ``EvoViewer``) raises an error that says so.

The rules are EvoGym's (``evogym/utils.py``): material codes 0 empty, 1 rigid, 2 soft, 3
horizontal and 4 vertical actuator; a robot is valid when its cells are one 4-connected piece
with an actuator; ``sample_robot`` draws each cell from ``pd`` with Python's global ``random``
(as EvoGym does: seed it with ``random.seed`` for repeatable draws) until the robot is valid.
"""

from __future__ import annotations

import random
from typing import Optional, Sequence, Tuple

import numpy as np

__all__ = [
    "EvoSim",
    "EvoViewer",
    "EvoWorld",
    "get_full_connectivity",
    "has_actuator",
    "is_connected",
    "sample_robot",
]

#: EvoGym's default relative probabilities of (empty, rigid, soft, horizontal, vertical).
DEFAULT_PD = (0.6, 0.2, 0.2, 0.2, 0.2)


def _grid(robot, name: str = "robot") -> np.ndarray:
    grid = np.asarray(robot)
    if grid.ndim != 2:
        raise ValueError(f"{name}: a 2-D array of material codes expected, got shape {grid.shape}")
    return grid


def is_connected(robot) -> bool:
    """Whether the robot's non-empty cells form one piece through their four neighbours (and
    there is at least one)."""
    grid = _grid(robot)
    cells = {(i, j) for i, j in zip(*np.nonzero(grid))}
    if not cells:
        return False
    stack, seen = [min(cells)], set()
    while stack:
        i, j = stack.pop()
        if (i, j) in seen:
            continue
        seen.add((i, j))
        for n in ((i + 1, j), (i - 1, j), (i, j + 1), (i, j - 1)):
            if n in cells and n not in seen:
                stack.append(n)
    return seen == cells


def has_actuator(robot) -> bool:
    """Whether the robot has a horizontal (3) or vertical (4) actuator."""
    grid = _grid(robot)
    return bool(np.isin(grid, (3, 4)).any())


def get_full_connectivity(robot) -> np.ndarray:
    """The ``(2, k)`` array of every pair of adjacent non-empty cells, each cell by its index in
    the flattened grid (rows top first), the right neighbour before the one below, cells in
    order: EvoGym's connections for a fully connected robot."""
    grid = _grid(robot)
    height, width = grid.shape
    pairs = []
    for i in range(grid.size):
        y, x = divmod(i, width)
        if grid[y, x] == 0:
            continue
        if x + 1 < width and grid[y, x + 1] != 0:
            pairs.append((i, i + 1))
        if y + 1 < height and grid[y + 1, x] != 0:
            pairs.append((i, i + width))
    return np.array(pairs, dtype=np.int64).reshape(-1, 2).T


def _draw(weights: np.ndarray) -> int:
    """An index drawn with the relative `weights`, from one ``random.uniform(0, 1)`` as EvoGym's
    ``draw``."""
    r = random.uniform(0, 1)
    total = 0.0
    for k, p in enumerate(weights / weights.sum()):
        total += p
        if r <= total:
            return k
    return len(weights) - 1


def sample_robot(robot_shape: Tuple[int, int], pd: Optional[Sequence[float]] = None) -> Tuple[np.ndarray, np.ndarray]:
    """A random valid robot of ``robot_shape`` ``(height, width)`` and its full connectivity:
    each cell drawn from ``pd`` (relative probabilities of empty, rigid, soft, horizontal and
    vertical actuator; default EvoGym's 0.6 empty, 0.2 each other) until the robot is one piece
    with an actuator."""
    if len(robot_shape) != 2 or min(robot_shape) < 1:
        raise ValueError(f"robot_shape: (height, width) of at least one cell each expected, got {robot_shape}")
    weights = np.asarray(DEFAULT_PD if pd is None else pd, dtype=np.float64)
    if weights.shape != (5,) or not np.all(np.isfinite(weights)) or (weights < 0).any():
        raise ValueError(f"pd: five non-negative relative probabilities expected, got {pd}")
    if weights[3] + weights[4] == 0:
        raise ValueError(f"pd: an actuator (codes 3, 4) must have a non-zero probability, got {pd}")
    if weights[1:].sum() == 0:
        raise ValueError(f"pd: a non-empty cell must have a non-zero probability, got {pd}")
    while True:
        robot = np.array([[_draw(weights) for _ in range(robot_shape[1])] for _ in range(robot_shape[0])], dtype=float)
        if is_connected(robot) and has_actuator(robot):
            return robot, get_full_connectivity(robot)


class _NotOffered:
    """EvoGym API that vsrlab does not offer yet: constructing it says so."""

    _what = ""

    def __init__(self, *args, **kwargs):
        raise NotImplementedError(
            f"vsrlab.evogym does not offer {self._what} yet: EvoGym's tasks run as "
            "gymnasium.make('vsrlab-evogym/<id>', body=...) (vsrlab.evogym_tasks() lists them), "
            "robots are sampled and checked with sample_robot, is_connected and has_actuator"
        )


class EvoWorld(_NotOffered):
    """EvoGym's world builder: not offered yet."""

    _what = "EvoWorld (building worlds by hand)"


class EvoSim(_NotOffered):
    """EvoGym's simulator object: not offered yet."""

    _what = "EvoSim (stepping a world by hand)"


class EvoViewer(_NotOffered):
    """EvoGym's OpenGL viewer: not offered (vsrlab renders with `vsrlab simulate --video`)."""

    _what = "EvoViewer (the OpenGL viewer)"
