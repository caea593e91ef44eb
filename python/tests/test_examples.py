"""The examples run as documented (with a small budget) and write a robot that replays."""

import subprocess
import sys

import pytest

import vsrlab


@pytest.mark.parametrize(
    "script, args",
    [
        ("evolve_biped.py", ["--generations", "3", "--population", "8"]),
        ("pycma_biped.py", ["--evaluations", "30"]),
    ],
)
def test_example_evolves_and_saves_a_robot(root, tmp_path, script, args):
    out = tmp_path / "best.robot.json"
    done = subprocess.run(
        [sys.executable, str(root / "python/examples" / script), *args, "--out", str(out)],
        capture_output=True, text=True, cwd=tmp_path, timeout=300,
    )
    assert done.returncode == 0, done.stderr
    assert out.is_file(), done.stdout
    robot = vsrlab.load_robot(out)
    assert robot.kind == "voxel" and robot.body == "####/####/#..#"
    assert vsrlab.simulate(robot, duration=2)["steps"] > 100


def test_the_readmes_python_lines_run(root, monkeypatch):
    """Every line of the README's Python block, in the repository (the Ray line needs a cluster:
    tests/test_ray.py covers it)."""
    text = (root / "README.md").read_text()
    block = text.split("```python\n", 1)[1].split("```", 1)[0]
    lines = [line for line in block.splitlines() if "ray=" not in line]
    assert len(lines) >= 4
    monkeypatch.chdir(root)
    scope: dict = {}
    for line in lines:
        exec(line, scope)
    assert scope["fitness"].shape == (200,)
    assert scope["env"].action_space.shape == (12,)
