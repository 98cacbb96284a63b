"""examples/sweep.py: a sweep on a 2-worker LocalCluster equals the same runs
one after the other."""

import importlib.util

import numpy as np
import pytest

from conftest import ROOT

distributed = pytest.importorskip("distributed")


def load_example():
    spec = importlib.util.spec_from_file_location("sweep", ROOT / "examples" / "sweep.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_sweep_on_a_local_cluster_equals_serial_runs(tmp_path):
    sweep = load_example()
    runs = sweep.configurations(
        sweep.base_configuration(), young_moduli=[2.0e10], heights=[0.006, 0.008],
        gravities=[-9.81, -19.62],
    )
    assert len(runs) == 4
    serial = [sweep.solve(p, cfg) for p, cfg in runs]
    with distributed.LocalCluster(
        n_workers=2, threads_per_worker=1, processes=False, dashboard_address=None,
        local_directory=str(tmp_path),
    ) as cluster, distributed.Client(cluster) as client:
        parallel = sweep.run_sweep(client, runs)
        # Both workers ran some of the runs.
        assert len(client.scheduler_info()["workers"]) == 2
    assert len(parallel) == len(serial)
    for a, b in zip(parallel, serial):
        np.testing.assert_array_equal(a["vertices"], b["vertices"])
        assert {k: v for k, v in a.items() if k != "vertices"} == {
            k: v for k, v in b.items() if k != "vertices"
        }
        assert a["status"] == "converged"
    # The parameters matter: four different equilibria.
    assert len({r["energy"] for r in serial}) == 4
