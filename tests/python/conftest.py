"""pytest setup for the Python package's tests (run from CTest: tests/python/CMakeLists.txt).

PKMOPT_SOURCE_DIR and PKMOPT_CLI (the `pkmopt` program the results are compared with) come
from the environment CTest sets; PYTHONPATH points at build/python.
"""

import os
import subprocess

import pytest

SOURCE = os.environ.get("PKMOPT_SOURCE_DIR",
                        os.path.abspath(os.path.join(os.path.dirname(__file__), "..", "..")))
CLI = os.environ.get("PKMOPT_CLI", os.path.join(SOURCE, "build", "bin", "pkmopt"))


def source(*parts):
    return os.path.join(SOURCE, *parts)


def run_cli(*args, check=True, cwd=None):
    """Runs `pkmopt ARGS...` and returns (exit status, stdout, stderr)."""
    p = subprocess.run([CLI, *args], capture_output=True, text=True, cwd=cwd)
    if check and p.returncode != 0:
        raise AssertionError(f"pkmopt {' '.join(args)} exited {p.returncode}: {p.stderr}")
    return p.returncode, p.stdout, p.stderr


def cli_error(*args):
    """The message `pkmopt ARGS...` prints for bad input (exit status 2), without its prefix."""
    code, _, err = run_cli(*args, check=False)
    assert code == 2, (code, err)
    line = err.strip()
    assert line.startswith("pkmopt: error: "), line
    return line[len("pkmopt: error: "):]


@pytest.fixture
def hexapod():
    import pkmopt
    return pkmopt.load_machine(source("examples", "hexapod.yaml"))
