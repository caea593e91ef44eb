"""The Gymnasium environments: check_env for every registered id, the vectorised environment
equal to single episodes, next-step autoreset, rendering, and bad actions refused."""

import gymnasium
import numpy as np
import pytest
from gymnasium.utils.env_checker import check_env

import vsrlab
import vsrlab.envs
from vsrlab.envs import ENVIRONMENTS


@pytest.mark.parametrize("env_id", sorted(ENVIRONMENTS))
def test_check_env_passes_for_every_registered_environment(env_id):
    env = gymnasium.make(env_id, duration=2.0, render_mode="rgb_array")
    check_env(env.unwrapped, skip_render_check=False)
    obs, _ = env.reset(seed=0)
    assert env.observation_space.contains(obs)
    env.close()


def test_locomotion_takes_body_and_terrain_and_rewards_forward_motion():
    env = gymnasium.make("vsrlab/Locomotion-v0", body="worm-6x2", terrain="hilly-1-10", duration=5.0)
    obs, _ = env.reset(seed=1)
    assert env.action_space.shape == (12,)
    total, t = 0.0, 0
    done = False
    while not done:
        # a travelling wave, the phase brain's actuation
        x = np.arange(12) % 6
        action = np.sin(2 * np.pi * (t / 60.0) + np.pi * x / 6)
        obs, reward, terminated, truncated, info = env.step(action)
        total += reward
        t += 1
        done = terminated or truncated
    # the CLI's episode length in steps (301 for 5 s: time is a float sum of 1/60 s steps, as in the original)
    assert truncated and not terminated and t == vsrlab.simulate(duration=5.0)["steps"]
    # the rewards add up to the task's distance
    assert total > 0 and abs(total - env.unwrapped.metrics()["distance"]) < 1e-9, total
    assert t == 301 and 5.0 <= info["time"] < 5.0 + 1.5 / 60, info["time"]


def test_the_vector_environment_equals_single_episodes():
    robot = vsrlab.Robot("biped-4x3", brain="constant:0")
    vec = vsrlab.VectorEpisode(robot, 3, "locomotion:hilly-1-10", 1.0, 0)
    single = [vsrlab.Episode(robot, "locomotion:hilly-1-10", 1.0, 0) for _ in range(3)]
    obs = vec.reset(40)
    for i, e in enumerate(single):
        assert np.array_equal(obs[i], e.reset(40 + i))
    rng = np.random.default_rng(0)
    for _ in range(30):
        a = rng.uniform(-1, 1, (3, vec.action_size))
        o, r, term, trunc = vec.step(a)
        for i, e in enumerate(single):
            so, sr, st, su = e.step(a[i].copy())
            assert np.array_equal(o[i], so) and r[i] == sr and (term[i], trunc[i]) == (st, su)


def test_make_vec_steps_many_robots_and_resets_at_the_next_step():
    envs = gymnasium.make_vec("vsrlab/Locomotion-v0", num_envs=4, vectorization_mode="vector_entry_point",
                              duration=0.1)
    obs, _ = envs.reset(seed=3)
    assert obs.shape == (4, envs.single_observation_space.shape[0])
    steps = 0
    while True:
        obs, rewards, terminated, truncated, _ = envs.step(envs.action_space.sample())
        steps += 1
        if truncated.all():
            break
    assert steps == vsrlab.simulate(duration=0.1)["steps"]
    first = obs.copy()
    obs, rewards, terminated, truncated, _ = envs.step(envs.action_space.sample())
    assert (rewards == 0).all() and not truncated.any()
    assert not np.array_equal(obs, first)
    envs.close()


def test_rendering_draws_the_robot_moving():
    env = gymnasium.make("vsrlab/Locomotion-v0", duration=3.0, render_mode="rgb_array")
    env.reset(seed=0)
    env.step(np.zeros(10))
    start = env.render()
    for t in range(120):
        env.step(np.full(10, np.sin(t / 5)))
    later = env.render()
    assert start.dtype == np.uint8 and start.ndim == 3 and start.shape[2] == 3
    assert start.shape == later.shape and (start != later).any()


def test_bad_actions_and_arguments_raise_value_error():
    env = gymnasium.make("vsrlab/Locomotion-v0", duration=1.0)
    env.reset(seed=0)
    with pytest.raises(ValueError, match="action: shape"):
        env.step(np.zeros(3))
    with pytest.raises(ValueError, match="finite"):
        env.step(np.full(10, np.nan))
    with pytest.raises(ValueError, match="^body"):
        gymnasium.make("vsrlab/Locomotion-v0", body="blob")
    with pytest.raises(ValueError, match="^task"):
        gymnasium.make("vsrlab/Locomotion-v0", terrain="lava")
    with pytest.raises(ValueError, match="render_mode"):
        vsrlab.envs.SoftRobotEnv(render_mode="human")
