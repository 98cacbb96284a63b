"""Shared fixtures of the Python module's tests (run by CTest: tests/CMakeLists.txt
sets PYTHONPATH to the build's module folder and the paths below).

A test file whose every test was skipped (the shared data folder is absent)
ends with status 77, which CTest reports as skipped, as the C++ tests do
(tests/skip.hpp)."""

import os
import pathlib
import shutil
import subprocess

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
SAMPLES = pathlib.Path(os.environ.get("XSHELL_SAMPLES_DIR", ROOT / "samples"))
# The same folder as the C++ tests' XSHELL_SHARED_DATA_DIR: ../shared/data/elasticrods
# beside the clone.
SHARED_DATA = pathlib.Path(
    os.environ.get("XSHELL_SHARED_DATA_DIR", ROOT.parent / "shared" / "data" / "elasticrods")
)
SKIP_CODE = 77


@pytest.fixture
def sample_config():
    return SAMPLES / "grid_gravity.json"


@pytest.fixture
def program():
    """The command-line program of the same build (XSHELL_PROGRAM), to compare with."""
    path = os.environ.get("XSHELL_PROGRAM") or shutil.which("xshell")
    if not path or not os.path.exists(path):
        pytest.skip("the xshell program is not built (XSHELL_PROGRAM unset)")
    return path


def run_program(program, *args, cwd=None):
    """Runs the command-line program; returns (status, stderr)."""
    done = subprocess.run(
        [program, *map(str, args)], cwd=cwd, capture_output=True, text=True, timeout=120
    )
    return done.returncode, done.stderr


@pytest.fixture
def shared_data():
    if not SHARED_DATA.is_dir():
        pytest.skip("%s is absent" % SHARED_DATA)
    return SHARED_DATA


def pytest_sessionfinish(session, exitstatus):
    reporter = session.config.pluginmanager.get_plugin("terminalreporter")
    if reporter is None or exitstatus != 0:
        return
    ran = sum(len(reporter.stats.get(k, [])) for k in ("passed", "failed", "error"))
    if ran == 0 and reporter.stats.get("skipped"):
        session.exitstatus = SKIP_CODE
