"""Shared fixtures of the Python tests (run by CTest as python.pytest, label python:
PYTHONPATH=build/python python3 -m pytest -q tests/python).

Environment (set by tests/CMakeLists.txt; defaults for a manual run from the source tree):
    RHABEL_SOURCE_DIR  the source tree (default: two levels above this file)
    RHABEL_BINARY_DIR  the build tree (default: SOURCE/build)
    RHABEL_CLI         the command-line program (default: BINARY/bin/rhabel; tests skip without it)
"""

import contextlib
import os
import pathlib
import signal
import threading
import time

import pytest

SOURCE_DIR = pathlib.Path(os.environ.get("RHABEL_SOURCE_DIR", pathlib.Path(__file__).resolve().parents[2]))
BINARY_DIR = pathlib.Path(os.environ.get("RHABEL_BINARY_DIR", SOURCE_DIR / "build"))
CLI = pathlib.Path(os.environ.get("RHABEL_CLI", BINARY_DIR / "bin" / "rhabel"))

# Tolerances (named, with the reason):
EPS = 2.220446049250313e-16
SOLVE_TOLERANCE = 1e-12  # rhabel.solve's default relative tolerance of the edge roots and expansions


@pytest.fixture(scope="session")
def cli():
    """Path of the command-line program; skips the test when it was not built."""
    if not CLI.is_file() or not os.access(CLI, os.X_OK):
        pytest.skip(f"the command line {CLI} is not built (cmake --build build --target rhabel_cli)")
    return CLI


def parabola_scene(alpha=0.3, nu=0.5, coulomb=0.0, radius=0.02, load=100.0, apex=0.0, E1=1.0e6, speed=0.01):
    return {"material": {"alpha": alpha, "E1": E1, "nu": nu, "coulomb": coulomb},
            "speed": speed,
            "indentors": [{"shape": "parabolic", "radius": radius, "load": load, "apex": apex}]}


@contextlib.contextmanager
def sigint_after(seconds):
    """Sends this process SIGINT (Ctrl-C) `seconds` into the block, which must raise
    KeyboardInterrupt; yields a list that then holds the moment the signal was sent
    (time.monotonic()), so that the test can bound how long the interruption took."""
    sent = []

    def interrupt():
        sent.append(time.monotonic())
        os.kill(os.getpid(), signal.SIGINT)

    timer = threading.Timer(seconds, interrupt)
    timer.start()
    try:
        with pytest.raises(KeyboardInterrupt):
            yield sent
    finally:
        timer.cancel()
