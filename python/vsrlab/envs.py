"""Gymnasium environments: a vsrlab robot stepped by your policy.

Observation: the robot's sensor readings (a ``Box`` of float64); action: one actuation in
[-1, 1] per actuator (voxel, or PSA spring/pressure output), applied for the next physics step;
reward: the step's Δx of the point locomotion measures (a voxel robot's mean voxel-polygon
centre); ``terminated`` when the task stops the episode (a PSA
that escaped its cage), ``truncated`` when its duration is over. ``render_mode="rgb_array"``
draws frames like the CLI's videos.

Registered ids (``gymnasium.make`` and ``gymnasium.make_vec``):
``vsrlab/Locomotion-v0`` (``terrain=``), ``vsrlab/Jump-v0``, ``vsrlab/Escape-v0`` and
``vsrlab/Carrier-v0`` (pressure-based soft agents by default).

EvoGym's tasks on vsrlab's engine (docs/multimaterial.md), with EvoGym's observations, actions (a
target length ratio in [0.6, 1.6] per actuator voxel), rewards and ends: ``vsrlab-evogym/<id>``
for every EvoGym id in ``vsrlab.evogym_tasks()``, and ``vsrlab/<id>`` too but for
``Carrier-v0`` (``vsrlab/Carrier-v0`` is vsrlab's own carrier task) (``vsrlab/Walker-v0``,
``vsrlab-evogym/Jumper-v0``, ``vsrlab/Balancer-v1``, …; ``body=``: the material grid as rows of
digits joined by ``/``, or a 2-D array of codes as EvoGym's ``body=``, top row first).
"""

from __future__ import annotations

import os
from typing import Any, Optional

import gymnasium
import numpy as np
from gymnasium import spaces
from gymnasium.vector.utils import batch_space

from ._native import Episode, EvoGymEnv, EvoGymVectorEnv, Robot, VectorEpisode, evogym_episode_steps, evogym_tasks

# the robot's own brain is never called: the policy gives the actions
_IDLE_BRAIN = "constant:0"


def _make_robot(body: str, robot: Optional[str], sensors: Optional[str], preset: Optional[str]) -> Robot:
    if robot is not None:
        return Robot.load(os.fspath(robot))
    if body.startswith("psa"):
        return Robot(body, brain=_IDLE_BRAIN)
    return Robot(body, brain=_IDLE_BRAIN, sensors=sensors, preset=preset)


def _spaces(observations: int, actions: int) -> tuple[spaces.Box, spaces.Box]:
    obs = spaces.Box(-np.inf, np.inf, shape=(observations,), dtype=np.float64)
    act = spaces.Box(-1.0, 1.0, shape=(actions,), dtype=np.float64)
    return obs, act


def _actions(action: Any, shape: tuple) -> np.ndarray:
    a = np.asarray(action, dtype=np.float64)
    if a.shape != shape:
        raise ValueError(f"action: shape {shape} expected, got {a.shape}")
    if not np.isfinite(a).all():
        raise ValueError("action: values must be finite (in [-1, 1])")
    return np.ascontiguousarray(np.clip(a, -1.0, 1.0))


class SoftRobotEnv(gymnasium.Env):
    """One robot on one task. ``body`` is a CLI body short form (``biped-4x3``, ``worm-10x4``,
    ``"###/#.#"``, ``psa:small``) or ``robot`` a robot file; ``task`` a task short form."""

    metadata = {"render_modes": ["rgb_array"], "render_fps": 60}

    def __init__(
        self,
        body: str = "biped-4x3",
        task: str = "locomotion:flat",
        duration: float = 30.0,
        sensors: Optional[str] = None,
        preset: Optional[str] = None,
        robot: Optional[str] = None,
        render_mode: Optional[str] = None,
    ):
        if render_mode not in (None, "rgb_array"):
            raise ValueError(f"render_mode: None or 'rgb_array', got {render_mode!r}")
        self.render_mode = render_mode
        self.robot = _make_robot(body, robot, sensors, preset)
        self.task = task
        self._episode = Episode(self.robot, task, float(duration), 0, render_mode == "rgb_array")
        self.observation_space, self.action_space = _spaces(
            self._episode.observation_size, self._episode.action_size
        )

    def reset(self, *, seed: Optional[int] = None, options: Optional[dict] = None):
        super().reset(seed=seed)
        episode_seed = int(self.np_random.integers(0, 2**63 - 1))
        obs = self._episode.reset(episode_seed)
        return obs, {"time": 0.0}

    def step(self, action):
        obs, reward, terminated, truncated = self._episode.step(_actions(action, self.action_space.shape))
        return obs, float(reward), bool(terminated), bool(truncated), {"time": self._episode.time}

    def render(self):
        if self.render_mode == "rgb_array":
            return self._episode.render()
        return None

    def metrics(self) -> dict:
        """The task's metrics so far (distance, velocity, …), as the CLI reports them."""
        return self._episode.metrics()


