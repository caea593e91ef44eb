"""Shared fixtures: the repository's files and the `vsrlab` binary the Python results are
compared with (VSRLAB_BIN, or target/{release,debug}/vsrlab)."""

from __future__ import annotations

import os
import subprocess
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]


@pytest.fixture(scope="session")
def root() -> Path:
    return ROOT


@pytest.fixture(scope="session")
def vsrlab_bin() -> Path:
    candidates = [os.environ.get("VSRLAB_BIN"), ROOT / "target/release/vsrlab", ROOT / "target/debug/vsrlab"]
    for c in candidates:
        if c and Path(c).is_file():
            return Path(c)
    pytest.fail("no vsrlab binary: build it (cargo build --release) or set VSRLAB_BIN")


def cli(binary: Path, *args: str, stdin: str | None = None) -> str:
    done = subprocess.run([str(binary), *args], input=stdin, capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    return done.stdout
