"""EvoGym's robot helpers as vsrlab.evogym offers them (issue 54, item 2): the rules of
evogym/utils.py, checked against cases whose answers are known, and a sampled robot running an
EvoGym task by its gym id, as an EvoGym script would."""

import random

import gymnasium
import numpy as np
import pytest

import vsrlab
from vsrlab import evogym


def test_connectivity_and_actuators_follow_evogyms_rules():
    assert evogym.is_connected(np.array([[1, 3], [0, 2]]))
    assert not evogym.is_connected(np.array([[1, 0], [0, 2]])), "diagonal cells are apart"
    assert not evogym.is_connected(np.zeros((2, 2)))
    assert evogym.has_actuator([[0, 4]]) and not evogym.has_actuator([[1, 2]])
    # a full 2 x 2 body: right neighbours before lower ones, cells in order
    pairs = evogym.get_full_connectivity(np.full((2, 2), 3))
    assert pairs.tolist() == [[0, 0, 1, 2], [1, 2, 3, 3]]
    assert evogym.get_full_connectivity(np.zeros((2, 2))).shape == (2, 0)


def test_sampled_robots_are_valid_repeatable_and_run_an_evogym_task():
    random.seed(3)
    robot, connections = evogym.sample_robot((5, 5))
    random.seed(3)
    again, _ = evogym.sample_robot((5, 5))
    assert (robot == again).all()
    assert robot.shape == (5, 5) and evogym.is_connected(robot) and evogym.has_actuator(robot)
    assert connections.shape[0] == 2 and connections.shape[1] > 0
    only_soft_and_vertical, _ = evogym.sample_robot((3, 4), pd=[0, 0, 1, 0, 1])
    assert set(np.unique(only_soft_and_vertical)) <= {2.0, 4.0}
    env = gymnasium.make("vsrlab-evogym/Jumper-v0", body=robot)
    obs, _ = env.reset(seed=0)
    for _ in range(5):
        obs, reward, terminated, truncated, _ = env.step(env.action_space.sample())
        assert np.isfinite(obs).all() and np.isfinite(reward)


def test_bad_arguments_and_what_is_not_offered_say_so():
    with pytest.raises(ValueError, match="pd: an actuator"):
        evogym.sample_robot((2, 2), pd=[1, 1, 1, 0, 0])
    with pytest.raises(ValueError, match="pd: five"):
        evogym.sample_robot((2, 2), pd=[1, 1])
    with pytest.raises(ValueError, match="robot_shape"):
        evogym.sample_robot((0, 3))
    with pytest.raises(ValueError, match="robot: a 2-D array"):
        evogym.is_connected([1, 2, 3])
    with pytest.raises(NotImplementedError, match="does not offer EvoWorld"):
        evogym.EvoWorld()
    with pytest.raises(NotImplementedError, match="EvoSim"):
        evogym.EvoSim(None)
    assert "Walker-v0" in vsrlab.evogym_tasks()
