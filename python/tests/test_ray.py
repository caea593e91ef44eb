"""Evaluations on a Ray cluster started on loopback (a head and one more worker node, one CPU
each): a run whose worker is killed mid-batch ends with the same files as the local run, for
every genotype kind (flat vectors, graphs, co-design grids and CPPNs) and for 3D robots."""

import os
import signal
import socket
import subprocess
import sys
import time
import json
from pathlib import Path

import numpy as np
import pytest
import ray

import vsrlab
from vsrlab import _native
from vsrlab.cluster import RayEvaluator, check_versions

CONFIG = """
name = "ray-small"
runs = 1
seed = 5
[representation]
body = "biped-4x3"
sensors = "uniform-vxy+a+t-0"
brain = { kind = "distributed-mlp", layout = "homogeneous", signals = 1, hidden = [] }
[task]
terrain = "flat"
duration = 3.0
fitness = "velocity"
[optimizer]
kind = "ga"
population_size = 16
offspring_size = 16
[stop]
evaluations = 112
"""

RAY = str(Path(sys.executable).parent / "ray")
ROOT = Path(__file__).resolve().parents[2]
# loopback tests only: Ray 2.60's token authentication off for head, worker and this driver
ENV = dict(os.environ, RAY_AUTH_MODE="disabled", RAY_USAGE_STATS_ENABLED="0")


def _free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def _ray(*args: str) -> None:
    done = subprocess.run([RAY, *args], env=ENV, capture_output=True, text=True, timeout=180)
    assert done.returncode == 0, done.stdout + done.stderr


@pytest.fixture(scope="module")
def cluster():
    port = _free_port()
    os.environ.update(RAY_AUTH_MODE="disabled", RAY_USAGE_STATS_ENABLED="0")
    _ray("start", "--head", f"--port={port}", "--node-ip-address=127.0.0.1", "--num-cpus=1",
         "--include-dashboard=false", "--disable-usage-stats")
    try:
        _ray("start", f"--address=127.0.0.1:{port}", "--node-ip-address=127.0.0.1", "--num-cpus=1")
        yield f"127.0.0.1:{port}"
    finally:
        subprocess.run([RAY, "stop", "--force"], env=ENV, capture_output=True, timeout=180)


def test_a_run_whose_worker_dies_mid_batch_ends_like_the_local_run(cluster, tmp_path):
    config = tmp_path / "ray.toml"
    config.write_text(CONFIG)
    local = vsrlab.run(config, tmp_path / "local")
    seen = {}

    def kill_second_actor(evaluator):
        seen["actors"] = len(evaluator.actors)
        seen["nodes"] = sum(1 for n in ray.nodes() if n["Alive"])
        if evaluator.batches == 3:
            # the second node's actor process, while it holds its part of the batch
            os.kill(evaluator.pids[1], signal.SIGKILL)
            seen["killed"] = evaluator.pids[1]
        seen["resubmitted"] = evaluator.resubmitted

    remote = vsrlab.run(config, tmp_path / "ray", ray=cluster, on_submit=kill_second_actor,
                        min_chunk_seconds=0)
    assert seen["nodes"] == 2 and seen["actors"] == 2
    assert "killed" in seen and seen["resubmitted"] >= 1, seen
    assert [s["best_fitness"] for s in remote] == [s["best_fitness"] for s in local]
    assert remote[0]["evaluations"] == local[0]["evaluations"] == 112
    ours = dict(_native.deterministic_files(str(tmp_path / "ray")))
    theirs = dict(_native.deterministic_files(str(tmp_path / "local")))
    assert sorted(ours) == sorted(theirs) and len(ours) >= 3
    for name in ours:
        assert ours[name] == theirs[name], name


def test_a_bad_experiment_fails_before_any_worker_starts(cluster, tmp_path):
    bad = tmp_path / "bad.toml"
    bad.write_text(CONFIG.replace("population_size = 16", 'population_size = "many"'))
    with pytest.raises(ValueError, match="population_size"):
        vsrlab.run(bad, tmp_path / "out", ray=cluster)


