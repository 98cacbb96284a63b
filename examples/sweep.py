"""A parameter sweep of xshell runs on a Dask cluster.

Relaxes the sample linkage (samples/grid_gravity.json) for every combination
of Young's modulus, section height and gravity (2 x 4 x 4 = 32 runs by
default), one run per Dask task, and writes one CSV row per run. Dask
distributed schedules the runs: on a LocalCluster on this machine by default,
or on any running Dask cluster given by its scheduler's address (one started
by `dask scheduler` / `dask worker`, or by dask-jobqueue on Slurm, PBS, ...).
Each worker imports xshell, so it must find the module (PYTHONPATH) and the
linkage file (a path every worker can read: a shared file system).

    PYTHONPATH=build/python /usr/bin/python3 examples/sweep.py --out sweep.csv
    PYTHONPATH=build/python /usr/bin/python3 examples/sweep.py \\
        --scheduler tcp://login1:8786 --out sweep.csv

README, "Sweeps on a cluster".
"""

import argparse
import csv
import itertools
import json
import os
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
SAMPLE = os.path.join(HERE, "..", "samples", "grid_gravity.json")

YOUNG_MODULI = [1.0e10, 2.0e10]  # Pa
HEIGHTS = [0.005, 0.007, 0.009, 0.011]  # m, the section's height
GRAVITIES = [-4.905, -9.81, -14.715, -19.62]  # m/s^2, along z


def base_configuration(path=SAMPLE):
    """The configuration at `path` as a dict, its linkage an absolute path
    (a dict's relative paths are relative to the working directory, which a
    worker does not share)."""
    with open(path) as f:
        cfg = json.load(f)
    cfg["linkage"] = os.path.abspath(os.path.join(os.path.dirname(path), cfg["linkage"]))
    cfg.pop("output", None)
    return cfg


def configurations(base, young_moduli=YOUNG_MODULI, heights=HEIGHTS, gravities=GRAVITIES):
    """One configuration per combination: (parameters, configuration dict)."""
    runs = []
    for e, h, g in itertools.product(young_moduli, heights, gravities):
        cfg = json.loads(json.dumps(base))
        cfg["material"]["young_modulus"] = e
        cfg["material"]["cross_section"]["height"] = h
        cfg["loads"]["gravity"] = [0.0, 0.0, g]
        runs.append(({"young_modulus": e, "height": h, "gravity": g}, cfg))
    return runs


def solve(parameters, cfg):
    """One run (a Dask task): the parameters and what the run found, as
    plain values (cheap to send back from a worker)."""
    import xshell  # on the worker

    res = xshell.relax(cfg)
    z = res.vertices[:, 2]
    row = dict(parameters)
    row.update(
        status=res.status,
        stable=res.stable,
        iterations=res.iterations,
        energy=res.energy["total"],
        max_sag=float(z.max() - z.min()),
        min_opening_angle=float(np.nanmin(res.opening_angles)),
        max_opening_angle=float(np.nanmax(res.opening_angles)),
    )
    row["vertices"] = res.vertices
    return row


def run_sweep(client, runs):
    """Every run on the cluster of `client`, in the order of `runs`."""
    futures = [client.submit(solve, p, cfg, pure=False) for p, cfg in runs]
    return client.gather(futures)


def write_csv(rows, path):
    fields = [k for k in rows[0] if k != "vertices"]
    with open(path, "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=fields, extrasaction="ignore")
        writer.writeheader()
        writer.writerows(rows)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--scheduler", help="address of a running Dask scheduler "
                        "(default: a LocalCluster on this machine)")
    parser.add_argument("--workers", type=int, default=2, help="LocalCluster workers (default 2)")
    parser.add_argument("--config", default=SAMPLE, help="the configuration to vary")
    parser.add_argument("--out", default="sweep.csv", help="the CSV file to write")
    args = parser.parse_args(argv)

    from dask.distributed import Client, LocalCluster

    runs = configurations(base_configuration(args.config))
    if args.scheduler:
        client = Client(args.scheduler)
        cluster = None
    else:
        # One thread per worker process: a run uses OpenMP threads of its own.
        cluster = LocalCluster(n_workers=args.workers, threads_per_worker=1)
        client = Client(cluster)
    try:
        print("sweep: %d runs on %s" % (len(runs), client), file=sys.stderr)
        rows = run_sweep(client, runs)
    finally:
        client.close()
        if cluster is not None:
            cluster.close()
    write_csv(rows, args.out)
    converged = sum(r["status"] == "converged" for r in rows)
    print("sweep: %d of %d runs converged; %s written" % (converged, len(rows), args.out),
          file=sys.stderr)
    return 0 if converged == len(rows) else 3


if __name__ == "__main__":
    sys.exit(main())
