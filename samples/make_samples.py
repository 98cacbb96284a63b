#!/usr/bin/env python3
"""Writes the sample linkages of this folder (run from anywhere).

grid.obj: a flat 4 x 4 grid of straight rods crossing at right angles
  (16 valence-4 joints), each rod running half a spacing past the last
  crossing to a free end; metres, spacing 0.25.
saddle.obj: the same grid lifted onto a hyperbolic paraboloid z = k (x^2 - y^2),
  so the rods are curved in 3D.
saddle_target.obj: a triangle mesh of the steeper paraboloid z = 0.9 (x^2 - y^2)
  over [-0.6, 0.6]^2: the target surface of saddle_design.json (xshell design).
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


def write(name, vertices, elements, comment, kind="l"):
    """An OBJ file: the vertices, then the elements (edges "l" or faces "f")."""
    with open(os.path.join(HERE, name), "w") as f:
        f.write(f"# {comment}\n")
        for v in vertices:
            f.write("v %.9g %.9g %.9g\n" % v)
        for element in elements:
            f.write(kind + "".join(f" {i + 1}" for i in element) + "\n")


def surface(f, m=25, size=0.6):
    """The graph z = f(x, y) over [-size, size]^2 as an m x m triangle mesh."""
    vertices, faces = [], []
    for i in range(m):
        for j in range(m):
            x, y = -size + 2 * size * j / (m - 1), -size + 2 * size * i / (m - 1)
            vertices.append((x, y, f(x, y)))
    for i in range(m - 1):
        for j in range(m - 1):
            a = i * m + j
            faces += [(a, a + 1, a + m + 1), (a, a + m + 1, a + m)]
    return vertices, faces


if __name__ == "__main__":
    write("grid.obj", *grid(), "flat 4 x 4 grid of straight rods, metres")
    write("saddle.obj", *grid(lift=lambda x, y: 0.6 * (x * x - y * y)),
          "4 x 4 grid on a hyperbolic paraboloid, metres")
    write("saddle_target.obj", *surface(lambda x, y: 0.9 * (x * x - y * y)),
          "target surface z = 0.9 (x^2 - y^2), metres", kind="f")
