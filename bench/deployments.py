#!/usr/bin/env python3
"""Whole deployments of the real designs, timed as a user runs them.

Each case is one `xshell relax` run with a "deployment", from loading the
configuration to the last output (the VTK series written at every step,
the engineering results, the summary), in its own process:

  manta_ray    from flat to an average opening angle of 93 degrees
  darth_vader  from flat to 115 degrees (the published deployments)
  scary_face, hourglass, large
               by 0.5 rad from their relaxed flat states, opening: away
               from the nearer collapsed state (the average angle raised
               when it is below pi/2, lowered otherwise: hourglass lies
               flat at 3.01 rad, near pi); the relaxation runs once per
               design, untimed, and the deployment starts from its
               state.json
  manta_ray_relax
               a plain relaxation of manta_ray from flat, no deployment
               (its "steps" are empty; with --gravity, loaded too)

Straight laths, millimetres, E = 20000 MPa, rectangle 10 x 7 mm (the
designs' own sections are listed in ../shared/data/elasticrods/README.txt;
one section keeps the cases comparable), 8 edges per segment, the default
pin, 20 steps. Per case, as medians of --reps runs (alternating between the
cases, so that the machine's drift spreads over all of them): accepted
steps, Newton iterations and factorizations (all of the run's, failed
attempts included), wall seconds (the process, from its start to its exit),
the run's own phase times (summary.json "timings", when it has them), peak
memory (MB, the process's maximum resident set), the end energy and how
many steps ended unstable. With --gravity G (length/s^2, downwards along
-z) the laths weigh (--density, default 7e-10: timber in tonnes per mm^3,
so G = 9810 for millimetres and seconds) and the run ends with the
stability analysis of a loaded state (its eigenmodes and buckling load
factor): the table adds the analysis' share of the run's wall time, its
stages' seconds (from the run's --progress json) and its statuses. With
--solver dynamics the deployments run by damped dynamics ("solver":
{"method": "dynamics"}), to set beside Newton's; "iterations" are then time
steps.

  /usr/bin/python3 bench/deployments.py [--xshell build/app/xshell]
      [--data ../shared/data/elasticrods] [--designs manta_ray,...]
      [--reps 3] [--subdivisions 8] [--steps 20] [--csv FILE] [--keep DIR]
      [--gravity 9810] [--density 7e-10] [--solver newton|dynamics]

Needs the data folder; says so and exits 0 when it is absent (skipped).
"""
import argparse
import csv
import json
import math
import os
import shutil
import statistics
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))

# name: (file, target): target "degrees" an absolute angle, "open" a raise
# of the relaxed state's average angle in radians, "relax" no deployment.
DESIGNS = {
    "manta_ray": ("manta_ray_5ca2f7ab.obj", ("degrees", 93.0)),
    "darth_vader": ("darth_vader_fig5_1693d9a2.obj", ("degrees", 115.0)),
    "scary_face": ("scary_face_8f39dd30.obj", ("open", 0.5)),
    "hourglass": ("hourglass_912c32dc.obj", ("open", 0.5)),
    "large": ("large_6d35a972.obj", ("open", 0.5)),
    "manta_ray_relax": ("manta_ray_5ca2f7ab.obj", ("relax", None)),
}

COLUMNS = ["design", "steps", "iterations", "factorizations", "iterations_per_step",
           "factorizations_per_step", "wall_s", "load_s", "setup_s", "solve_s", "analysis_s",
           "output_s", "analysis_share", "eigen_modes_s", "unloaded_equilibrium_s",
           "buckling_s", "buckling_check_s", "eigenvalues", "buckling", "load_factor", "peak_mb",
           "energy", "unstable_steps", "status", "reps"]

# The analysis' stages, in their order (README, "Progress").
STAGES = ["eigen_modes", "unloaded_equilibrium", "buckling", "buckling_check"]


def config(obj, subdivisions, deployment=None, gravity=None, density=7e-10, solver="newton"):
    c = {
        "linkage": obj,
        "subdivisions": subdivisions,
        "rest_shape": "straight",
        "material": {"young_modulus": 20000,
                     "cross_section": {"shape": "rectangle", "width": 10, "height": 7}},
        "output": {"directory": "out"},
    }
    if deployment is not None:
        c["deployment"] = deployment
        if solver != "newton":
            c["solver"] = {"method": solver}
    if gravity:
        c["material"]["density"] = density
        c["loads"] = {"gravity": [0.0, 0.0, -gravity]}
    return c