def test_a_batch_that_fails_stops_at_the_checkpoint_and_resume_on_ray_finishes_it(cluster, tmp_path):
    config = tmp_path / "ray.toml"
    config.write_text(CONFIG)
    local = vsrlab.run(config, tmp_path / "local")

    def fail_at_the_fourth_batch(evaluator):
        if evaluator.batches == 4:
            raise RuntimeError("the cluster went away")

    with pytest.raises(ValueError, match="the cluster went away"):
        vsrlab.run(config, tmp_path / "ray", ray=cluster, on_submit=fail_at_the_fourth_batch)
    assert (tmp_path / "ray" / "experiment.toml").is_file()
    resumed = vsrlab.run(config, tmp_path / "ray", ray=cluster, resume=True)
    assert [s["best_fitness"] for s in resumed] == [s["best_fitness"] for s in local]
    ours = dict(_native.deterministic_files(str(tmp_path / "ray")))
    theirs = dict(_native.deterministic_files(str(tmp_path / "local")))
    assert ours == theirs


# One small experiment per genotype kind the vector run above does not cover; co-design
# evaluations train PPO (a few tiny iterations) on the worker.
KINDS = {
    "graph": """
name = "ray-graph"
runs = 1
seed = 2
[representation]
body = "biped-4x3"
preset = "2021"
sensors = "spinedTouchSighted-f-f-0.01"
brain = { kind = "graph" }
[genotype]
kind = "graph"
connectivity = "full"
modularity = "plain"
modules = "legs-torso"
[task]
terrain = "flat"
duration = 2.0
fitness = "velocity"
[optimizer]
kind = "ga"
population_size = 8
offspring_size = 8
mutation_probability = 1.0
[stop]
evaluations = 32
""",
    "material-grid": """
name = "ray-material-grid"
runs = 1
seed = 1
[genotype]
kind = "material-grid"
width = 3
height = 3
mutation_rate = 0.2
[genotype.ppo]
iterations = 2
environments = 2
steps_per_environment = 16
hidden = [8]
[task]
kind = "evogym"
env = "Walker-v0"
[optimizer]
kind = "ga"
population_size = 2
offspring_size = 4
tournament_size = 1
mutation_probability = 1.0
initial_population_size = 4
[stop]
evaluations = 12
""",
    "cppn": """
name = "ray-cppn"
runs = 1
seed = 1
[genotype]
kind = "cppn"
width = 3
height = 3
[genotype.ppo]
iterations = 2
environments = 2
steps_per_environment = 16
hidden = [8]
[task]
kind = "evogym"
env = "Walker-v0"
[optimizer]
kind = "neat"
population_size = 4
[stop]
evaluations = 12
""",
    "3d": """
name = "ray-3d"
runs = 1
seed = 1
[representation]
body = { kind = "voxel3d", body = "quadruped", sensors = "cpg:5,touch,floor,vy,vx" }
brain = { kind = "distributed-mlp", signals = 1 }
[task]
kind = "locomotion3d"
duration = 0.05
fitness = "distance"
[optimizer]
kind = "ga"
population_size = 8
offspring_size = 8
[stop]
evaluations = 16
""",
}


