"""vsrlab from Python: voxel-based soft robots and pressure-based soft agents, simulated in Rust.

The same robots, tasks and experiment files as the ``vsrlab`` command line (docs/python.md):

>>> import vsrlab
>>> robot = vsrlab.Robot("biped-4x3", brain="phase")
>>> vsrlab.simulate(robot, task="locomotion:flat", duration=5)["distance"]   # doctest: +SKIP
>>> fitness = vsrlab.evaluate_batch("experiments/quickstart.toml", genotypes)  # doctest: +SKIP

``gymnasium.make("vsrlab/Locomotion-v0", body="worm-6x2", terrain="hilly-1-10")`` steps a robot
from your own policy; ``vsrlab.run(config, ray="auto")`` spreads an experiment's evaluations over
a Ray cluster (docs/cluster.md).
"""

from __future__ import annotations

import json
import os
from pathlib import Path
from typing import Any, Optional, Sequence, Union

import numpy as np

from . import _native
from ._native import BatchEvaluator, Episode, EvoGymEnv, Robot, VectorEpisode, __version__, evogym_tasks

__all__ = [
    "BatchEvaluator",
    "Episode",
    "EvoGymEnv",
    "Robot",
    "VectorEpisode",
    "__version__",
    "config_text",
    "evogym_tasks",
    "evaluate_batch",
    "genotype_length",
    "evaluate_records",
    "load_robot",
    "robot_of",
    "run",
    "campaign",
    "simulate",
]

PathLike = Union[str, "os.PathLike[str]"]


def load_robot(path: PathLike) -> Robot:
    """Reads a robot file (voxel robot or PSA), as written by ``vsrlab run`` or ``Robot.save``."""
    return Robot.load(os.fspath(path))


def _robot(robot: Union[Robot, PathLike], brain: Optional[str], sensors: Optional[str], preset: Optional[str]) -> Robot:
    if isinstance(robot, Robot):
        return robot
    if not isinstance(robot, (str, os.PathLike)):
        raise ValueError(f"robot: a Robot, a body short form or a robot file path, got {type(robot).__name__}")
    text = os.fspath(robot)
    if text.endswith(".json"):
        return Robot.load(text)
    return Robot(text, brain=brain, sensors=sensors, preset=preset)


def simulate(
    robot: Union[Robot, PathLike] = "biped-4x3",
    task: str = "locomotion:flat",
    duration: Optional[float] = None,
    seed: int = 0,
    video: Optional[PathLike] = None,
    brain: Optional[str] = None,
    sensors: Optional[str] = None,
    preset: Optional[str] = None,
) -> dict:
    """Runs one episode and returns its outcome: ``fitness`` (a list), the task's metrics
    (``distance``, ``velocity``, …), ``steps`` and ``units``.

    ``robot`` is a :class:`Robot`, a robot file (``.json``) or a body short form (then ``brain``,
    ``sensors`` and ``preset`` complete it, as on the command line); ``task`` a short form
    (``locomotion:hilly-1-10``, ``jump``, ``escape``, ``carrier``) or an experiment file whose task
    is replayed; ``duration`` defaults to 30 s; ``video`` writes a GIF, MP4 or PNG.
    """
    r = _robot(robot, brain, sensors, preset)
    return _native.simulate(r, task, duration, int(seed), None if video is None else os.fspath(video))


def config_text(config: Union[PathLike, str]) -> tuple[str, str]:
    """The TOML text of an experiment and a name for error messages: ``config`` is a file path or
    the text itself."""
    if isinstance(config, os.PathLike) or (isinstance(config, str) and "\n" not in config and "=" not in config):
        path = Path(config)
        if not path.is_file():
            raise ValueError(f"config: no experiment file at {path}")
        return path.read_text(), str(path)
    if not isinstance(config, str):
        raise ValueError(f"config: a path or TOML text, got {type(config).__name__}")
    return config, "config"


_evaluators: dict = {}


def _evaluator(config: Union[PathLike, str], threads: int) -> BatchEvaluator:
    text, origin = config_text(config)
    key = (text, int(threads))
    if key not in _evaluators:
        if len(_evaluators) > 8:
            _evaluators.clear()
        _evaluators[key] = BatchEvaluator(text, origin, int(threads))
    return _evaluators[key]


def genotype_length(config: Union[PathLike, str]) -> int:
    """Genes per genotype of an experiment (the width of ``evaluate_batch``'s matrix)."""
    return _evaluator(config, 0).genotype_length


def _genotype_matrix(genotypes: Any, width: int) -> np.ndarray:
    try:
        g = np.asarray(genotypes, dtype=np.float64)
    except (TypeError, ValueError) as e:
        raise ValueError(f"genotypes: not an array of numbers ({e})") from None
    if g.ndim == 1:
        g = g.reshape(1, -1)
    if g.ndim != 2:
        raise ValueError(f"genotypes: a 2-D array (one genotype per row) is needed, got {g.ndim} dimensions")
    if g.shape[1] != width:
        raise ValueError(
            f"genotypes: shape {g.shape} has rows of {g.shape[1]} genes; this experiment's genotypes have {width}"
        )
    return np.ascontiguousarray(g)


def _seed_array(seeds: Optional[Sequence[int]], rows: int) -> np.ndarray:
    if seeds is None:
        return np.arange(rows, dtype=np.uint64)
    s = np.asarray(seeds)
    if s.ndim == 0:
        s = np.full(rows, int(s))
    if s.ndim != 1 or s.shape[0] != rows:
        raise ValueError(f"seeds: one seed per genotype ({rows}), got shape {s.shape}")
    if s.dtype.kind not in "iu" or (s.dtype.kind == "i" and (s < 0).any()):
        raise ValueError("seeds: non-negative integers are needed")
    return np.ascontiguousarray(s.astype(np.uint64))


