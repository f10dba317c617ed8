"""Fixtures of the Python tests: the command-line binary (the second front the package is
compared with), the shipped instance, and a scratch directory."""

import json
import os
import pathlib
import subprocess

import pytest

import swarmplan

REPO = pathlib.Path(__file__).resolve().parents[2]


@pytest.fixture(scope="session")
def cli():
    """Runs the `swarmplan` binary of this checkout (built once by cargo; SWARMPLAN_BIN
    overrides) and returns its completed process."""
    binary = os.environ.get("SWARMPLAN_BIN")
    if not binary:
        subprocess.run(
            ["cargo", "build", "--release", "--locked", "--bin", "swarmplan"],
            cwd=REPO,
            check=True,
        )
        target = os.environ.get("CARGO_TARGET_DIR", str(REPO / "target"))
        binary = str(pathlib.Path(target) / "release" / "swarmplan")

    def run(*args, check=True):
        out = subprocess.run([binary, *map(str, args)], capture_output=True, text=True)
        if check and out.returncode != 0:
            raise AssertionError(f"swarmplan {' '.join(map(str, args))}: {out.stderr}")
        return out

    return run


@pytest.fixture(scope="session")
def cli_json(cli):
    """The JSON a command prints."""

    def run(*args):
        return json.loads(cli(*args).stdout)

    return run


@pytest.fixture(scope="session")
def paper():
    return swarmplan.Instance.embedded("paper-195")


def without_times(value):
    """A document without its wall-clock measurements (`execution_ms`, `solve_ms`, `ms`)."""
    if isinstance(value, dict):
        return {
            k: without_times(v)
            for k, v in value.items()
            if k not in ("execution_ms", "solve_ms", "ms", "elapsed_s")
        }
    if isinstance(value, list):
        return [without_times(v) for v in value]
    return value