@pytest.mark.parametrize("kind", sorted(KINDS))
def test_every_genotype_kind_runs_on_ray_with_a_worker_killed_and_ends_like_the_local_run(cluster, tmp_path, kind):
    config = tmp_path / f"{kind}.toml"
    config.write_text(KINDS[kind])
    local = vsrlab.run(config, tmp_path / "local")
    seen = {}

    def kill_second_actor(evaluator):
        if evaluator.batches == 1:
            os.kill(evaluator.pids[1], signal.SIGKILL)
        if evaluator.batches == 2:
            # Ray started the killed actor again; whether the chunk it held was sent again depends
            # on whether it had finished (the vector run above asserts the resending)
            seen["restarted"] = ray.get(evaluator.actors[1].ready.remote())[0] != evaluator.pids[1]

    remote = vsrlab.run(config, tmp_path / "ray", ray=cluster, on_submit=kill_second_actor,
                        min_chunk_seconds=0)
    assert seen.get("restarted"), seen
    assert [s["best_fitness"] for s in remote] == [s["best_fitness"] for s in local]
    ours = dict(_native.deterministic_files(str(tmp_path / "ray")))
    theirs = dict(_native.deterministic_files(str(tmp_path / "local")))
    assert any(name.endswith("best.robot.json") for name in ours), sorted(ours)
    assert sorted(ours) == sorted(theirs)
    for name in ours:
        assert ours[name] == theirs[name], name


def test_a_worker_of_another_vsrlab_version_is_refused_by_name():
    check_versions([(11, _native.__version__), (12, _native.__version__)])
    with pytest.raises(RuntimeError, match=r"process 12\) runs vsrlab 0\.0\.1, the driver"):
        check_versions([(11, _native.__version__), (12, "0.0.1")])


def test_a_worker_evaluates_json_genotypes_like_the_batch_evaluator(tmp_path):
    worker = _native.Worker(CONFIG, "ray.toml", 1)
    batch = _native.BatchEvaluator(CONFIG, "ray.toml", 1)
    genes = np.random.default_rng(3).uniform(-1, 1, (3, batch.genotype_length))
    seeds = np.array([1, 2, 3], dtype=np.uint64)
    served = json.loads(worker.evaluations([json.dumps(list(row)) for row in genes], seeds))
    local = json.loads(batch.evaluations(genes, seeds))
    assert [e["objectives"] for e in served] == [e["objectives"] for e in local]
    with pytest.raises(ValueError, match=r"genotypes\[1\]"):
        worker.evaluations(["[0.5]" * 1, '{"edges": 3}', "[]"], seeds)


def test_a_campaign_on_ray_whose_driver_is_killed_resumes_to_the_local_campaigns_files(cluster, tmp_path):
    files = []
    for name, seed in (("camp-a", 5), ("camp-b", 6)):
        path = tmp_path / f"{name}.toml"
        text = CONFIG.replace('name = "ray-small"', f'name = "{name}"').replace("runs = 1", "runs = 2")
        path.write_text(text.replace("seed = 5", f"seed = {seed}"))
        files.append(path)
    local = vsrlab.campaign(files, tmp_path / "local", threads=2)
    assert [s["name"] for s in local["settings"]] == ["camp-a", "camp-b"]
    assert local["table"].splitlines()[0].startswith("setting")

    out = tmp_path / "ray"
    command = [sys.executable, "-m", "vsrlab", "campaign", *map(str, files), "--out", str(out), "--ray", cluster]
    log = tmp_path / "driver.log"
    with open(log, "w") as sink:
        driver = subprocess.Popen(command, env=ENV, stdout=sink, stderr=subprocess.STDOUT)
    deadline = time.monotonic() + 180
    while not list(out.glob("*/run-*/checkpoint.json")):
        assert driver.poll() is None, log.read_text()
        assert time.monotonic() < deadline, "no checkpoint in 3 minutes"
        time.sleep(0.05)
    driver.kill()
    driver.wait()
    assert not all((out / s / "summary.json").is_file() for s in ("camp-a", "camp-b")), "killed before the end"
    resumed = vsrlab.campaign(files, out, resume=True, ray=cluster)
    assert [len(s["summaries"]) for s in resumed["settings"]] == [2, 2]
    for name in ("camp-a", "camp-b"):
        ours = dict(_native.deterministic_files(str(out / name)))
        theirs = dict(_native.deterministic_files(str(tmp_path / "local" / name)))
        assert sorted(ours) == sorted(theirs) and len(ours) >= 6
        for file in ours:
            assert ours[file] == theirs[file], f"{name}/{file}"


