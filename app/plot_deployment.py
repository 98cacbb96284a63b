"""deployment.png: energy and torque of a deployment against the average
opening angle, drawn from deployment.csv with matplotlib.

Run by xshell (app/deployment_plot.cpp) as
    python3 plot_deployment.py --wait TABLE PICTURE TEMPORARY [ENERGY_LABEL TORQUE_LABEL]
which loads matplotlib (exit status 3 when it cannot), prints "ready", and
draws once a line "draw" arrives on its input (any other line, or the end
of the input, ends it without drawing): xshell starts it before the
deployment, which writes TABLE meanwhile. Without --wait it draws at once.
The picture is drawn to TEMPORARY (in PICTURE's folder) and renamed onto
PICTURE, so that PICTURE is either absent or complete. The labels name the
energy and torque axes with their units (e.g. "energy [N mm]").
"""
import csv
import math
import os
import sys

if sys.argv[1:2] == ["--wait"]:
    # Loading beside the deployment's solve: yield the cores to it. Not
    # SCHED_IDLE, nor a lower priority: an unprivileged process cannot
    # raise its priority again to draw, and beside other busy processes
    # (a sweep, the tests) it would all but stop.
    os.nice(10)

try:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt  # noqa: E402  (after the backend is chosen)
except ImportError:
    sys.exit(3)


def main(table, picture, temporary, energy_label="energy",
         torque_label="torque dE/dA (energy per radian)"):
    with open(table, newline="") as f:
        rows = list(csv.DictReader(f))
    angle = [math.degrees(float(r["average_angle"])) for r in rows]
    fig, left = plt.subplots(figsize=(8, 5), dpi=120)
    for key, style, label in (("energy_total", "o-", "total"), ("energy_bending", "--", "bending"),
                              ("energy_twisting", ":", "twisting"),
                              ("energy_stretching", "-.", "stretching")):
        left.plot(angle, [float(r[key]) for r in rows], style, color="tab:blue", label=label,
                  markersize=3, linewidth=1.5 if key == "energy_total" else 1.0)
    left.set_xlabel("average opening angle (degrees)")
    left.set_ylabel(energy_label, color="tab:blue")
    left.legend(loc="upper left", title="energy")
    right = left.twinx()
    right.plot(angle, [float(r["torque"]) for r in rows], "s-", color="tab:red", markersize=3)
    unstable = [(a, float(r["torque"])) for a, r in zip(angle, rows) if r["stable"] != "true"]
    if unstable:
        right.plot(*zip(*unstable), "x", color="black", label="not stable")
        right.legend(loc="lower right")
    right.set_ylabel(torque_label, color="tab:red")
    left.set_title("deployment")
    fig.tight_layout()
    fig.savefig(temporary, format="png")
    os.replace(temporary, picture)


if __name__ == "__main__":
    if sys.argv[1:2] == ["--wait"]:
        print("ready", flush=True)
        if sys.stdin.readline().strip() != "draw":
            sys.exit(0)
        main(*sys.argv[2:7])
        sys.stdout.flush()
        os._exit(0)  # the picture is in place: skip the interpreter's teardown
    else:
        main(*sys.argv[1:6])
