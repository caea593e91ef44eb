"""evaluate_batch: the CLI's fitness bit for bit, any thread count, the GIL released, and
ValueError for bad arrays."""

import threading
import time

import numpy as np
import pytest

import vsrlab
from conftest import cli

HILLY = """
name = "hilly-random"
[representation]
body = "worm-6x2"
sensors = "uniform-a+vxy-0"
brain = { kind = "mlp", hidden = [4] }
[task]
terrain = "hilly-1-10"
duration = 3.0
fitness = "velocity"
random_terrain_per_evaluation = true
[optimizer]
kind = "ga"
[stop]
evaluations = 100
"""


def _csv(genotypes: np.ndarray) -> str:
    return "\n".join(",".join(repr(float(v)) for v in row) for row in genotypes) + "\n"


def test_a_thousand_genotypes_match_vsrlab_evaluate_exactly(root, vsrlab_bin, tmp_path):
    # the quickstart with 2 s episodes, to keep the suite short
    config = tmp_path / "quickstart-2s.toml"
    config.write_text((root / "experiments/quickstart.toml").read_text().replace("duration = 10.0", "duration = 2.0"))
    n = vsrlab.genotype_length(config)
    genotypes = np.random.default_rng(7).uniform(-1, 1, (1000, n))
    ours = vsrlab.evaluate_batch(config, genotypes)
    theirs = cli(vsrlab_bin, "evaluate", str(config), "-", stdin=_csv(genotypes))
    theirs = np.array([float(line) for line in theirs.split()])
    assert ours.shape == (1000,)
    assert np.array_equal(ours, theirs)
    assert len(np.unique(ours)) > 900


def test_seeds_pick_the_random_terrain_as_in_the_cli(tmp_path, vsrlab_bin):
    config = tmp_path / "hilly.toml"
    config.write_text(HILLY)
    n = vsrlab.genotype_length(config)
    genotypes = np.random.default_rng(1).uniform(-1, 1, (20, n))
    seeds = np.arange(100, 120, dtype=np.uint64)
    ours = vsrlab.evaluate_batch(config, genotypes, seeds)
    theirs = cli(vsrlab_bin, "evaluate", str(config), "-", "--seeds", ",".join(map(str, seeds)), stdin=_csv(genotypes))
    assert np.array_equal(ours, np.array([float(x) for x in theirs.split()]))
    same_genotype = vsrlab.evaluate_batch(config, np.repeat(genotypes[:1], 3, axis=0), [5, 6, 5])
    assert same_genotype[0] == same_genotype[2] != same_genotype[1]
    # the TOML text works as well as its file
    assert np.array_equal(vsrlab.evaluate_batch(HILLY, genotypes, seeds), ours)


def test_thread_count_never_changes_fitness(root):
    config = root / "experiments/quickstart.toml"
    g = np.random.default_rng(3).uniform(-1, 1, (64, vsrlab.genotype_length(config)))
    assert np.array_equal(vsrlab.evaluate_batch(config, g, threads=1), vsrlab.evaluate_batch(config, g, threads=2))


def test_the_gil_is_released_during_a_batch(root):
    config = root / "experiments/quickstart.toml"
    g = np.random.default_rng(4).uniform(-1, 1, (100, vsrlab.genotype_length(config)))
    ticks = []
    stop = threading.Event()

    def count():
        while not stop.is_set():
            ticks.append(time.perf_counter())
            time.sleep(0.001)

    t = threading.Thread(target=count)
    t.start()
    time.sleep(0.05)
    start = time.perf_counter()
    vsrlab.evaluate_batch(config, g, threads=1)
    end = time.perf_counter()
    stop.set()
    t.join()
    during = [x for x in ticks if start < x < end]
    assert end - start > 0.2, "the batch is too short to tell"
    # with the GIL held the other thread could not tick at all while Rust runs
    assert len(during) > 0.2 * (end - start) / 0.001 * 0.5, (len(during), end - start)


@pytest.mark.parametrize(
    "genotypes, seeds, pattern",
    [
        (np.zeros((2, 3)), None, "^genotypes: shape \\(2, 3\\) has rows of 3 genes"),
        (np.zeros((2, 2, 45)), None, "^genotypes: a 2-D array"),
        ([["a"] * 45], None, "^genotypes: not an array of numbers"),
        (np.zeros((2, 45)), [1], "^seeds: one seed per genotype"),
        (np.zeros((2, 45)), [-1, 2], "^seeds: non-negative"),
    ],
)
def test_bad_arrays_raise_value_error_naming_the_argument(root, genotypes, seeds, pattern):
    with pytest.raises(ValueError, match=pattern):
        vsrlab.evaluate_batch(root / "experiments/quickstart.toml", genotypes, seeds)


def test_non_finite_genes_and_bad_configs_are_refused(root, tmp_path):
    g = np.zeros((3, 45))
    g[1, 4] = np.nan
    with pytest.raises(ValueError, match="row 1, gene 4 is NaN"):
        vsrlab.evaluate_batch(root / "experiments/quickstart.toml", g)
    with pytest.raises(ValueError, match="no experiment file"):
        vsrlab.evaluate_batch(tmp_path / "missing.toml", g)
    with pytest.raises(ValueError, match="population_size"):
        vsrlab.evaluate_batch(HILLY.replace('kind = "ga"', 'kind = "ga"\npopulation_size = "many"'), g)


def test_the_robot_of_a_genotype_replays_its_fitness_on_the_experiments_task(root, tmp_path):
    config = root / "experiments/quickstart.toml"
    g = np.random.default_rng(9).uniform(-1, 1, (4, vsrlab.genotype_length(config)))
    fitness = vsrlab.evaluate_batch(config, g)
    for row, f in zip(g, fitness):
        robot = vsrlab.robot_of(config, row)
        assert vsrlab.simulate(robot, task=str(config))["fitness"] == [f]
    robot.save(tmp_path / "r.json")
    assert vsrlab.simulate(str(tmp_path / "r.json"), task=str(config))["fitness"] == [fitness[-1]]
    with pytest.raises(ValueError, match="^genotype: one genotype"):
        vsrlab.robot_of(config, g)
