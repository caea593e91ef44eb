"""EvoGym's tasks from Python (issue 33): Gymnasium's checker passes for each id, the observation
and action sizes are EvoGym's, and EvoGym's own simulator's reward for a fixed gait is reproduced
(measured side by side with bench/evogym/tasks.py: Walker-v0 +1.172 in 500 steps)."""

import gymnasium
import numpy as np
import pytest
from gymnasium.utils.env_checker import check_env

import vsrlab
from vsrlab.envs import EVOGYM_ENVIRONMENTS

FULL = "33333/33333/33333/33333/33333"


@pytest.mark.parametrize("env_id", sorted(EVOGYM_ENVIRONMENTS))
def test_check_env_passes_for_every_evogym_task(env_id):
    env = gymnasium.make(env_id)
    check_env(env.unwrapped, skip_render_check=True)
    env.close()


@pytest.mark.parametrize(
    "env_id,observations",
    [
        ("vsrlab/Walker-v0", 74),
        ("vsrlab/BridgeWalker-v0", 75),
        ("vsrlab/BeamToppler-v0", 79),
        ("vsrlab/CaveCrawler-v0", 96),
        ("vsrlab/Jumper-v0", 79),
        ("vsrlab/Balancer-v0", 73),
        ("vsrlab/Balancer-v1", 73),
        ("vsrlab/Climber-v0", 74),
        ("vsrlab/Climber-v1", 74),
        ("vsrlab/Climber-v2", 82),
        ("vsrlab/UpStepper-v0", 86),
        ("vsrlab/GapJumper-v0", 86),
        ("vsrlab/Flipper-v0", 73),
        ("vsrlab/AreaMaximizer-v0", 72),
        ("vsrlab/Lifter-v0", 79),
        ("vsrlab-evogym/Carrier-v0", 78),
        ("vsrlab/Traverser-v0", 86),
        ("vsrlab/BidirectionalWalker-v0", 77),
    ],
)
def test_sizes_are_evogyms_for_a_full_5x5_body(env_id, observations):
    env = gymnasium.make(env_id, body=np.full((5, 5), 3))
    assert env.observation_space.shape == (observations,)
    assert env.action_space.shape == (25,)
    assert (env.action_space.low == 0.6).all() and (env.action_space.high == 1.6).all()


def test_a_square_wave_gait_earns_evogyms_reward_on_walker():
    env = gymnasium.make("vsrlab/Walker-v0", body=FULL)
    env.reset(seed=0)
    total, steps, done = 0.0, 0, False
    while not done:
        action = np.array([1.6 if (steps + 5 * (i % 5)) % 20 < 10 else 0.6 for i in range(25)])
        _, reward, terminated, truncated, info = env.step(action)
        total, steps, done = total + reward, steps + 1, terminated or truncated
    assert steps == 500 and truncated and not info["unstable"]
    # EvoGym 2.0.0's own simulator gives +1.172 for this robot and gait
    assert abs(total - 1.172) < 0.002, total


def test_every_implemented_task_is_a_gym_id_with_its_class():
    tasks = vsrlab.evogym_tasks()
    assert {"Walker-v0", "Jumper-v0", "Balancer-v1", "Climber-v1", "WingspanMazimizer-v0"} <= set(tasks)
    assert len(tasks) == 32
    assert {f"vsrlab-evogym/{t}" for t in tasks} <= set(EVOGYM_ENVIRONMENTS)
    assert vsrlab.envs.BalancerV1Env().unwrapped._env.observation_size == 73
    assert f"vsrlab/{tasks[-1]}" in gymnasium.registry
    # vsrlab's own carrier task keeps vsrlab/Carrier-v0; EvoGym's is under vsrlab-evogym/
    assert EVOGYM_ENVIRONMENTS["vsrlab-evogym/Carrier-v0"] == "EvoGymCarrierEnv"
    assert "vsrlab/Carrier-v0" not in EVOGYM_ENVIRONMENTS
    assert gymnasium.make("vsrlab-evogym/Carrier-v0").observation_space.shape == (78,)
    assert vsrlab.envs.CarrierEnv is not vsrlab.envs.EvoGymCarrierEnv