class SoftRobotVectorEnv(gymnasium.vector.VectorEnv):
    """``num_envs`` copies of :class:`SoftRobotEnv` stepped together in Rust threads, one call per
    step; an episode that ended is reset at the next step (next-step autoreset)."""

    metadata = {"render_modes": [], "autoreset_mode": gymnasium.vector.AutoresetMode.NEXT_STEP}

    def __init__(
        self,
        num_envs: int = 8,
        body: str = "biped-4x3",
        task: str = "locomotion:flat",
        duration: float = 30.0,
        sensors: Optional[str] = None,
        preset: Optional[str] = None,
        robot: Optional[str] = None,
        render_mode: Optional[str] = None,
    ):
        if render_mode is not None:
            raise ValueError("render_mode: the vectorised environment does not render; use SoftRobotEnv")
        self.num_envs = int(num_envs)
        self.robot = _make_robot(body, robot, sensors, preset)
        self._episodes = VectorEpisode(self.robot, self.num_envs, task, float(duration), 0)
        self.single_observation_space, self.single_action_space = _spaces(
            self._episodes.observation_size, self._episodes.action_size
        )
        self.observation_space = batch_space(self.single_observation_space, self.num_envs)
        self.action_space = batch_space(self.single_action_space, self.num_envs)

    def reset(self, *, seed: Optional[int] = None, options: Optional[dict] = None):
        super().reset(seed=seed)
        base = int(self.np_random.integers(0, 2**62))
        return self._episodes.reset(base), {}

    def step(self, actions):
        obs, rewards, terminated, truncated = self._episodes.step(_actions(actions, self.action_space.shape))
        return obs, rewards, terminated, truncated, {}


def _task_env(task: str, default_body: str):
    class TaskEnv(SoftRobotEnv):
        def __init__(self, body: str = default_body, **kwargs: Any):
            super().__init__(body=body, task=kwargs.pop("task", task), **kwargs)

    class TaskVectorEnv(SoftRobotVectorEnv):
        def __init__(self, num_envs: int = 8, body: str = default_body, **kwargs: Any):
            super().__init__(num_envs=num_envs, body=body, task=kwargs.pop("task", task), **kwargs)

    return TaskEnv, TaskVectorEnv


class LocomotionEnv(SoftRobotEnv):
    """Locomotion on ``terrain`` (``flat``, ``hilly-H-W[-SEED]``, ``steppy-H-W[-SEED]``,
    ``uphill-DEG``, ``downhill-DEG``, ``psa-hilly-H-W[-SEED]``)."""

    def __init__(self, body: str = "biped-4x3", terrain: str = "flat", **kwargs: Any):
        super().__init__(body=body, task=f"locomotion:{terrain}", **kwargs)


class LocomotionVectorEnv(SoftRobotVectorEnv):
    """The vectorised :class:`LocomotionEnv`."""

    def __init__(self, num_envs: int = 8, body: str = "biped-4x3", terrain: str = "flat", **kwargs: Any):
        super().__init__(num_envs=num_envs, body=body, task=f"locomotion:{terrain}", **kwargs)


JumpEnv, JumpVectorEnv = _task_env("jump", "biped-4x3")
EscapeEnv, EscapeVectorEnv = _task_env("escape", "psa")
CarrierEnv, CarrierVectorEnv = _task_env("carrier", "psa")

