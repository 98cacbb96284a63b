"""Invalid inputs raise ValueError with the command line's message."""

import json

import pytest

import xshell
from conftest import SAMPLES, run_program


def cli_error(program, *args):
    """The command line's message for a rejected input, without "xshell: error: "."""
    status, err = run_program(program, "relax", *args)
    assert status == 2, err
    line = [l for l in err.splitlines() if l.startswith("xshell: error: ")]
    assert len(line) == 1, err
    return line[0][len("xshell: error: ") :]


def write_config(path, **changes):
    with open(SAMPLES / "grid_gravity.json") as f:
        cfg = json.load(f)
    cfg["linkage"] = str(SAMPLES / cfg["linkage"])
    cfg.update(changes)
    path.write_text(json.dumps(cfg))
    return cfg


def test_bad_key(program, tmp_path):
    cfg = write_config(tmp_path / "bad.json", subdivison=8)
    expected = cli_error(program, tmp_path / "bad.json", "--out", tmp_path / "out")
    assert "subdivison" in expected and "subdivisions" in expected
    with pytest.raises(ValueError) as e:
        xshell.relax(tmp_path / "bad.json")
    assert str(e.value) == expected
    # A dict is named "<dict>" where the command line names the file.
    with pytest.raises(ValueError) as e:
        xshell.relax(cfg)
    assert str(e.value) == expected.replace(str(tmp_path / "bad.json"), "<dict>")
    with pytest.raises(ValueError) as e:
        xshell.Linkage(cfg)
    assert str(e.value) == expected.replace(str(tmp_path / "bad.json"), "<dict>")


def test_bad_value(program, tmp_path):
    write_config(tmp_path / "bad.json", subdivisions=1)
    expected = cli_error(program, tmp_path / "bad.json", "--out", tmp_path / "out")
    with pytest.raises(ValueError) as e:
        xshell.relax(tmp_path / "bad.json")
    assert str(e.value) == expected


@pytest.mark.parametrize("content", [None, "{not json", ""])
def test_bad_files(program, tmp_path, content):
    path = tmp_path / "config.json"
    if content is not None:
        path.write_text(content)
    expected = cli_error(program, path, "--out", tmp_path / "out")
    with pytest.raises(ValueError) as e:
        xshell.relax(path)
    assert str(e.value) == expected


def test_bad_linkage_file(program, tmp_path):
    (tmp_path / "broken.obj").write_text("v 0 0 0\nl 1 7\n")
    write_config(tmp_path / "config.json", linkage=str(tmp_path / "broken.obj"))
    expected = cli_error(program, tmp_path / "config.json", "--out", tmp_path / "out")
    with pytest.raises(ValueError) as e:
        xshell.relax(tmp_path / "config.json")
    assert str(e.value) == expected


def test_foreign_state(program, tmp_path):
    """A state of another linkage (other subdivisions) is refused."""
    write_config(tmp_path / "other.json", subdivisions=6)
    other = xshell.relax(tmp_path / "other.json")
    other.state.save(tmp_path / "state.json")
    config = SAMPLES / "grid_gravity.json"
    expected = cli_error(program, config, "--init", tmp_path / "state.json", "--out", tmp_path / "o")
    with pytest.raises(ValueError) as e:
        xshell.relax(config, init=tmp_path / "state.json")
    assert str(e.value) == expected
    with pytest.raises(ValueError) as e:
        xshell.relax(config, init=xshell.State.load(tmp_path / "state.json"))
    assert str(e.value) == expected
    with pytest.raises(ValueError) as e:
        xshell.Linkage(config, init=other.state)
    assert "subdivisions" in str(e.value)


def test_bad_solver(program, tmp_path):
    config = SAMPLES / "grid_gravity.json"
    expected = cli_error(program, config, "--solver", "magic", "--out", tmp_path / "o")
    with pytest.raises(ValueError) as e:
        xshell.relax(config, solver="magic")
    assert str(e.value) == expected


def test_wrong_types():
    with pytest.raises(TypeError):
        xshell.relax(42)
    with pytest.raises(TypeError):
        xshell.relax(SAMPLES / "grid_gravity.json", init=3.5)
    with pytest.raises(ValueError, match="not a JSON configuration"):
        xshell.relax({"linkage": float("nan")})


def test_a_failed_solve_is_a_result(sample_config):
    """Not converging is no exception: the status says so, as exit status 3 does."""
    with open(sample_config) as f:
        cfg = json.load(f)
    cfg["linkage"] = str(SAMPLES / cfg["linkage"])
    cfg["solver"]["max_iterations"] = 1
    res = xshell.relax(cfg)
    assert res.status == "max_iterations" and not res.converged and res.stable is None
    assert res.exit_status == 3
