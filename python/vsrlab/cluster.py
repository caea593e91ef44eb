"""Evaluations on a Ray cluster: the route from a laptop to a cluster (docs/cluster.md).

:class:`RayPool` keeps one actor per node, each evaluating on every CPU Ray gives it (rayon
threads in Rust) for any experiment it is sent: it builds an experiment's evaluator from the
experiment's text the first time and keeps it. :class:`RayEvaluator` binds a pool to one
experiment: the runner (``vsrlab.run(config, out, ray=...)``, or each setting of
``vsrlab.campaign(files, out, ray=...)``) hands it every batch as the JSON texts of its
genotypes, whatever their kind (vectors, graphs, co-design bodies, ...); it splits the batch into
chunks, sends them to the actors and joins the answers in order. Each evaluation is a pure
function of (genotype, seed), so the results are the same bit for bit as a local run. A run's best
robot file is made on an actor too (a co-designed robot's policy is learned there).

A worker that dies mid-batch: Ray restarts its actor (``max_restarts=-1``) and the chunk it was
evaluating is sent again, to the next actor; nothing is lost. A batch that cannot be finished
(every attempt failed, or ``timeout`` passed) stops the run with an error at its last
checkpoint, and ``resume=True`` continues it.
"""

from __future__ import annotations

import hashlib
import json
from collections import deque
import os
import threading
import time
from typing import Any, Callable, Optional

import numpy as np

from ._native import Worker, __version__


#: seconds of evaluations a chunk aims at once evaluations are known to be slow
CHUNK_SECONDS = 0.5
#: seconds of evaluations a chunk holds at least once evaluations are known to be quick: a Ray
#: task costs about a millisecond of the driver's and the node's time, so that many small runs
#: (a campaign's) send few tasks, and the actors take them from all runs
MIN_CHUNK_SECONDS = 0.05


class _Worker:
    """A Ray actor: the evaluators of the experiments it is sent, on one node."""

    def __init__(self, threads: int):
        self.threads = threads
        self.workers: dict = {}
        self.lock = threading.Lock()

    def ready(self) -> tuple:
        return os.getpid(), __version__

    def _worker(self, key: str, text: str, origin: str) -> Worker:
        with self.lock:
            if key not in self.workers:
                self.workers[key] = Worker(text, origin, self.threads)
            return self.workers[key]

    def evaluate(self, key: str, text: str, origin: str, genotypes: list, seeds: np.ndarray) -> str:
        worker = self._worker(key, text, origin)
        return worker.evaluations(genotypes, np.ascontiguousarray(seeds, dtype=np.uint64))

    def robot_file(self, key: str, text: str, origin: str, genotype: str, record: Optional[str], note: str) -> bytes:
        return bytes(self._worker(key, text, origin).robot_file(genotype, record, note))


def check_versions(found: list, driver: str = __version__) -> None:
    """Refuses workers whose vsrlab is not the driver's: ``found`` holds each actor's
    (pid, version). A run joins the results of one model version only."""
    for pid, version in found:
        if version != driver:
            raise RuntimeError(
                f"ray: a worker (process {pid}) runs vsrlab {version}, the driver {driver}: "
                "install the same vsrlab on every node"
            )