class EvoGymTaskEnv(gymnasium.Env):
    """One of EvoGym's tasks (``Walker-v0``, …) with one robot, on vsrlab's mass-spring engine."""

    metadata = {"render_modes": ["rgb_array", "img"], "render_fps": 30}

    def __init__(
        self,
        task: str = "Walker-v0",
        body: Any = "33333/33333/33333/33333/33333",
        render_mode: Optional[str] = None,
        render_options: Optional[dict] = None,
    ):
        if render_mode not in (None, "rgb_array", "img"):
            raise ValueError(
                "render_mode: None, 'rgb_array' or 'img' (an image drawn without OpenGL); EvoGym's "
                f"'screen' and 'human' windows are not offered, got {render_mode!r}"
            )
        # EvoGym's `render_options` (hidden grid, edges…) are accepted and not used: the frame
        # is drawn as vsrlab's videos are
        self.render_mode = render_mode
        self._env = EvoGymEnv(task, _body_rows(body))
        self.observation_space = spaces.Box(-np.inf, np.inf, shape=(self._env.observation_size,), dtype=np.float64)
        self.action_space = spaces.Box(0.6, 1.6, shape=(self._env.action_size,), dtype=np.float64)

    def reset(self, *, seed: Optional[int] = None, options: Optional[dict] = None):
        # without a seed, the next episode's is drawn from the environment's generator (seeded
        # by the last seed given), so tasks that draw at reset (Catcher's world,
        # BidirectionalWalker's goals) start another episode each time, as EvoGym's do
        super().reset(seed=seed)
        episode = seed if seed is not None else int(self.np_random.integers(0, 2**63))
        return self._env.reset(episode), {}

    def step(self, action):
        a = np.asarray(action, dtype=np.float64)
        if a.shape != self.action_space.shape:
            raise ValueError(f"action: shape {self.action_space.shape} expected, got {a.shape}")
        obs, reward, terminated, truncated, unstable = self._env.step(np.ascontiguousarray(a))
        return obs, reward, terminated, truncated, {"unstable": unstable, "steps": self._env.steps}

    def render(self):
        """The current state as an RGB array (height × width × 3, uint8) with
        ``render_mode="rgb_array"`` (or EvoGym's ``"img"``); ``None`` without a render mode."""
        if self.render_mode in ("rgb_array", "img"):
            return self._env.render()
        return None


def _body_rows(body: Any) -> str:
    """A material grid as rows of digits joined by ``/`` (a string, or a 2-D array of codes)."""
    if isinstance(body, str):
        return body
    grid = np.asarray(body)
    if grid.ndim != 2:
        raise ValueError(f"body: a 2-D array of material codes expected, got shape {grid.shape}")
    return "/".join("".join(str(int(c)) for c in row) for row in grid)


class EvoGymTaskVectorEnv(gymnasium.vector.VectorEnv):
    """``num_envs`` copies of an EvoGym task with one body, stepped together on every core in one
    call per step (each group of four in population lanes, the bits of each stepped alone); an
    episode that ended is reset at the next step (next-step autoreset). ``info["unstable"]``
    says which environments became unstable."""

    metadata = {"render_modes": [], "autoreset_mode": gymnasium.vector.AutoresetMode.NEXT_STEP}

    def __init__(
        self,
        num_envs: int = 8,
        task: str = "Walker-v0",
        body: Any = "33333/33333/33333/33333/33333",
        render_mode: Optional[str] = None,
        max_episode_steps: Optional[int] = None,
    ):
        if render_mode is not None:
            raise ValueError("render_mode: the vectorised environment does not render; use the single environment")
        length = evogym_episode_steps(task)
        if max_episode_steps is not None and max_episode_steps != length:
            raise ValueError(f"max_episode_steps: {task}'s episodes last its own {length} steps, got {max_episode_steps}")
        self.num_envs = int(num_envs)
        self._envs = EvoGymVectorEnv(task, _body_rows(body), self.num_envs)
        self.single_observation_space = spaces.Box(-np.inf, np.inf, shape=(self._envs.observation_size,), dtype=np.float64)
        self.single_action_space = spaces.Box(0.6, 1.6, shape=(self._envs.action_size,), dtype=np.float64)
        self.observation_space = batch_space(self.single_observation_space, self.num_envs)
        self.action_space = batch_space(self.single_action_space, self.num_envs)

    def reset(self, *, seed: Optional[int] = None, options: Optional[dict] = None):
        super().reset(seed=seed)
        base = int(self.np_random.integers(0, 2**62)) if seed is None else int(seed)
        return self._envs.reset(base), {}

    def step(self, actions):
        a = np.ascontiguousarray(np.asarray(actions, dtype=np.float64))
        if a.shape != self.action_space.shape:
            raise ValueError(f"actions: shape {self.action_space.shape} expected, got {a.shape}")
        obs, rewards, terminated, truncated, unstable = self._envs.step(a)
        return obs, rewards, terminated, truncated, {"unstable": unstable}