def run_xshell(xshell, directory, args):
    """Runs xshell in `directory`; returns (exit status, wall s, peak MB, stderr)."""
    start = time.perf_counter()
    with open(os.path.join(directory, "stderr.txt"), "wb") as err:
        p = subprocess.Popen([xshell] + args, cwd=directory, stdout=subprocess.DEVNULL, stderr=err)
        _, status, usage = os.wait4(p.pid, 0)
    wall = time.perf_counter() - start
    code = os.waitstatus_to_exitcode(status)
    with open(os.path.join(directory, "stderr.txt"), errors="replace") as f:
        errors = f.read()
    return code, wall, usage.ru_maxrss / 1024.0, errors


def average_angle(summary):
    angles = [a for a in summary["opening_angles"] if a is not None]
    return sum(angles) / len(angles)


def prepare(xshell, data, name, subdivisions, steps, root, gravity=None, density=7e-10,
            solver="newton"):
    """The case's folder and configuration (relaxing the flat state first
    for a relative target)."""
    obj, (kind, value) = DESIGNS[name]
    folder = os.path.join(root, name)
    os.makedirs(folder, exist_ok=True)
    path = os.path.join(data, obj)
    args = ["relax", "deploy.json"]
    if kind == "relax":
        with open(os.path.join(folder, "deploy.json"), "w") as f:
            json.dump(config(path, subdivisions, None, gravity, density), f)
        return folder, args + ["--progress", "json"]
    if kind == "degrees":
        target = math.radians(value)
    else:
        with open(os.path.join(folder, "flat.json"), "w") as f:
            json.dump(config(path, subdivisions) | {"output": {"directory": "flat"}}, f)
        code, _, _, errors = run_xshell(xshell, folder, ["relax", "flat.json", "--quiet"])
        if code != 0:
            raise RuntimeError(f"{name}: the relaxation failed ({code}): {errors[-400:]}")
        with open(os.path.join(folder, "flat", "summary.json")) as f:
            flat = average_angle(json.load(f))
        # Opening leaves the collapsed state nearer to the flat angle (0 or pi).
        target = flat + value if flat < math.pi / 2 else flat - value
        args += ["--init", os.path.join("flat", "state.json")]
    deployment = {"average_opening_angle": target, "steps": steps}
    with open(os.path.join(folder, "deploy.json"), "w") as f:
        json.dump(config(path, subdivisions, deployment, gravity, density, solver), f)
    return folder, args + ["--progress", "json"]


def measure(xshell, folder, args):
    """One run: its row (before the medians)."""
    code, wall, peak, errors = run_xshell(xshell, folder, args)
    row = {"wall_s": wall, "peak_mb": peak, "status": f"exit {code}"} | stage_seconds(errors)
    summary_path = os.path.join(folder, "out", "summary.json")
    if not os.path.exists(summary_path):
        print(errors[-400:], file=sys.stderr)
        return row
    with open(summary_path) as f:
        s = json.load(f)
    d = s.get("deployment") or {}
    row["status"] = d.get("status", s["status"])
    row["steps"] = d.get("steps")
    row["iterations"] = d.get("iterations", s["iterations"])
    row["energy"] = s["energy"]["total"]
    for phase, seconds in (s.get("timings") or {}).items():
        row[f"{phase}_s"] = seconds
    if "analysis_s" in row:
        row["analysis_share"] = row["analysis_s"] / wall
    analysis = s.get("stability_analysis") or {}
    row["eigenvalues"] = analysis.get("eigenvalues")
    row["buckling"] = analysis.get("buckling")
    row["load_factor"] = s.get("buckling_load_factor")
    table = []
    if os.path.exists(os.path.join(folder, "out", "deployment.csv")):
        with open(os.path.join(folder, "out", "deployment.csv")) as f:
            table = list(csv.DictReader(f))
    row["unstable_steps"] = sum(1 for t in table if t["stable"] != "true")
    if "factorizations" in d:
        row["factorizations"] = d["factorizations"]
    elif table and "factorizations" in table[0]:  # older runs: the accepted steps' only
        row["factorizations"] = sum(int(t["factorizations"]) for t in table)
    if row["steps"]:
        row["iterations_per_step"] = row["iterations"] / row["steps"]
        if "factorizations" in row:
            row["factorizations_per_step"] = row["factorizations"] / row["steps"]
    return row


