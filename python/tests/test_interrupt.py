"""Ctrl-C during a solve stops it at its next iteration: the interrupted
run's outputs are written, then KeyboardInterrupt is raised."""

import _thread
import json
import os
import signal
import threading
import time

import pytest

import xshell
from conftest import SAMPLES


def long_run():
    """Kinetic damping to a tolerance below its round-off floor: about 10 s
    of iterations before its stagnation test ends it (a few seconds more on
    a loaded machine; at 8 subdivisions, 1.7 s), so that a test whose
    interrupt does not stop it fails in seconds, not by a timeout."""
    with open(SAMPLES / "grid_gravity.json") as f:
        cfg = json.load(f)
    cfg["linkage"] = str(SAMPLES / cfg["linkage"])
    cfg["subdivisions"] = 16
    cfg["solver"] = {"method": "kinetic-damping", "gradient_tolerance": 1e-13, "max_steps": 100000}
    cfg["output"] = {"every": 1000}
    return cfg


def interrupt_during_solve(send, tmp_path):
    records = []
    timer = threading.Timer(0.5, send)
    start = time.perf_counter()
    timer.start()
    try:
        with pytest.raises(KeyboardInterrupt):
            xshell.relax(long_run(), out=tmp_path, progress=records.append)
    finally:
        timer.cancel()
    elapsed = time.perf_counter() - start
    assert elapsed < 5.0
    assert records, "the solve never started"
    with open(tmp_path / "summary.json") as f:
        summary = json.load(f)
    assert summary["status"] == "interrupted" and summary["interrupted"] is True
    assert summary["reason"] == "interrupted by a signal"
    assert os.path.exists(tmp_path / "state.json")


def test_interrupt_from_another_thread(tmp_path):
    interrupt_during_solve(_thread.interrupt_main, tmp_path)


def test_interrupt_by_a_signal(tmp_path):
    interrupt_during_solve(lambda: os.kill(os.getpid(), signal.SIGINT), tmp_path)


def test_the_run_is_long_without_an_interrupt():
    """The run above does not end by itself within the time the tests allow it."""
    records = []

    class Enough(Exception):
        pass

    def progress(record):
        records.append(record)
        if time.perf_counter() - start > 1.5:
            raise Enough()

    start = time.perf_counter()
    with pytest.raises(Enough):
        xshell.relax(long_run(), progress=progress)
    # The exception stopped the solve at once.
    assert time.perf_counter() - start < 3.0