def evaluate_batch(
    config: Union[PathLike, str],
    genotypes: Any,
    seeds: Optional[Sequence[int]] = None,
    threads: int = 0,
) -> np.ndarray:
    """Fitness of every genotype (a row of genes) on an experiment's robot and task, on every core
    with the GIL released; exactly what ``vsrlab run`` and ``vsrlab evaluate`` compute for the same
    genotype and seed (NaN where an evaluation failed).

    ``config`` is an experiment file (or its TOML text); ``seeds`` one candidate seed per genotype
    (default 0, 1, 2, …: they matter only for tasks with a random terrain per evaluation).
    """
    evaluator = _evaluator(config, threads)
    g = _genotype_matrix(genotypes, evaluator.genotype_length)
    return evaluator.fitness(g, _seed_array(seeds, g.shape[0]))


def robot_of(config: Union[PathLike, str], genotype: Any) -> Robot:
    """The robot a genotype stands for in an experiment (to simulate, render or save it)."""
    evaluator = _evaluator(config, 0)
    g = _genotype_matrix(genotype, evaluator.genotype_length)
    if g.shape[0] != 1:
        raise ValueError(f"genotype: one genotype is needed, got {g.shape[0]} rows")
    return evaluator.robot(list(map(float, g[0])))


def evaluate_records(config: Union[PathLike, str], genotypes: Any, seeds: Optional[Sequence[int]] = None) -> list:
    """Like :func:`evaluate_batch`, but each evaluation's record: fitness, distance, velocity,
    body and error (why an evaluation failed)."""
    evaluator = _evaluator(config, 0)
    g = _genotype_matrix(genotypes, evaluator.genotype_length)
    return json.loads(evaluator.records(g, _seed_array(seeds, g.shape[0])))


def run(
    config: PathLike,
    out: PathLike,
    resume: bool = False,
    threads: int = 0,
    ray: Optional[str] = None,
    verbose: bool = False,
    solver: Optional[str] = None,
    **ray_options: Any,
) -> list:
    """Runs an experiment file like ``vsrlab run`` (same files, checkpoints and ``resume``) and
    returns each run's summary.

    ``ray`` sends every batch of evaluations to a Ray cluster instead of local threads: ``"auto"``
    (a cluster started with ``ray start``), ``"local"`` (a new one on this machine) or an address
    such as ``"10.0.0.1:6379"``; the results are identical bit for bit (docs/cluster.md).
    ``ray_options`` go to :class:`vsrlab.cluster.RayEvaluator`. ``solver`` replaces the file's 2D
    physics solver (``"soft-substeps"`` or ``"sequential-impulses"``), like ``vsrlab run --solver``.
    """
    path = Path(config)
    if not path.is_file():
        raise ValueError(f"config: no experiment file at {path}")
    evaluate = None
    if ray is not None:
        from .cluster import RayEvaluator

        text = _native.experiment_text(os.fspath(path), solver)
        evaluate = RayEvaluator(text, address=ray, origin=str(path), **ray_options)
    try:
        text = _native.run(os.fspath(path), os.fspath(out), resume, int(threads), evaluate, verbose, solver)
    finally:
        if evaluate is not None:
            evaluate.close()
    return json.loads(text)


def campaign(
    files: Any,
    out: PathLike,
    resume: bool = False,
    threads: int = 0,
    ray: Optional[str] = None,
    verbose: bool = False,
    solver: Optional[str] = None,
    **ray_options: Any,
) -> dict:
    """Runs many experiment files (every setting of a sweep file, every run) side by side, each
    setting into ``out/<setting name>`` as ``vsrlab run`` writes it, and returns
    ``{"settings": [{"name", "out", "runs", "summaries"}], "table": text}``.

    Locally the runs share one pool of ``threads``; with ``ray`` (as in :func:`run`) every
    setting's batches go to one shared pool of Ray actors, so a cluster stays busy even when each
    run's batch is small. ``resume=True`` continues every unfinished run from its checkpoint.
    The files are the same bit for bit as running each file alone (docs/cluster.md). ``solver``
    replaces every file's 2D physics solver, as in :func:`run`.
    """
    paths = [os.fspath(files)] if isinstance(files, (str, os.PathLike)) else [os.fspath(f) for f in files]
    for path in paths:
        if not Path(path).is_file():
            raise ValueError(f"files: no experiment file at {path}")
    pool = None
    evaluators = None
    if ray is not None:
        from .cluster import RayEvaluator, RayPool

        settings = json.loads(_native.campaign_settings(paths, os.fspath(out), solver))
        pool_keys = ("actors", "cpus_per_actor", "concurrency", "timeout")
        pool = RayPool(ray, **{k: v for k, v in ray_options.items() if k in pool_keys})
        rest = {k: v for k, v in ray_options.items() if k not in pool_keys or k == "timeout"}
        evaluators = [RayEvaluator(s["text"], origin=s["name"], pool=pool, **rest) for s in settings]
    try:
        text = _native.campaign(paths, os.fspath(out), resume, int(threads), evaluators, verbose, solver)
    finally:
        if pool is not None:
            pool.close()
    return json.loads(text)


def _register() -> None:
    try:
        import gymnasium  # noqa: F401
    except ImportError:  # the environments need gymnasium; the rest does not
        return
    from . import envs

    envs.register_all()


_register()
