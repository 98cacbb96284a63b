#!/usr/bin/python3
"""Plots xshell_bench's CSV: time per Newton iteration and per numeric
factorization against the number of free unknowns, log-log.

    /usr/bin/python3 bench/plot.py xshell_bench.csv bench.png   (Debian python3-matplotlib)
"""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main():
    source = sys.argv[1] if len(sys.argv) > 1 else "xshell_bench.csv"
    target = sys.argv[2] if len(sys.argv) > 2 else "xshell_bench.png"
    rows = []
    with open(source) as f:
        for row in csv.DictReader(f):
            try:
                row["n"] = float(row["free_unknowns"])
                row["iter"] = float(row["iteration_ms"])
                row["fact"] = float(row["factorization_ms"])
                row["hess"] = float(row["hessian_ms"])
            except ValueError:
                continue
            rows.append(row)
    fig, ax = plt.subplots(figsize=(7, 5))
    series = [
        ("grid", "0", "grids", "o"),
        ("grid", "1", "grids, gravity", "s"),
        ("graph", "0", "designs", "^"),
    ]
    for kind, gravity, label, marker in series:
        pts = sorted((r for r in rows if r["kind"] == kind and r["gravity"] == gravity), key=lambda r: r["n"])
        if not pts:
            continue
        n = [r["n"] for r in pts]
        line = "-" if kind == "grid" else ""
        it = [(r["n"], r["iter"]) for r in pts if r["iter"] == r["iter"]]
        if it:
            ax.plot(*zip(*it), line + marker, color="C0", label=f"Newton iteration ({label})")
        ax.plot(n, [r["fact"] for r in pts], line + marker, color="C1", mfc="none",
                label=f"numeric factorization ({label})")
        ax.plot(n, [r["hess"] for r in pts], line + marker, color="C2", mfc="none", alpha=0.6,
                label=f"Hessian assembly ({label})")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("free unknowns")
    ax.set_ylabel("time (ms, median)")
    ax.set_title("xshell: time per Newton iteration vs factorization")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(target, dpi=120)
    print(f"wrote {target}")


if __name__ == "__main__":
    main()
