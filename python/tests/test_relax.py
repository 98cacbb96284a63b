"""xshell.relax reproduces the command line, with and without files."""

import json
import os
import subprocess
import sys
import threading
import time

import numpy as np
import pytest

import xshell
from conftest import SAMPLES, run_program


def read_summary(folder):
    with open(os.path.join(folder, "summary.json")) as f:
        return json.load(f)


def assert_same_run(res, summary):
    """The module's result against a command-line summary.json."""
    assert res.status == summary["status"]
    assert res.reason == summary["reason"]
    assert res.converged == summary["converged"]
    assert res.stable == summary["stable"]
    assert res.iterations == summary["iterations"]
    cli = np.array(summary["vertices"], dtype=float)
    assert res.vertices.shape == cli.shape
    scale = np.abs(cli).max()
    assert np.abs(res.vertices - cli).max() <= 1e-12 * scale
    for key in ("total", "stretching", "bending", "twisting", "external"):
        assert res.energy[key] == pytest.approx(summary["energy"][key], rel=1e-12, abs=1e-300)
    angles = np.array([np.nan if a is None else a for a in summary["opening_angles"]])
    np.testing.assert_array_equal(np.isnan(res.opening_angles), np.isnan(angles))
    ok = ~np.isnan(angles)
    assert np.abs(res.opening_angles[ok] - angles[ok]).max() <= 1e-12 * np.pi


@pytest.mark.parametrize("solver", ["newton", "dynamics"])
def test_relax_reproduces_the_command_line(program, sample_config, tmp_path, solver):
    status, err = run_program(
        program, "relax", sample_config, "--solver", solver, "--out", tmp_path / "cli", "--quiet"
    )
    assert status == 0, err
    summary = read_summary(tmp_path / "cli")
    res = xshell.relax(sample_config, solver=solver)
    assert_same_run(res, summary)
    assert res.exit_status == status
    # The whole summary but for the run's times.
    for key in set(summary) - {"wall_seconds", "timings", "history", "configuration"}:
        assert res.summary[key] == summary[key], key
    assert set(res.summary["timings"]) == set(summary["timings"])
    # The configuration: but for the output folder (--out), the file's.
    del summary["configuration"]["output"]["directory"]
    configuration = dict(res.summary["configuration"])
    assert configuration["output"].pop("directory").endswith("out/grid_gravity")
    assert configuration == summary["configuration"]
    assert len(res.summary["history"]) == len(summary["history"])


def test_out_writes_what_the_command_line_writes(program, sample_config, tmp_path):
    status, err = run_program(program, "relax", sample_config, "--out", tmp_path / "cli", "--quiet")
    assert status == 0, err
    res = xshell.relax(sample_config, out=tmp_path / "py")
    cli_files = sorted(p for p in os.listdir(tmp_path / "cli") if not p.startswith("."))
    py_files = sorted(p for p in os.listdir(tmp_path / "py") if not p.startswith("."))
    assert py_files == cli_files
    assert "summary.json" in py_files and "state.json" in py_files
    written = read_summary(tmp_path / "py")
    assert written["vertices"] == res.summary["vertices"]
    with open(tmp_path / "py" / "state.json") as f:
        assert f.read() == res.state.text


def test_out_none_writes_no_file(sample_config, tmp_path, monkeypatch):
    with open(sample_config) as f:
        cfg = json.load(f)
    cfg["linkage"] = str(SAMPLES / cfg["linkage"])
    cfg["output"] = {"directory": "would_be_written"}
    monkeypatch.chdir(tmp_path)
    res = xshell.relax(cfg)
    assert res.converged
    assert os.listdir(tmp_path) == []


def test_a_dict_runs_as_its_file(sample_config, tmp_path, monkeypatch):
    with open(sample_config) as f:
        cfg = json.load(f)
    from_file = xshell.relax(sample_config)
    # Relative paths in a dict are relative to the working directory.
    monkeypatch.chdir(SAMPLES)
    from_dict = xshell.relax(cfg)
    np.testing.assert_array_equal(from_dict.vertices, from_file.vertices)
    assert from_dict.energy == from_file.energy
    monkeypatch.chdir(tmp_path)
    with pytest.raises(ValueError, match="grid.obj"):
        xshell.relax(cfg)  # no grid.obj here


def test_state_restarts_a_run(sample_config, tmp_path):
    first = xshell.relax(sample_config)
    again = xshell.relax(sample_config, solver="dynamics", init=first.state)
    assert again.converged
    assert again.iterations < first.iterations or again.iterations <= 2
    first.state.save(tmp_path / "state.json")
    loaded = xshell.State.load(tmp_path / "state.json")
    assert loaded == first.state
    from_file = xshell.relax(sample_config, init=loaded)
    # Restarted at the equilibrium: Newton converges at once, where it was.
    assert from_file.converged and from_file.iterations <= 1
    np.testing.assert_allclose(from_file.vertices, first.vertices, rtol=0, atol=1e-9)