def test_catchers_world_follows_the_seed():
    env = gymnasium.make("vsrlab/Catcher-v0")
    first = [env.reset(seed=s)[0] for s in range(4)]
    again = [env.reset(seed=s)[0] for s in range(4)]
    assert all(np.array_equal(a, b) for a, b in zip(first, again))
    # the package's offset from the robot (the first two values) moves with the drawn world
    assert len({tuple(o[:2]) for o in first}) > 1
    assert env.observation_space.shape == (79,)


def test_rgb_array_frames_are_drawn_without_opengl():
    env = gymnasium.make("vsrlab/Walker-v0", render_mode="rgb_array")
    env.reset(seed=0)
    first = env.render()
    assert first.dtype == np.uint8 and first.ndim == 3 and first.shape[2] == 3
    # the robot's horizontal actuators are drawn in EvoGym's orange (0xfd8e3e)
    orange = np.all(np.abs(first.astype(int) - [0xFD, 0x8E, 0x3E]) < 8, axis=2)
    assert orange.sum() > 100, orange.sum()
    for t in range(40):
        env.step(np.array([1.6 if (t + 5 * (i % 5)) % 20 < 10 else 0.6 for i in range(25)]))
    assert not np.array_equal(env.render(), first)
    plain = gymnasium.make("vsrlab/Walker-v0")
    plain.reset(seed=0)
    assert plain.render() is None
    with pytest.raises(ValueError, match="render_mode"):
        vsrlab.envs.WalkerEnv(render_mode="screen")


def test_vector_environments_step_every_core_with_the_bits_of_single_ones():
    n, body = 6, "33333/33333/33333"
    vec = gymnasium.make_vec("vsrlab-evogym/Catcher-v0", num_envs=n, vectorization_mode="vector_entry_point", body=body)
    assert type(vec).__name__ == "CatcherVectorEnv"
    singles = [gymnasium.make("vsrlab-evogym/Catcher-v0", body=body).unwrapped for _ in range(n)]
    obs, _ = vec.reset(seed=10)
    for i, env in enumerate(singles):
        assert np.array_equal(obs[i], env.reset(seed=10 + i)[0])
    rng = np.random.default_rng(0)
    for t in range(400):
        actions = rng.uniform(0.6, 1.6, size=(n, 15))
        obs, rewards, terminated, truncated, info = vec.step(actions)
        for i, env in enumerate(singles):
            o, r, term, trunc, single_info = env.step(actions[i])
            assert np.array_equal(obs[i], o) and rewards[i] == r, (t, i)
            assert (terminated[i], truncated[i], info["unstable"][i]) == (term, trunc, single_info["unstable"])
    assert truncated.all(), "Catcher's episodes last 400 steps"
    # next-step autoreset: the action is ignored, each environment starts its next episode
    obs, rewards, terminated, truncated, _ = vec.step(np.ones((n, 15)))
    assert (rewards == 0).all() and not truncated.any()
    for i, env in enumerate(singles):
        assert np.array_equal(obs[i], env.reset(seed=10 + i + n)[0])
    with pytest.raises(ValueError, match="actions: shape"):
        vec.step(np.ones((n, 3)))


def test_bad_bodies_and_actions_are_refused_naming_the_field():
    with pytest.raises(ValueError, match="body"):
        vsrlab.EvoGymEnv("Walker-v0", "1.3")
    with pytest.raises(ValueError, match="task: unknown EvoGym task 'Runner-v0': expected one of Walker-v0"):
        vsrlab.EvoGymEnv("Runner-v0", FULL)
    env = vsrlab.EvoGymEnv("Walker-v0", "131")
    env.reset()
    with pytest.raises(ValueError, match="actions"):
        env.step(np.ones(3))
    with pytest.raises(ValueError, match="actions"):
        env.step(np.array([np.nan]))
