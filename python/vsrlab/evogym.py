"""EvoGym's Python API under the names EvoGym scripts call, so that a script written for EvoGym
runs after changing its imports (``from vsrlab.evogym import EvoWorld, EvoSim, EvoViewer,
sample_robot``): its robot helpers (``evogym.utils``), its worlds (``EvoWorld``, ``WorldObject``,
read from EvoGym's world files), its simulator (``EvoSim``, on vsrlab's engine) and a viewer that
draws images without OpenGL (``EvoViewer.render("img")``); its tasks are the Gymnasium ids
``vsrlab-evogym/<id>`` (``vsrlab.evogym_tasks()``, ``BASELINE_ENV_NAMES``). What vsrlab does not
offer raises an error that says so: EvoGym's OpenGL windows (``render("screen")``) and the
simulator's snapshots of earlier times (``*_at_time`` answers for the current time only).

The rules are EvoGym's (``evogym/utils.py``): material codes 0 empty, 1 rigid, 2 soft, 3
horizontal and 4 vertical actuator; a robot is valid when its cells are one 4-connected piece
with an actuator; ``sample_robot`` draws each cell from ``pd`` with Python's global ``random``
(as EvoGym does: seed it with ``random.seed`` for repeatable draws) until the robot is valid.
"""

from __future__ import annotations

import random
import json
from dataclasses import dataclass
from typing import Dict, List, Optional, Sequence, Tuple

import numpy as np

from vsrlab._native import EvoGymSim, evogym_check_world, evogym_tasks

#: EvoGym's registered task ids (every one is a Gymnasium id under ``vsrlab-evogym/``).
BASELINE_ENV_NAMES = list(evogym_tasks())

__all__ = [
    "BASELINE_ENV_NAMES",
    "EvoSim",
    "EvoViewer",
    "EvoWorld",
    "Pair",
    "VOXEL_TYPES",
    "WorldObject",
    "draw",
    "get_full_connectivity",
    "get_uniform",
    "has_actuator",
    "is_connected",
    "sample_robot",
]

#: EvoGym's material codes.
VOXEL_TYPES = {"EMPTY": 0, "RIGID": 1, "SOFT": 2, "H_ACT": 3, "V_ACT": 4, "FIXED": 5}

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


def get_uniform(x: int) -> np.ndarray:
    """The uniform distribution over ``x`` elements (``x`` positive)."""
    if int(x) <= 0:
        raise ValueError(f"x: a positive size expected, got {x}")
    return np.ones(int(x)) / int(x)


def draw(pd) -> int:
    """An index drawn with the relative probabilities ``pd`` (non-negative, not all 0), from one
    ``random.uniform(0, 1)`` as EvoGym's ``draw``."""
    weights = np.array(pd, dtype=np.float64).reshape(-1)
    if weights.size == 0 or not np.all(np.isfinite(weights)) or (weights < 0).any() or weights.sum() <= 0:
        raise ValueError(f"pd: non-negative relative probabilities, not all 0, expected, got {pd}")
    return _draw(weights)


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




@dataclass
class Pair:
    """Two integers, a cell's (x, y) or a size, as EvoGym's ``Pair``."""

    x: int
    y: int

    def __add__(self, other: "Pair") -> "Pair":
        return Pair(self.x + other.x, self.y + other.y)

    def __sub__(self, other: "Pair") -> "Pair":
        return Pair(self.x - other.x, self.y - other.y)

    def __hash__(self) -> int:
        return hash((self.x, self.y))

    def copy(self) -> "Pair":
        return Pair(self.x, self.y)


