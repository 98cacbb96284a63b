"""xshell.design: the inverse design from Python, the same run as `xshell design`."""

import json

import numpy as np
import pytest

import xshell

from conftest import run_program


def dome_files(folder, n=3, k=0.8):
    """An n x n grid on the dome z = -k r^2 (stress-free as drawn) and a
    target 5% higher in the middle: (linkage path, target path)."""
    half = 0.5 * (n - 1) * 0.25
    vertices = [(-half + 0.25 * j, -half + 0.25 * i) for i in range(n) for j in range(n)]
    lines = ["v %r %r %r" % (x, y, -k * (x * x + y * y)) for x, y in vertices]
    for i in range(n):
        for j in range(n):
            v = i * n + j + 1
            if j + 1 < n:
                lines.append("l %d %d" % (v, v + 1))
            if i + 1 < n:
                lines.append("l %d %d" % (v, v + n))
    (folder / "dome.obj").write_text("\n".join(lines) + "\n")
    return folder / "dome.obj"


def dome_config(folder):
    linkage = dome_files(folder)
    surface = folder / "surface.obj"
    m, size, k = 9, 0.8, 1.05
    lines = []
    for i in range(m):
        for j in range(m):
            x, y = -size + 2 * size * j / (m - 1), -size + 2 * size * i / (m - 1)
            lines.append("v %r %r %r" % (x, y, -k * (x * x + y * y)))
    for i in range(m - 1):
        for j in range(m - 1):
            a = i * m + j + 1
            lines.append("f %d %d %d" % (a, a + 1, a + m + 1))
            lines.append("f %d %d %d" % (a, a + m + 1, a + m))
    surface.write_text("\n".join(lines) + "\n")
    return {
        "linkage": str(linkage),
        "subdivisions": 5,
        "rest_shape": "input",
        "material": {"young_modulus": 2e10, "cross_section": {"width": 0.01, "height": 0.007}},
        "supports": [{"vertex": 4, "fix": ["position", "orientation"]}],
        "design": {
            "average_opening_angle": 1.8,
            "target_surface": str(surface),
            "max_iterations": 8,
        },
    }


def test_design_reports_its_iterations_and_matches_the_command_line(tmp_path, program):
    config = dome_config(tmp_path)
    records = []
    res = xshell.design(config, progress=records.append)
    assert res.status in ("converged", "max_iterations")
    assert res.exit_status in (0, 3)
    assert len(records) == len(res.history) == res.iterations + 1
    assert [r["iteration"] for r in records] == list(range(res.iterations + 1))
    assert res.fit["targets"] == 9
    assert res.history[-1]["fit_rms"] < res.history[0]["fit_rms"]
    assert res.rest_lengths.shape == (12,)
    assert "xshell.DesignResult" in repr(res)
    # No file without `out`; the command line's run gives the same design.
    assert not (tmp_path / "out").exists()
    (tmp_path / "design.json").write_text(json.dumps(config))
    status, err = run_program(program, "design", "design.json", "--out", "cli", cwd=tmp_path)
    assert status == res.exit_status, err
    cli = json.loads((tmp_path / "cli" / "design.json").read_text())
    np.testing.assert_allclose(cli["rest_lengths"], res.rest_lengths, rtol=1e-12)


def test_design_writes_its_outputs_and_states(tmp_path):
    config = dome_config(tmp_path)
    config["design"]["max_iterations"] = 2
    res = xshell.design(config, out=tmp_path / "result")
    for name in ("design.json", "deployed_state.json", "flat_state.json", "flat_layout.obj"):
        assert (tmp_path / "result" / name).exists(), name
    assert json.loads((tmp_path / "result" / "design.json").read_text()) == res.report
    # The flat state is a state of the same linkage: it starts a relax run.
    relaxed = xshell.relax(dict(config, rest_lengths=list(res.rest_lengths)), init=res.flat_state)
    assert relaxed.converged


def test_design_refuses_bad_inputs(tmp_path):
    config = dome_config(tmp_path)
    del config["design"]
    with pytest.raises(ValueError, match='needs a "design" section'):
        xshell.design(config)
    config = dome_config(tmp_path)
    config["design"]["bounds"] = 2
    with pytest.raises(ValueError, match="design.bounds"):
        xshell.design(config)