def stage_seconds(progress):
    """Seconds of each analysis stage, from the JSON progress lines: a stage
    lasts until the next phase or stage starts."""
    events = []
    for text in progress.splitlines():
        if text.startswith("{"):
            try:
                events.append(json.loads(text))
            except ValueError:
                pass
    starts = [(e.get("phase"), e.get("stage"), e["elapsed"]) for e in events
              if e.get("event") in ("phase", "done") and "elapsed" in e]
    out = {}
    for (phase, stage, t), (_, _, end) in zip(starts, starts[1:]):
        if phase == "analysis" and stage in STAGES:
            out[f"{stage}_s"] = out.get(f"{stage}_s", 0.0) + end - t
    return out


def medians(rows):
    out = {"reps": len(rows), "status": ",".join(sorted({r["status"] for r in rows}))}
    for key in ("eigenvalues", "buckling"):
        out[key] = ",".join(sorted({str(r.get(key)) for r in rows}))
    for key in COLUMNS:
        values = [r[key] for r in rows if isinstance(r.get(key), (int, float))]
        if values:
            out[key] = statistics.median(values)
    return out


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--xshell", default=os.path.join(HERE, "..", "build", "app", "xshell"))
    parser.add_argument("--data", default=os.path.join(HERE, "..", "..", "shared", "data",
                                                       "elasticrods"))
    parser.add_argument("--designs", default=",".join(DESIGNS))
    parser.add_argument("--reps", type=int, default=3)
    parser.add_argument("--subdivisions", type=int, default=8)
    parser.add_argument("--steps", type=int, default=20)
    parser.add_argument("--csv")
    parser.add_argument("--keep", help="run in this folder and keep it (default: a temporary one)")
    parser.add_argument("--gravity", type=float, help="downwards acceleration (length/s^2)")
    parser.add_argument("--density", type=float, default=7e-10, help="with --gravity")
    parser.add_argument("--solver", choices=["newton", "dynamics"], default="newton",
                        help="the deployment's solver (the flat states are relaxed by Newton)")
    a = parser.parse_args()
    if not os.path.isdir(a.data):
        print(f"deployments: skipped: no data folder {a.data}")
        return 0
    names = [n for n in a.designs.split(",") if n]
    unknown = [n for n in names if n not in DESIGNS]
    if unknown:
        parser.error(f"unknown designs {unknown}; known: {','.join(DESIGNS)}")
    xshell = os.path.abspath(a.xshell)
    root = a.keep or tempfile.mkdtemp(prefix="xshell-deployments-")
    os.makedirs(root, exist_ok=True)
    try:
        return run_cases(a, xshell, names, root)
    finally:
        if not a.keep:  # each case's VTK series: gigabytes over a few runs
            shutil.rmtree(root, ignore_errors=True)


def run_cases(a, xshell, names, root):
    """Prepares and measures the cases in `root`; prints the table."""
    cases = {n: prepare(xshell, a.data, n, a.subdivisions, a.steps, root, a.gravity, a.density,
                        a.solver)
             for n in names}
    runs = {n: [] for n in names}
    for rep in range(a.reps):
        for n in names:
            runs[n].append(measure(xshell, *cases[n]))
            r = runs[n][-1]
            print(f"  {n} rep {rep + 1}: {r.get('steps')} steps, {r.get('iterations')} "
                  f"iterations, {r['wall_s']:.2f} s, {r['status']}", file=sys.stderr)
    table = [{"design": n} | medians(runs[n]) for n in names]
    show = ["design", "steps", "iterations", "factorizations", "iterations_per_step",
            "factorizations_per_step", "wall_s", "solve_s", "analysis_s", "output_s", "peak_mb",
            "energy", "unstable_steps", "status"]
    if a.gravity:
        show[show.index("output_s") + 1:show.index("output_s") + 1] = [
            "analysis_share", "eigen_modes_s", "unloaded_equilibrium_s", "buckling_s",
            "buckling_check_s",
            "eigenvalues", "buckling", "load_factor"]
    print(" | ".join(show))
    for row in table:
        cells = []
        for k in show:
            v = row.get(k, "")
            cells.append(f"{v:.4g}" if isinstance(v, float) else str(v))
        print(" | ".join(cells))
    if a.csv:
        with open(a.csv, "w", newline="") as f:
            w = csv.DictWriter(f, fieldnames=COLUMNS)
            w.writeheader()
            for row in table:
                w.writerow(row)
    return 0


if __name__ == "__main__":
    sys.exit(main())
