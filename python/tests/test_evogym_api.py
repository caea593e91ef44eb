"""EvoGym's robot helpers as vsrlab.evogym offers them (issue 54, item 2): the rules of
evogym/utils.py, checked against cases whose answers are known, and a sampled robot running an
EvoGym task by its gym id, as an EvoGym script would."""

import json
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
    assert "Walker-v0" in vsrlab.evogym_tasks()
    assert sorted(evogym.BASELINE_ENV_NAMES) == sorted(vsrlab.evogym_tasks()) and len(evogym.BASELINE_ENV_NAMES) == 32
    random.seed(1)
    assert evogym.draw([0, 15]) == 1 and evogym.draw([0.2, 0]) == 0
    assert np.allclose(evogym.get_uniform(4), 0.25)


#: A world file as EvoGym's design tool writes one: a 10-cell fixed floor (row 0) and a 2 x 1 soft
#: box on it at (6, 1).
WORLD = {
    "grid_width": 10,
    "grid_height": 4,
    "objects": {
        "ground": {
            "indices": list(range(10)),
            "types": [5] * 10,
            "neighbors": {str(i): [j for j in (i - 1, i + 1) if 0 <= j < 10] for i in range(10)},
        },
        "box": {"indices": [16, 17], "types": [2, 2], "neighbors": {"16": [17], "17": [16]}},
    },
}


def write(tmp_path, doc, name="world.json"):
    path = tmp_path / name
    path.write_text(json.dumps(doc))
    return str(path)


def test_a_world_from_a_file_and_a_robot_simulate_and_draw(tmp_path, capsys):
    world = evogym.EvoWorld.from_json(write(tmp_path, WORLD))
    assert sorted(world.objects) == ["box", "ground"]
    assert world.objects["box"].get_pos() == (6, 1) and world.objects["box"].get_structure().tolist() == [[2, 2]]
    robot = np.array([[3, 3], [3, 3]])
    world.add_from_array("robot", robot, x=1, y=1)
    world.pretty_print()
    printed = capsys.readouterr().out
    assert "H H" in printed and "S S" in printed and "F F" in printed
    with pytest.raises(ValueError, match="overlaps"):
        world.add_from_array("other", np.array([[1]]), x=6, y=1)
    with pytest.raises(ValueError, match="overlap"):
        world.move_object("robot", 5, 1)
    assert world.objects["robot"].get_pos() == (1, 1), "a refused move leaves the object in place"

    sim = evogym.EvoSim(world)
    assert sim.get_dim_action_space("robot") == 4
    assert sim.get_actuator_indices("robot").tolist() == [0, 1, 2, 3]
    start = sim.object_pos_at_time(0, "robot")
    # in cells: the robot's 3 x 3 points span x 1 … 3 and y 1 … 3
    assert start.shape == (2, 9) and start[0].min() == pytest.approx(1) and start[1].max() == pytest.approx(3)
    for t in range(40):
        sim.set_action("robot", np.full(4, 1.6 if t % 10 < 5 else 0.6))
        assert sim.step() is False
    assert sim.get_time() == 40
    moved = sim.object_pos_at_time(40, "robot")
    assert not np.allclose(moved, start)
    assert sim.pos_at_time(40).shape[0] == 2 and np.isfinite(sim.vel_at_time(40)).all()
    assert np.isfinite(sim.object_orientation_at_time(40, "box"))
    with pytest.raises(ValueError, match="only the current state"):
        sim.object_pos_at_time(3, "robot")
    with pytest.raises(ValueError, match="not a valid robot name"):
        sim.set_action("box", np.ones(2))
    with pytest.raises(ValueError, match="expected action with 4 values"):
        sim.set_action("robot", np.ones(3))
    viewer = evogym.EvoViewer(sim)
    viewer.track_objects("robot", "box")
    frame = viewer.render("img")
    assert frame.dtype == np.uint8 and frame.ndim == 3 and frame.shape[2] == 3
    with pytest.raises(NotImplementedError, match="OpenGL"):
        viewer.render("screen")
    sim.reset()
    assert sim.get_time() == 0 and np.array_equal(sim.object_pos_at_time(0, "robot"), start)


def test_malformed_world_files_name_the_file_and_the_field(tmp_path):
    cases = [
        ({k: v for k, v in WORLD.items() if k != "objects"}, "objects"),
        ({**WORLD, "grid_width": 0}, "grid_width"),
    ]
    unknown = json.loads(json.dumps(WORLD))
    unknown["objects"]["box"]["types"] = [2, 9]
    cases.append((unknown, "objects.box.types[1]"))
    apart = json.loads(json.dumps(WORLD))
    apart["objects"]["box"]["neighbors"] = {"16": [19], "17": [16]}
    cases.append((apart, "objects.box.neighbors.16[0]"))
    overlapping = json.loads(json.dumps(WORLD))
    overlapping["objects"]["box"]["indices"] = [9, 16]
    overlapping["objects"]["box"]["neighbors"] = {"9": [], "16": []}
    cases.append((overlapping, "objects.box"))
    for k, (doc, field) in enumerate(cases):
        path = write(tmp_path, doc, f"bad{k}.json")
        with pytest.raises(ValueError) as e:
            evogym.EvoWorld.from_json(path)
        assert path in str(e.value) and field in str(e.value), str(e.value)
    with pytest.raises(ValueError, match="world: an EvoWorld"):
        evogym.EvoSim(None)
