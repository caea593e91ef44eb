"""Robots, robot files and single episodes from Python: the CLI's strings and files, the CLI's
outcomes, and ValueError naming the field for bad input."""

import json

import pytest

import vsrlab
from conftest import cli


def test_short_forms_build_both_kinds(root):
    r = vsrlab.Robot("biped-4x3", brain="mlp")
    assert (r.kind, r.brain, r.body) == ("voxel", "mlp", "####/####/#..#")
    p = vsrlab.Robot("psa:small")
    assert (p.kind, p.brain, p.body) == ("psa", "heads", None)
    assert "psa with" in repr(p)


@pytest.mark.parametrize(
    "kwargs, field",
    [
        ({"body": "blob-3"}, "body"),
        ({"body": "biped-4x3", "brain": "neat"}, "brain"),
        ({"body": "biped-4x3", "sensors": "uniform-zz-0"}, "sensors"),
        ({"body": "biped-4x3", "preset": "1999"}, "preset"),
        ({"body": "psa", "sensors": "uniform-a-0"}, "sensors"),
    ],
)
def test_bad_short_forms_raise_value_error_naming_the_field(kwargs, field):
    with pytest.raises(ValueError, match=f"^{field}"):
        vsrlab.Robot(**kwargs)


def test_robot_files_round_trip_and_bad_files_are_refused(tmp_path, root):
    example = vsrlab.load_robot(root / "examples/biped-distributed.robot.json")
    path = tmp_path / "copy.robot.json"
    example.save(str(path), note="copied from Python")
    again = vsrlab.load_robot(path)
    assert json.loads(again.to_json())["robot"] == json.loads(example.to_json())["robot"]
    assert json.loads(path.read_text())["note"] == "copied from Python"
    assert vsrlab.simulate(again, duration=3) == vsrlab.simulate(example, duration=3)
    (tmp_path / "bad.json").write_text('{"format": "vsrlab-robot/1", "body": 3}')
    with pytest.raises(ValueError, match="bad.json"):
        vsrlab.load_robot(tmp_path / "bad.json")
    with pytest.raises(ValueError):
        vsrlab.Robot.from_json("not json")


def test_simulate_gives_the_clis_outcome(root, vsrlab_bin):
    robot_file = root / "examples/biped-distributed.robot.json"
    ours = vsrlab.simulate(str(robot_file), task="locomotion:hilly-1-10", duration=10, seed=3)
    theirs = json.loads(
        cli(vsrlab_bin, "simulate", "--robot", str(robot_file), "--task", "locomotion:hilly-1-10",
            "--duration", "10", "--seed", "3", "--json")
    )
    assert ours["distance"] == theirs["distance"]
    assert ours["velocity"] == theirs["velocity"]
    assert ours["steps"] == theirs["steps"]
    assert ours["fitness"] == [theirs["velocity"]]


def test_the_example_biped_walks_and_a_psa_runs_its_tasks(tmp_path, root):
    walk = vsrlab.simulate(str(root / "examples/biped-distributed.robot.json"), duration=30)
    assert walk["distance"] > 150, walk
    out = vsrlab.simulate(vsrlab.Robot("psa:small"), task="escape", duration=2, video=tmp_path / "e.png")
    assert set(out) >= {"fitness", "steps", "units"} and (tmp_path / "e.png").stat().st_size > 1000


@pytest.mark.parametrize(
    "kwargs, pattern",
    [
        ({"task": "swim"}, "^task: unknown task"),
        ({"task": "locomotion:lava"}, "^task"),
        ({"duration": -1.0}, "duration"),
        ({"robot": 3}, "^robot"),
        ({"task": "nowhere.toml"}, "^task"),
    ],
)
def test_bad_simulate_arguments_raise_value_error(kwargs, pattern):
    with pytest.raises(ValueError, match=pattern):
        vsrlab.simulate(**kwargs)


def test_an_evogym_short_form_takes_the_observation_of_the_task_it_runs(vsrlab_bin, tmp_path):
    # issue 56, item 7: Python's simulate kept Walker-v0's observation and refused BridgeWalker
    body = "evogym:33333/33333/33333/33333/33333"
    ours = vsrlab.simulate(body, task="bridge-walker", duration=0.03)
    out = cli(vsrlab_bin, "simulate", "--body", body, "--task", "bridge-walker", "--duration", "0.03", "--json")
    assert json.loads(out)["reward"] == ours["reward"] and ours["steps"] == 10
    # a robot file keeps its brain: weights made for Walker-v0 are refused on BridgeWalker
    path = tmp_path / "walker.json"
    vsrlab.Robot(body).save(path)
    with pytest.raises(ValueError, match="robot.env"):
        vsrlab.simulate(str(path), task="bridge-walker", duration=0.03)


def test_short_forms_of_every_kind_take_their_kinds_defaults(vsrlab_bin):
    # issue 56, item 1: simulate() gave every body the voxel robots' preset 2021
    evogym = vsrlab.simulate("evogym:33333/33333/33333/33333/33333", task="walker", duration=0.2)
    assert evogym["steps"] > 0 and len(evogym["fitness"]) == 1
    cube = vsrlab.simulate("3d:quadruped", task="locomotion3d", duration=0.05)
    assert cube["steps"] > 0
    # the same outcome as the command line, which passes no preset either
    out = cli(vsrlab_bin, "simulate", "--body", "3d:quadruped", "--task", "locomotion3d", "--duration", "0.05", "--json")
    assert json.loads(out)["distance"] == cube["distance"]
    # a voxel robot keeps its kind's default, 2021, and a preset given to another kind is refused
    assert vsrlab.simulate("biped-4x3", duration=1)["fitness"] == vsrlab.simulate("biped-4x3", duration=1, preset="2021")["fitness"]
    with pytest.raises(ValueError, match="preset"):
        vsrlab.simulate("3d:quadruped", task="locomotion3d", duration=0.05, preset="2021")
    # a 3D body in the 2D locomotion environment: told which task it runs in, not about a preset
    import gymnasium

    with pytest.raises(ValueError, match="locomotion3d"):
        gymnasium.make("vsrlab/Locomotion-v0", body="3d:quadruped")
