#!/usr/bin/env python3
"""Writes the sample linkages of this folder (run from anywhere).

grid.obj: a flat 4 x 4 grid of straight rods crossing at right angles
  (16 valence-4 joints), each rod running half a spacing past the last
  crossing to a free end; metres, spacing 0.25.
saddle.obj: the same grid lifted onto a hyperbolic paraboloid z = k (x^2 - y^2),
  so the rods are curved in 3D.
"""
import os

HERE = os.path.dirname(os.path.abspath(__file__))


def grid(n=4, spacing=0.25, lift=None):
    vertices, edges = [], []
    index = {}

    def vertex(x, y):
        key = (round(x, 9), round(y, 9))
        if key not in index:
            z = lift(x, y) if lift else 0.0
            index[key] = len(vertices)
            vertices.append((x, y, z))
        return index[key]

    half = (n - 1) * spacing / 2
    coords = [-half + i * spacing for i in range(n)]
    ends = [-half - spacing / 2, half + spacing / 2]
    for c in coords:
        for along_x in (True, False):
            stations = [ends[0]] + coords + [ends[1]]
            chain = [vertex(s, c) if along_x else vertex(c, s) for s in stations]
            edges += list(zip(chain, chain[1:]))
    return vertices, edges


def write(name, vertices, edges, comment):
    with open(os.path.join(HERE, name), "w") as f:
        f.write(f"# {comment}\n")
        for v in vertices:
            f.write("v %.9g %.9g %.9g\n" % v)
        for a, b in edges:
            f.write(f"l {a + 1} {b + 1}\n")


if __name__ == "__main__":
    write("grid.obj", *grid(), "flat 4 x 4 grid of straight rods, metres")
    write("saddle.obj", *grid(lift=lambda x, y: 0.6 * (x * x - y * y)),
          "4 x 4 grid on a hyperbolic paraboloid, metres")