def test_rest_lengths_pass_through_a_dict(tmp_path):
    """"rest_lengths" of a dict: a free lath drawn 1 long relaxes to 1.02;
    a count other than the segments' is the command line's error."""
    (tmp_path / "lath.obj").write_text("v 0 0 0\nv 1 0 0\nl 1 2\n")
    cfg = {
        "linkage": str(tmp_path / "lath.obj"),
        "subdivisions": 5,
        "rest_shape": "straight",
        "rest_lengths": [1.02],
        "material": {"young_modulus": 2e4, "cross_section": {"width": 0.01, "height": 0.007}},
        "supports": [{"vertex": 0, "fix": ["position"]}, {"vertex": 1, "fix": ["y", "z"]}],
        "solver": {"gradient_tolerance": 1e-12},
    }
    res = xshell.relax(cfg)
    assert res.converged
    assert abs(res.vertices[1, 0] - 1.02) <= 1e-9
    assert res.summary["configuration"]["rest_lengths"] == [1.02]
    with pytest.raises(ValueError, match="rest_lengths: 2 rest lengths given; the linkage has 1 "):
        xshell.relax(dict(cfg, rest_lengths=[1.0, 1.0]))
    with pytest.raises(ValueError, match="not a JSON configuration"):
        xshell.relax(dict(cfg, rest_lengths=[float("nan")]))


def test_progress_receives_one_dict_per_iteration(sample_config):
    records = []
    res = xshell.relax(sample_config, progress=records.append)
    assert len(records) == len(res.summary["history"]) > 1
    assert [r["iteration"] for r in records] == [h["iteration"] for h in res.summary["history"]]
    assert records[-1]["energy"] == res.summary["history"][-1]["energy"]


def test_the_gil_is_released_during_a_solve(sample_config):
    """While solves run in two threads, the main thread keeps running: its
    loop goes on well inside each solve, away from the moments at its ends
    where the call holds the GIL to convert its arguments and its result. A
    solve that held the GIL would leave no turn of the loop inside it, however
    loaded the machine; a count of turns, not the length of the pauses, so
    that a busy machine's scheduling cannot fail it. The threads find what
    one solve alone finds. The sample's rods are divided finer than its own 8
    edges per segment, so that a solve lasts long enough to tell (0.02 s on
    8, about 0.15 s on 40)."""
    with open(sample_config) as f:
        config = json.load(f)
    config["linkage"] = os.fspath(SAMPLES / config["linkage"])
    config["subdivisions"] = 40
    del config["output"]
    alone = xshell.relax(config)
    results, windows = {}, {}

    def solve(name):
        start = time.perf_counter()
        results[name] = xshell.relax(config)
        windows[name] = (start, time.perf_counter())

    threads = [threading.Thread(target=solve, args=(n,)) for n in ("a", "b")]
    stamps = []
    for t in threads:
        t.start()
    while any(t.is_alive() for t in threads):
        stamps.append(time.perf_counter())
    for t in threads:
        t.join()
    for name in ("a", "b"):
        np.testing.assert_array_equal(results[name].vertices, alone.vertices)
    # Ten times Python's switch interval (5 ms) at each end.
    margin = 10 * sys.getswitchinterval()
    for name, (start, end) in windows.items():
        assert end - start > 3 * margin, ("too short a solve to tell", name, end - start)
        inside = sum(start + margin < s < end - margin for s in stamps)
        assert inside >= 100, (name, inside, end - start)


def test_python_m_xshell_relax(sample_config, tmp_path):
    done = subprocess.run(
        [sys.executable, "-m", "xshell", "relax", str(sample_config), "--out", str(tmp_path), "--quiet"],
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert done.returncode == 0, done.stderr
    assert read_summary(tmp_path)["status"] == "converged"


def test_a_deployment_as_the_command_line_runs_it(program, tmp_path):
    """The deployment's files too (deployment.csv, deployment.png); without
    files, the same summary but for the plot."""
    with open(SAMPLES / "grid_gravity.json") as f:
        cfg = json.load(f)
    cfg["linkage"] = str(SAMPLES / cfg["linkage"])
    start = np.nanmean(xshell.Linkage(cfg).opening_angles)
    cfg["deployment"] = {"average_opening_angle": start + 0.05, "steps": 2}
    (tmp_path / "deploy.json").write_text(json.dumps(cfg))
    status, err = run_program(
        program, "relax", tmp_path / "deploy.json", "--out", tmp_path / "cli", "--quiet"
    )
    assert status == 0, err
    res = xshell.relax(tmp_path / "deploy.json", out=tmp_path / "py")
    cli_files = sorted(p for p in os.listdir(tmp_path / "cli") if not p.startswith("."))
    py_files = sorted(p for p in os.listdir(tmp_path / "py") if not p.startswith("."))
    assert py_files == cli_files and "deployment.csv" in py_files
    assert (tmp_path / "py" / "deployment.csv").read_text() == (
        tmp_path / "cli" / "deployment.csv"
    ).read_text()
    summary = read_summary(tmp_path / "cli")
    assert_same_run(res, summary)
    assert res.summary["deployment"] == summary["deployment"]
    no_files = xshell.relax(tmp_path / "deploy.json")
    assert_same_run(no_files, summary)
    expected = dict(summary["deployment"], plot=None)
    assert no_files.summary["deployment"] == expected