class RayPool:
    """Ray actors, one per node (or ``actors`` of ``cpus_per_actor`` CPUs each), that evaluate
    batches of any experiment; ``concurrency`` chunks at once per actor (a campaign's runs share
    them).

    ``address``: ``"auto"`` (a cluster started with ``ray start``), ``"local"`` (start one on this
    machine) or ``"HOST:PORT"``.
    """

    def __init__(
        self,
        address: str = "auto",
        actors: Optional[int] = None,
        cpus_per_actor: Optional[int] = None,
        concurrency: int = 4,
        timeout: float = 3600.0,
    ):
        import ray
        from ray.util.scheduling_strategies import NodeAffinitySchedulingStrategy

        self._ray = ray
        self._connected = False
        if not ray.is_initialized():
            if address == "local":
                ray.init(include_dashboard=False, logging_level="warning")
            else:
                ray.init(address=address, logging_level="warning")
            self._connected = True
        self.timeout = float(timeout)
        remote = ray.remote(max_restarts=-1, max_task_retries=0)(_Worker)
        nodes = [n for n in ray.nodes() if n.get("Alive") and n.get("Resources", {}).get("CPU", 0) >= 1]
        if not nodes:
            raise RuntimeError("ray: the cluster has no node with a CPU")
        concurrency = max(1, int(concurrency))
        self.actors = []
        if actors is None:
            for node in nodes:
                cpus = int(cpus_per_actor or node["Resources"]["CPU"])
                strategy = NodeAffinitySchedulingStrategy(node_id=node["NodeID"], soft=True)
                options = dict(num_cpus=cpus, scheduling_strategy=strategy, max_concurrency=concurrency)
                self.actors.append(remote.options(**options).remote(cpus))
        else:
            cpus = int(cpus_per_actor or 1)
            for _ in range(int(actors)):
                self.actors.append(remote.options(num_cpus=cpus, max_concurrency=concurrency).remote(cpus))
        found = ray.get([a.ready.remote() for a in self.actors], timeout=self.timeout)
        check_versions(found)
        #: each actor's worker process id, as it started (tests kill one)
        self.pids = [pid for pid, _ in found]
        #: chunks in flight on each actor, from every evaluator sharing the pool
        self.busy = [0] * len(self.actors)
        self._lock = threading.Lock()

    def take(self, allowed: list) -> int:
        """The least busy actor among ``allowed`` (indices), counted busy by one more chunk."""
        with self._lock:
            actor = min(allowed, key=lambda k: (self.busy[k], k))
            self.busy[actor] += 1
            return actor

    def release(self, actor: int) -> None:
        """One chunk of ``actor`` is done (answered or failed)."""
        with self._lock:
            self.busy[actor] -= 1

    def close(self) -> None:
        """Ends the actors (and the connection, when this pool made it)."""
        for a in self.actors:
            try:
                self._ray.kill(a)
            except Exception:  # an actor already gone
                pass
        self.actors = []
        if self._connected:
            self._ray.shutdown()
            self._connected = False