def test_the_cli_s_solver_reaches_the_cluster_and_ends_like_the_local_run(cluster, tmp_path, vsrlab_bin):
    config = tmp_path / "ray.toml"
    config.write_text(CONFIG.replace("evaluations = 112", "evaluations = 48"))
    solver = ["--solver", "sequential-impulses"]
    local = subprocess.run([str(vsrlab_bin), "run", str(config), "--out", str(tmp_path / "local"), *solver],
                           capture_output=True, text=True, timeout=600)
    assert local.returncode == 0, local.stderr
    env = dict(ENV, VSRLAB_PYTHON=sys.executable)
    remote = subprocess.run([str(vsrlab_bin), "run", str(config), "--out", str(tmp_path / "ray"), "--ray", cluster,
                             *solver], capture_output=True, text=True, env=env, timeout=600)
    assert remote.returncode == 0, remote.stderr
    resolved = (tmp_path / "ray" / "experiment.toml").read_text()
    assert 'solver = "sequential-impulses"' in resolved, resolved
    ours = dict(_native.deterministic_files(str(tmp_path / "ray")))
    theirs = dict(_native.deterministic_files(str(tmp_path / "local")))
    assert sorted(ours) == sorted(theirs) and len(ours) >= 3
    for name in ours:
        assert ours[name] == theirs[name], name
    # the default solver gives other results: the option was not dropped on the way
    plain = vsrlab.run(config, tmp_path / "plain")
    assert plain[0]["best_fitness"] != json.loads((tmp_path / "ray" / "summary.json").read_text())[0]["best_fitness"]


def test_a_bad_solver_is_refused_naming_the_argument_before_anything_is_written(tmp_path):
    config = tmp_path / "ray.toml"
    config.write_text(CONFIG)
    with pytest.raises(ValueError, match="solver: expected soft-substeps"):
        vsrlab.run(config, tmp_path / "out", solver="dyn4j")
    with pytest.raises(ValueError, match="solver: the affordance task has no 2D"):
        vsrlab.campaign([ROOT / "experiments/ch5.1/reduced.toml"], tmp_path / "out", solver="soft-substeps")
    assert not (tmp_path / "out").exists()


def test_quick_evaluations_go_in_few_chunks_and_give_the_same_answers(cluster, tmp_path):
    # a campaign's many small runs should send few Ray tasks: once a batch's evaluations are
    # known to be quick, a chunk holds at least `min_chunk_seconds` of them
    config = tmp_path / "quick.toml"
    config.write_text(CONFIG)
    text = _native.experiment_text(str(config))
    rows = np.random.default_rng(3).uniform(-1, 1, (16, vsrlab.genotype_length(config)))
    genotypes = [json.dumps(list(map(float, row))) for row in rows]
    seeds = np.arange(16, dtype=np.uint64)
    answers = {}
    for floor in (0.0, 1000.0):
        evaluator = RayEvaluator(text, address=cluster, origin=str(config), min_chunk_seconds=floor)
        first = evaluator(genotypes, seeds)
        assert evaluator.chunks == 8, "no estimate yet: 4 chunks per actor"
        second = evaluator(genotypes, seeds)
        answers[floor] = (evaluator.chunks, first, second)
        robot = json.loads(evaluator.robot_file(genotypes[0], None, "test"))
        assert robot, "a best robot's file comes back"
        assert evaluator.pool.busy == [0, 0], "every chunk and file released on the shared pool"
        evaluator.close()
    assert answers[0.0][0] == 8, "no lower bound: chunks as before"
    assert answers[1000.0][0] == 1, "a floor above the batch's seconds: the batch goes whole"

    def without_times(answer: str) -> list:
        return [{k: v for k, v in e.items() if k != "seconds"} for e in json.loads(answer)]

    rounds = [without_times(a) for floor in answers for a in answers[floor][1:]]
    assert len(rounds[0]) == 16 and all(r == rounds[0] for r in rounds)
