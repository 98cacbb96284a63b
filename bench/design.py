#!/usr/bin/env python3
"""The inverse design of a real linkage, timed as a user runs it.

manta_ray (straight 10 x 7 mm laths, millimetres, E = 20000 MPa, 8 edges per
segment, the default pin) is deployed by `xshell relax` to 93 degrees (the
published deployment, 20 steps); its deployed joints are smoothed (each
joint moved halfway to the mean of its neighbours, --smoothing times) and
`xshell design` fits the flat linkage's rest lengths so that its deployment
to the same angle reaches that smoothed shape ("target_joints", fit weight 1,
regularization 1e-3, bounds 0.2, --iterations design iterations at most).

Reported: the design's status, iterations, evaluations (each one
warm-started constrained Newton solve of the deployed equilibrium and one
adjoint solve), the rms and largest distance to the targets before and
after, wall seconds (the process), seconds per design iteration and per
evaluation, and their ratio to one deployed solve: a deployment step of the
relax run (its solve seconds over its steps: one constrained Newton solve
from the previous step's equilibrium, the same kind of solve as an
evaluation's).

  /usr/bin/python3 bench/design.py [--xshell build/app/xshell]
      [--data ../shared/data/elasticrods] [--iterations 30] [--smoothing 3]
      [--keep DIR]

Needs the data folder; says so and exits 0 when it is absent (skipped).
"""
import argparse
import json
import math
import os
import shutil
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ANGLE = math.radians(93.0)


def base_config(obj):
    return {
        "linkage": obj,
        "units": {"length": "mm", "force": "N"},
        "subdivisions": 8,
        "rest_shape": "straight",
        "material": {"young_modulus": 20000, "poisson_ratio": 0.3,
                     "cross_section": {"shape": "rectangle", "width": 10, "height": 7}},
        "output": {"directory": "out", "solids": False},
        "analysis": {"modes": 0},
    }


def run(xshell, folder, args):
    start = time.perf_counter()
    done = subprocess.run([xshell] + args, cwd=folder, capture_output=True, text=True)
    seconds = time.perf_counter() - start
    if done.returncode not in (0, 3):
        sys.exit("xshell %s failed (%d): %s" % (" ".join(args), done.returncode, done.stderr))
    return seconds, done


def edges_of(obj):
    edges = []
    with open(obj) as f:
        for line in f:
            parts = line.split()
            if parts and parts[0] == "l":
                chain = [int(p.split("/")[0]) - 1 for p in parts[1:]]
                edges += list(zip(chain, chain[1:]))
    return edges


def smoothed_joints(vertices, angles, edges, passes):
    """The joints (vertices with an opening angle) moved halfway to their
    neighbours' mean, `passes` times; free ends get no target (None)."""
    neighbours = [[] for _ in vertices]
    for a, b in edges:
        neighbours[a].append(b)
        neighbours[b].append(a)
    x = [list(v) for v in vertices]
    for _ in range(passes):
        new = [list(v) for v in x]
        for v, n in enumerate(neighbours):
            if angles[v] is None or not n:
                continue
            for k in range(3):
                new[v][k] = 0.5 * x[v][k] + 0.5 * sum(x[u][k] for u in n) / len(n)
        x = new
    return [x[v] if angles[v] is not None else None for v in range(len(x))]


def distances(vertices, targets):
    d = [math.dist(v, t) for v, t in zip(vertices, targets) if t is not None]
    return math.sqrt(sum(e * e for e in d) / len(d)), max(d)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--xshell", default=os.path.join(HERE, "..", "build", "app", "xshell"))
    parser.add_argument("--data", default=os.path.join(HERE, "..", "..", "shared", "data",
                                                       "elasticrods"))
    parser.add_argument("--iterations", type=int, default=30)
    parser.add_argument("--smoothing", type=int, default=3)
    parser.add_argument("--keep", help="run in this folder and keep it (default: a temporary one)")
    args = parser.parse_args()
    obj = os.path.abspath(os.path.join(args.data, "manta_ray_5ca2f7ab.obj"))
    if not os.path.exists(obj):
        print("design benchmark skipped: %s is absent" % obj)
        return 0
    xshell = os.path.abspath(args.xshell)
    folder = args.keep or tempfile.mkdtemp(prefix="xshell-bench-design-")
    os.makedirs(folder, exist_ok=True)
    try:
        return run_design(args, xshell, obj, folder)
    finally:
        if not args.keep:  # the runs' outputs
            shutil.rmtree(folder, ignore_errors=True)


def run_design(args, xshell, obj, folder):
    """Deploys, designs and prints the report, in `folder`."""
    deploy = base_config(obj)
    deploy["deployment"] = {"average_opening_angle": ANGLE, "steps": 20}
    deploy["output"]["every"] = 1000
    with open(os.path.join(folder, "deploy.json"), "w") as f:
        json.dump(deploy, f, indent=1)
    _, _ = run(xshell, folder, ["relax", "deploy.json", "--out", "deployed", "--quiet"])
    with open(os.path.join(folder, "deployed", "summary.json")) as f:
        summary = json.load(f)
    steps = summary["deployment"]["steps"] if isinstance(summary.get("deployment"), dict) else 20
    step_seconds = summary["timings"]["solve"] / max(steps, 1)
    targets = smoothed_joints(summary["vertices"], summary["opening_angles"], edges_of(obj),
                              args.smoothing)
    before = distances(summary["vertices"], targets)
    with open(os.path.join(folder, "targets.json"), "w") as f:
        json.dump({"positions": targets}, f)

    design = base_config(obj)
    design["design"] = {"average_opening_angle": ANGLE, "target_joints": "targets.json",
                        "weights": {"fit": 1, "regularization": 1e-3},
                        "max_iterations": args.iterations}
    with open(os.path.join(folder, "design.json"), "w") as f:
        json.dump(design, f, indent=1)
    seconds, done = run(xshell, folder, ["design", "design.json", "--out", "designed", "--quiet"])
    with open(os.path.join(folder, "designed", "design.json")) as f:
        report = json.load(f)
    iterations = max(report["iterations"], 1)
    per_iteration = report["wall_seconds"] / iterations
    per_evaluation = report["wall_seconds"] / max(report["evaluations"], 1)
    print("manta_ray design to a smoothed copy of its deployed shape (%d smoothing passes)"
          % args.smoothing)
    print("  deployment step (relax, %d steps): %.3f s of solve each" % (steps, step_seconds))
    print("  status %s (%s), %d iterations, %d evaluations (%d failed), %.1f s wall"
          % (report["status"], report["reason"], report["iterations"], report["evaluations"],
             report["failed_evaluations"], seconds))
    print("  fit rms %.3f -> %.3f mm, max %.3f -> %.3f mm"
          % (before[0], report["fit"]["rms"], before[1], report["fit"]["max"]))
    print("  per design iteration %.3f s (%.1f deployment steps), per evaluation %.3f s (%.1f)"
          % (per_iteration, per_iteration / step_seconds, per_evaluation,
             per_evaluation / step_seconds))
    return 0


if __name__ == "__main__":
    sys.exit(main())