class RayEvaluator:
    """Sends one experiment's batches of evaluations to the actors of a :class:`RayPool` (its
    own, made with ``pool_options``, or ``pool``, shared).

    ``chunks_per_actor`` splits a batch finer for load balance; ``min_chunk_seconds`` keeps chunks
    of quick evaluations at least that long (from the previous batch's seconds per evaluation), so
    that a campaign's many small runs send few Ray tasks (0: no lower bound); ``attempts`` is how
    many times one chunk may be sent before the batch fails; ``on_submit`` (tests) is called with
    this evaluator after each batch is sent.
    """

    def __init__(
        self,
        config_text: str,
        address: str = "auto",
        origin: str = "config",
        chunks_per_actor: int = 4,
        attempts: int = 5,
        timeout: float = 3600.0,
        on_submit: Optional[Callable[["RayEvaluator"], Any]] = None,
        pool: Optional[RayPool] = None,
        min_chunk_seconds: float = MIN_CHUNK_SECONDS,
        **pool_options: Any,
    ):
        # a local check first: a bad file fails here, with its field named, not on a worker
        Worker(config_text, origin, 1)  # built and dropped: only the check matters
        self.text = config_text
        self.origin = origin
        self.key = hashlib.sha256(config_text.encode()).hexdigest()[:16]
        self._own = pool is None
        self.pool = pool if pool is not None else RayPool(address, timeout=timeout, **pool_options)
        self._ray = self.pool._ray
        self.chunks_per_actor = max(1, int(chunks_per_actor))
        self.attempts = max(1, int(attempts))
        self.timeout = float(timeout)
        self.on_submit = on_submit
        self.min_chunk_seconds = float(min_chunk_seconds)
        #: the last batch's number of chunks
        self.chunks = 0
        self.batches = 0
        self.resubmitted = 0
        #: the last batch's mean seconds per evaluation, which sizes the next batch's chunks
        self.seconds_per_evaluation: Optional[float] = None

    @property
    def actors(self) -> list:
        return self.pool.actors

    @property
    def pids(self) -> list:
        return self.pool.pids

    def robot_file(self, genotype: str, record: Optional[str], note: str) -> bytes:
        """A run's best robot file, made on the least busy actor (a campaign's runs end at about
        the same time: their files spread over the nodes), another one if it dies."""
        ray = self._ray
        exceptions = (ray.exceptions.RayActorError, ray.exceptions.WorkerCrashedError)
        failed: set = set()
        for attempt in range(self.attempts):
            allowed = [k for k in range(len(self.actors)) if k not in failed] or list(range(len(self.actors)))
            actor = self.pool.take(allowed)
            try:
                ref = self.actors[actor].robot_file.remote(self.key, self.text, self.origin, genotype, record, note)
                return ray.get(ref, timeout=self.timeout)
            except exceptions as e:
                failed.add(actor)
                if attempt + 1 == self.attempts:
                    raise RuntimeError(f"ray: the best robot's file failed {self.attempts} times: {e}") from e
            finally:
                self.pool.release(actor)
        raise RuntimeError("ray: no attempt")

    def __call__(self, genotypes: list, seeds: np.ndarray) -> str:
        rows = len(genotypes)
        actors = len(self.actors)
        parts = min(rows, actors * self.chunks_per_actor)
        # cheap chunks: two in flight per actor, so that it never waits for the next one
        in_flight = 2
        if self.seconds_per_evaluation is not None:
            seconds = max(self.seconds_per_evaluation, 1e-9)
            # evaluations that take long (a co-design body's PPO training) go in smaller chunks,
            # down to one each, so that a batch's last chunk is short: about CHUNK_SECONDS each;
            # one in flight per actor, the next to whichever actor frees up first
            per_chunk = max(1, int(CHUNK_SECONDS / seconds))
            if per_chunk < -(-rows // parts):
                parts = min(rows, -(-rows // per_chunk))
                in_flight = 1
            # quick ones: no chunk under `min_chunk_seconds` (a small batch goes whole)
            if self.min_chunk_seconds > 0:
                parts = max(1, min(parts, int(rows * seconds / self.min_chunk_seconds)))
        bounds = np.linspace(0, rows, parts + 1).astype(int)
        chunks = [(int(a), int(b)) for a, b in zip(bounds[:-1], bounds[1:]) if b > a]
        self.chunks = len(chunks)
        results: list = [None] * len(chunks)
        tries = [0] * len(chunks)
        waiting = deque(range(len(chunks)))
        busy = [0] * actors
        pending = {}

        def submit(i: int, actor: int) -> None:
            a, b = chunks[i]
            tries[i] += 1
            busy[actor] += 1
            ref = self.actors[actor].evaluate.remote(self.key, self.text, self.origin, genotypes[a:b], seeds[a:b])
            pending[ref] = (i, actor)

        def feed() -> None:
            # each actor holds at most `in_flight` of this batch's chunks: the next chunk goes to
            # whichever frees up first, so that slow chunks do not hold up a batch (dynamic load
            # balance); among those, to the actor with the fewest chunks of every evaluator
            # sharing the pool (a campaign's other runs)
            while waiting:
                allowed = [k for k in range(actors) if busy[k] < in_flight]
                if not allowed:
                    return
                submit(waiting.popleft(), self.pool.take(allowed))

        feed()
        self.batches += 1
        if self.on_submit is not None:
            self.on_submit(self)
        try:
            self._collect(pending, results, tries, waiting, busy, chunks, feed)
        finally:
            # a batch that failed leaves no chunk counted on the shared pool
            for _, actor in pending.values():
                self.pool.release(actor)
        # each part is the JSON list of its chunk's evaluations: join them in order
        inner = [r.strip()[1:-1] for r in results]
        joined = "[" + ",".join(p for p in inner if p) + "]"
        seconds = [e.get("seconds", 0.0) for e in json.loads(joined)]
        if seconds:
            self.seconds_per_evaluation = sum(seconds) / len(seconds)
        return joined

    def _collect(self, pending: dict, results: list, tries: list, waiting: deque, busy: list, chunks: list, feed) -> None:
        """Waits for the batch's chunks, sending failed ones again, until every chunk answered."""
        ray = self._ray
        exceptions = (ray.exceptions.RayActorError, ray.exceptions.WorkerCrashedError)
        deadline = time.monotonic() + self.timeout
        while pending:
            left = deadline - time.monotonic()
            if left <= 0:
                raise RuntimeError(f"ray: a batch took longer than {self.timeout} s")
            done, _ = ray.wait(list(pending), num_returns=1, timeout=left)
            for ref in done:
                i, actor = pending.pop(ref)
                busy[actor] -= 1
                self.pool.release(actor)
                try:
                    results[i] = ray.get(ref)
                except exceptions as e:
                    if tries[i] >= self.attempts:
                        raise RuntimeError(f"ray: rows {chunks[i]} failed {tries[i]} times: {e}") from e
                    # sent again, first in line (a dead actor's tasks wait for Ray to restart it)
                    self.resubmitted += 1
                    waiting.appendleft(i)
            feed()

    def close(self) -> None:
        """Ends its own pool's actors (a shared pool is closed by its owner)."""
        if self._own:
            self.pool.close()