class WorldObject:
    """One object of a world: its cells (``grid``, bottom row first, as EvoGym keeps it), its
    connections (``neighbors``: cell → connected cells) and the position of its bottom-left
    cell (``pos``)."""

    def __init__(self) -> None:
        self.name = ""
        self.pos = Pair(0, 0)
        self.grid_size = Pair(0, 0)
        self.voxels: List[Pair] = []
        self.grid = np.zeros((0, 0), dtype=int)
        self.neighbors: Dict[Pair, List[Pair]] = {}

    @classmethod
    def from_json(cls, file_path: str) -> "WorldObject":
        """The one object of a world file; a ``ValueError`` if it holds another number."""
        world = EvoWorld.from_json(file_path)
        if len(world.objects) != 1:
            raise ValueError(f"{file_path}: objects: {len(world.objects)} objects, a single object's file holds one")
        return next(iter(world.objects.values()))

    def load_from_json(self, file_path: str) -> None:
        """Becomes the one object of a world file."""
        self.__dict__.update(WorldObject.from_json(file_path).__dict__)

    @classmethod
    def from_array(cls, name: str, structure, connections=None) -> "WorldObject":
        """An object from its material codes (rows top first) and its ``(2, k)`` connections
        (cells by their index in the flattened structure; default: every pair of neighbours)."""
        out = cls()
        out.load_from_array(name, structure, connections)
        return out

    def load_from_array(self, name: str, structure, connections=None) -> None:
        """Becomes the object of ``structure`` and ``connections`` (as :meth:`from_array`)."""
        structure = _grid(structure, "structure").astype(int)
        if not np.isin(structure, list(VOXEL_TYPES.values())).all():
            raise ValueError(f"structure: material codes 0-5 expected, got {sorted(set(structure.flat))}")
        pairs = get_full_connectivity(structure) if connections is None else np.asarray(connections)
        if pairs.size and (pairs.ndim != 2 or pairs.shape[0] != 2):
            raise ValueError(f"connections: a (2, k) array of cell indices expected, got shape {pairs.shape}")
        height, width = structure.shape
        self.name = str(name)
        self.grid = np.flipud(structure).copy()
        self.grid_size = Pair(width, height)
        self.pos = Pair(0, 0)
        self.voxels = [Pair(x, y) for y in range(height) for x in range(width) if self.grid[y, x] != 0]
        self.neighbors = {v: [] for v in self.voxels}
        for a, b in pairs.reshape(2, -1).T:
            ends = []
            for i in (int(a), int(b)):
                if not 0 <= i < structure.size or structure.flat[i] == 0:
                    raise ValueError(f"connections: {i} is not a cell of the structure")
                ends.append(Pair(i % width, height - 1 - i // width))
            self.neighbors[ends[0]].append(ends[1])
            self.neighbors[ends[1]].append(ends[0])

    def _load_from_parsed_json(self, name: str, data: dict, grid_width: int) -> None:
        """Becomes object ``name`` of a checked world file (``evogym_check_world``)."""
        cells = [Pair(i % grid_width, i // grid_width) for i in data["indices"]]
        low = Pair(min(c.x for c in cells), min(c.y for c in cells))
        high = Pair(max(c.x for c in cells), max(c.y for c in cells))
        self.name, self.pos = name, low
        self.grid_size = high - low + Pair(1, 1)
        self.grid = np.zeros((self.grid_size.y, self.grid_size.x), dtype=int)
        local = {i: c - low for i, c in zip(data["indices"], cells)}
        for i, t in zip(data["indices"], data["types"]):
            self.grid[local[i].y, local[i].x] = int(t)
        self.voxels = list(local.values())
        self.neighbors = {local[i]: [local[n] for n in data["neighbors"][str(i)]] for i in data["indices"]}

    def translate(self, dx: int, dy: int) -> None:
        """Moves the object by (dx, dy) cells."""
        self.set_pos(self.pos.x + dx, self.pos.y + dy)

    def set_pos(self, x: int, y: int) -> None:
        """Places the object's bottom-left cell at (x, y) (non-negative)."""
        if x < 0 or y < 0:
            raise ValueError(f"pos: ({x}, {y}) for object {self.name}: positions are non-negative")
        self.pos = Pair(int(x), int(y))

    def get_structure(self) -> np.ndarray:
        """The material codes, rows top first."""
        return np.flipud(self.grid).copy()

    def get_connections(self) -> np.ndarray:
        """The ``(2, k)`` connections, cells by their index in the flattened structure, each
        pair once."""
        height, width = self.grid.shape
        index = lambda c: (height - 1 - c.y) * width + c.x  # noqa: E731
        pairs = sorted({tuple(sorted((index(a), index(b)))) for a, ns in self.neighbors.items() for b in ns})
        return np.array(pairs, dtype=np.int64).reshape(-1, 2).T

    def get_pos(self) -> Tuple[int, int]:
        """The bottom-left cell's position."""
        return self.pos.x, self.pos.y

    def rename(self, name: str) -> None:
        """Gives the object another name."""
        self.name = str(name)

    def get_name(self) -> str:
        """The object's name."""
        return self.name

    def copy(self) -> "WorldObject":
        """An independent copy."""
        out = WorldObject()
        out.name, out.pos, out.grid_size = self.name, self.pos.copy(), self.grid_size.copy()
        out.voxels, out.grid = list(self.voxels), self.grid.copy()
        out.neighbors = {k: list(v) for k, v in self.neighbors.items()}
        return out

    def __copy__(self) -> "WorldObject":
        return self.copy()

    def __repr__(self) -> str:
        return f"WorldObject({self.name!r} at ({self.pos.x}, {self.pos.y}), {self.grid_size.x} x {self.grid_size.y})"


class EvoWorld:
    """A world of named objects on a grid of cells (``grid``: every object's codes, bottom row
    first), read from EvoGym's world files or built object by object."""

    def __init__(self) -> None:
        self.grid = np.array([[0]])
        self.grid_size = Pair(1, 1)
        self.objects: Dict[str, WorldObject] = {}

    @classmethod
    def from_json(cls, file_path: str) -> "EvoWorld":
        """The world of an EvoGym world file (as its design tool writes them)."""
        out = cls()
        out.add_from_json(file_path)
        return out

    def add_from_json(self, file_path: str) -> None:
        """Adds a world file's objects. A file vsrlab cannot build is refused with a
        ``ValueError`` naming the file and the field (``objects.box.types[3]``)."""
        with open(file_path, "r", encoding="utf-8") as f:
            text = f.read()
        try:
            evogym_check_world(text)
        except ValueError as e:
            raise ValueError(f"{file_path}: {e}") from None
        state = json.loads(text)
        for name, data in sorted(state["objects"].items()):
            if name in self.objects:
                raise ValueError(f"{file_path}: objects.{name}: the world already has an object of that name")
            obj = WorldObject()
            obj._load_from_parsed_json(name, data, int(state["grid_width"]))
            self.add_object(obj)

    def add_from_array(self, name: str, structure, x: int, y: int, connections=None) -> None:
        """Adds an object made from an array (:meth:`WorldObject.from_array`) at (x, y)."""
        obj = WorldObject.from_array(name, structure, connections)
        obj.set_pos(x, y)
        self.add_object(obj)

    def add_object(self, obj: WorldObject) -> None:
        """Adds an object; refuses a name the world has or cells another object holds."""
        if obj.name in self.objects:
            raise ValueError(f"name: the world already has an object named {obj.name}")
        x0, y0 = obj.pos.x, obj.pos.y
        x1, y1 = x0 + obj.grid_size.x, y0 + obj.grid_size.y
        if x1 > self.grid_size.x or y1 > self.grid_size.y:
            grown = np.zeros((max(y1, self.grid_size.y), max(x1, self.grid_size.x)), dtype=int)
            grown[: self.grid.shape[0], : self.grid.shape[1]] = self.grid
            self.grid, self.grid_size = grown, Pair(grown.shape[1], grown.shape[0])
        region = self.grid[y0:y1, x0:x1]
        if np.any((region != 0) & (obj.grid != 0)):
            raise ValueError(f"{obj.name}: overlaps an object of the world at ({x0}, {y0})")
        region[obj.grid != 0] = obj.grid[obj.grid != 0]
        self.objects[obj.name] = obj

    def remove_object(self, obj_name: str) -> WorldObject:
        """Removes the object named ``obj_name`` and returns it."""
        if obj_name not in self.objects:
            raise ValueError(f"name: the world has no object named {obj_name}")
        obj = self.objects.pop(obj_name)
        x0, y0 = obj.pos.x, obj.pos.y
        region = self.grid[y0 : y0 + obj.grid_size.y, x0 : x0 + obj.grid_size.x]
        region[obj.grid != 0] = 0
        return obj

    def translate_object(self, obj_name: str, dx: int, dy: int) -> None:
        """Moves an object by (dx, dy) cells; refused (and left in place) where it would overlap."""
        obj = self.remove_object(obj_name)
        start = obj.pos.copy()
        try:
            obj.translate(dx, dy)
            self.add_object(obj)
        except ValueError:
            obj.set_pos(start.x, start.y)
            self.add_object(obj)
            raise

    def move_object(self, obj_name: str, x: int, y: int) -> None:
        """Moves an object to (x, y); refused (and left in place) where it would overlap."""
        obj = self.objects.get(obj_name)
        if obj is None:
            raise ValueError(f"name: the world has no object named {obj_name}")
        self.translate_object(obj_name, x - obj.pos.x, y - obj.pos.y)

    def pretty_print(self, voxels_per_line: int = 50) -> None:
        """Prints the world: (R)igid, (S)oft, (H)orizontal and (V)ertical actuators, (F)ixed."""
        marks = {0: ". ", 1: "R ", 2: "S ", 3: "H ", 4: "V ", 5: "F "}
        for start in range(0, self.grid_size.x, voxels_per_line):
            columns = range(start, min(self.grid_size.x, start + voxels_per_line))
            for y in reversed(range(self.grid_size.y)):
                print(f"{y % 10} | " + "".join(marks[int(self.grid[y][x])] for x in columns))
            print("   -" + "--" * len(columns))
            print("    " + "".join(f"{x % 10} " for x in columns))

    def _to_json(self) -> str:
        """The world in EvoGym's world-file format."""
        width = self.grid_size.x
        objects = {}
        for name, obj in self.objects.items():
            index = lambda c: (obj.pos.y + c.y) * width + obj.pos.x + c.x  # noqa: E731,B023
            cells = sorted(obj.voxels, key=index)
            objects[name] = {
                "indices": [index(c) for c in cells],
                "types": [int(obj.grid[c.y, c.x]) for c in cells],
                "neighbors": {str(index(c)): [index(n) for n in obj.neighbors.get(c, [])] for c in cells},
            }
        return json.dumps({"grid_width": width, "grid_height": self.grid_size.y, "objects": objects})


class EvoSim:
    """A world simulated on vsrlab's engine as EvoGym's ``EvoSim``: objects with actuators are
    robots driven by ``set_action``; ``step`` runs one step (30 substeps) and answers whether
    the simulation became unstable. Positions and velocities are in cells (EvoGym's units).
    vsrlab keeps the current state only: the ``*_at_time`` methods answer for
    ``get_time()``."""

    VOXEL_SIZE = 0.1

    def __init__(self, world: EvoWorld) -> None:
        if not isinstance(world, EvoWorld):
            raise ValueError(f"world: an EvoWorld expected, got {type(world).__name__}")
        self._sim = EvoGymSim(world._to_json())
        self._objects = {name: (robot, actuators) for name, robot, _, actuators in self._sim.objects()}
        self._actuators = {
            name: np.flatnonzero(np.isin(world.objects[name].get_structure(), (3, 4)))
            for name, (robot, _) in self._objects.items()
            if robot
        }

    def _check_valid_robot_name(self, robot_name: str) -> None:
        if robot_name not in self._actuators:
            raise ValueError(f"{robot_name} is not a valid robot name (robots: {', '.join(self._actuators)})")

    def _check_valid_object_name(self, object_name: str) -> None:
        if object_name not in self._objects:
            raise ValueError(f"{object_name} is not a valid object name (objects: {', '.join(self._objects)})")

    def _check_valid_time(self, time: int) -> None:
        if not isinstance(time, (int, np.integer)):
            raise TypeError(f"time {time} is not of type int")
        if time != self.get_time():
            raise ValueError(
                f"time {time}: vsrlab keeps only the current state (time {self.get_time()}); "
                "EvoGym's snapshots of earlier times are not offered"
            )

    def get_actuator_indices(self, robot_name: str) -> np.ndarray:
        """The robot's actuator cells, by their index in its flattened structure (rows top
        first), in the order of its actions."""
        self._check_valid_robot_name(robot_name)
        return self._actuators[robot_name].copy()

    def get_dim_action_space(self, robot_name: str) -> int:
        """The robot's number of actuators."""
        self._check_valid_robot_name(robot_name)
        return len(self._actuators[robot_name])

    def set_action(self, robot_name: str, action) -> None:
        """The robot's targets (one length ratio per actuator, clipped into [0.6, 1.6]) for the
        next steps."""
        self._check_valid_robot_name(robot_name)
        a = np.ascontiguousarray(np.asarray(action, dtype=np.float64).reshape(-1))
        if a.size != len(self._actuators[robot_name]):
            raise ValueError(
                f"expected action with {len(self._actuators[robot_name])} values but got action with {a.size} values for {robot_name}"
            )
        self._sim.set_action(robot_name, a)

    def step(self) -> bool:
        """One step; ``True`` when the simulation became unstable."""
        return self._sim.step()

    def reset(self) -> None:
        """Back to time 0, every actuator at rest."""
        self._sim.reset()

    def get_time(self) -> int:
        """Steps taken since the start."""
        return self._sim.steps

    def pos_at_time(self, time: int) -> np.ndarray:
        """Every point's position, ``(2, n)``, in cells."""
        self._check_valid_time(time)
        return self._sim.positions() / self.VOXEL_SIZE

    def vel_at_time(self, time: int) -> np.ndarray:
        """Every point's velocity, ``(2, n)``, in cells per second."""
        self._check_valid_time(time)
        return self._sim.velocities() / self.VOXEL_SIZE

    def object_pos_at_time(self, time: int, object_name: str) -> np.ndarray:
        """An object's points' positions, ``(2, n)``, in cells."""
        self._check_valid_time(time)
        self._check_valid_object_name(object_name)
        return self._sim.positions(object_name) / self.VOXEL_SIZE

    def object_vel_at_time(self, time: int, object_name: str) -> np.ndarray:
        """An object's points' velocities, ``(2, n)``, in cells per second."""
        self._check_valid_time(time)
        self._check_valid_object_name(object_name)
        return self._sim.velocities(object_name) / self.VOXEL_SIZE

    def object_orientation_at_time(self, time: int, object_name: str) -> float:
        """An object's orientation since the start (radians)."""
        self._check_valid_time(time)
        self._check_valid_object_name(object_name)
        return self._sim.orientation(object_name)


class EvoViewer:
    """Draws a simulation as images without OpenGL (``render("img")``, as vsrlab's videos: the
    view follows the first robot). EvoGym's camera settings are accepted and not used; its
    windows (``render("screen")``, ``"human"``) are not offered and say so."""

    def __init__(self, sim: EvoSim, target_rps: Optional[int] = None, pos=(12, 4), view_size=(40, 20), resolution=(1200, 600)):
        if not isinstance(sim, EvoSim):
            raise ValueError(f"sim: an EvoSim expected, got {type(sim).__name__}")
        self._sim = sim

    def render(self, mode: str = "screen", verbose: bool = False, **options) -> Optional[np.ndarray]:
        """The current state as an RGB array (height × width × 3, uint8) for ``mode`` ``"img"``
        (or ``"rgb_array"``)."""
        if mode in ("img", "rgb_array"):
            return self._sim._sim.render()
        if mode in ("screen", "human"):
            raise NotImplementedError(
                f"render({mode!r}): vsrlab has no OpenGL window; render('img') returns the frame as an array"
            )
        raise ValueError(f"mode: 'img' or 'rgb_array' expected, got {mode!r}")

    def track_objects(self, *objects) -> None:
        """Accepted: the view follows the first robot."""

    def set_pos(self, pos) -> None:
        """Accepted and not used."""

    def set_view_size(self, view_size) -> None:
        """Accepted and not used."""

    def set_resolution(self, resolution) -> None:
        """Accepted and not used."""

    def set_target_rps(self, target_rps) -> None:
        """Accepted and not used: frames are drawn when asked."""

    def show_debug_window(self) -> None:
        """Accepted: there is no window."""

    def hide_debug_window(self) -> None:
        """Accepted: there is no window."""

    def close(self) -> None:
        """Nothing to close."""