def _evogym_env(task: str):
    class TaskEnv(EvoGymTaskEnv):
        def __init__(
            self,
            body: Any = "33333/33333/33333/33333/33333",
            render_mode: Optional[str] = None,
            render_options: Optional[dict] = None,
        ):
            super().__init__(task=task, body=body, render_mode=render_mode, render_options=render_options)

    class TaskVectorEnv(EvoGymTaskVectorEnv):
        def __init__(
            self,
            num_envs: int = 8,
            body: Any = "33333/33333/33333/33333/33333",
            render_mode: Optional[str] = None,
            max_episode_steps: Optional[int] = None,
        ):
            super().__init__(num_envs, task, body, render_mode, max_episode_steps)

    TaskEnv.__name__ = TaskEnv.__qualname__ = _evogym_class_name(task)
    vector = _evogym_class_name(task)[: -len("Env")] + "VectorEnv"
    TaskVectorEnv.__name__ = TaskVectorEnv.__qualname__ = vector
    return TaskEnv, TaskVectorEnv


def _evogym_class_name(task: str) -> str:
    """``Walker-v0`` → ``WalkerEnv``, ``Balancer-v1`` → ``BalancerV1Env``; ``EvoGym`` in front
    where vsrlab has a class of that name (``Carrier-v0`` → ``EvoGymCarrierEnv``)."""
    name, version = task.rsplit("-", 1)
    name = name + ("" if version == "v0" else version.upper()) + "Env"
    return "EvoGym" + name if name in _OWN_CLASSES else name


#: vsrlab's own environment classes, whose names EvoGym's must not take.
_OWN_CLASSES = {"LocomotionEnv", "JumpEnv", "EscapeEnv", "CarrierEnv"}

#: vsrlab's own ids, which EvoGym's must not take under ``vsrlab/``.
_OWN_IDS = {"vsrlab/Locomotion-v0", "vsrlab/Jump-v0", "vsrlab/Escape-v0", "vsrlab/Carrier-v0"}

#: EvoGym's task ids and their environment classes: every task vsrlab implements
#: (``evogym_tasks()``), each a class of this module (``WalkerEnv``, ``BalancerV1Env``…), under
#: ``vsrlab-evogym/<id>`` (all of them) and under ``vsrlab/<id>`` (all but ``Carrier-v0``, which
#: is vsrlab's own carrier task there).
EVOGYM_ENVIRONMENTS = {}
for _task in evogym_tasks():
    _class = _evogym_class_name(_task)
    globals()[_class], _vector = _evogym_env(_task)
    globals()[_vector.__name__] = _vector
    EVOGYM_ENVIRONMENTS[f"vsrlab-evogym/{_task}"] = _class
    if f"vsrlab/{_task}" not in _OWN_IDS:
        EVOGYM_ENVIRONMENTS[f"vsrlab/{_task}"] = _class


#: Every registered id and its environment classes.
ENVIRONMENTS = {
    "vsrlab/Locomotion-v0": ("LocomotionEnv", "LocomotionVectorEnv"),
    "vsrlab/Jump-v0": ("JumpEnv", "JumpVectorEnv"),
    "vsrlab/Escape-v0": ("EscapeEnv", "EscapeVectorEnv"),
    "vsrlab/Carrier-v0": ("CarrierEnv", "CarrierVectorEnv"),
}


def register_all() -> None:
    """Registers the environments with Gymnasium (done on ``import vsrlab``)."""
    for env_id, (single, vector) in ENVIRONMENTS.items():
        if env_id in gymnasium.registry:
            continue
        gymnasium.register(
            id=env_id,
            entry_point=f"vsrlab.envs:{single}",
            vector_entry_point=f"vsrlab.envs:{vector}",
        )
    for env_id, single in EVOGYM_ENVIRONMENTS.items():
        if env_id not in gymnasium.registry:
            steps = evogym_episode_steps(env_id.split("/", 1)[1])
            vector = single[: -len("Env")] + "VectorEnv"
            gymnasium.register(
                id=env_id,
                entry_point=f"vsrlab.envs:{single}",
                vector_entry_point=f"vsrlab.envs:{vector}",
                max_episode_steps=steps,
            )
