#!/usr/bin/env python3
"""Write the triangle meshes of the scenes as Wavefront OBJ files.

Each mesh is one function returning (vertices, triangles): vertices a list
of (x, y, z), triangles a list of 0-based (a, b, c), counter-clockwise seen
from outside.  OUTPUTS lists the files and the function that makes each; a
new mesh is one more function and one more row.  Paths are relative to the
repository root, wherever the script is run from.

    scripts/make-meshes.py            write every mesh
    scripts/make-meshes.py sphere     only the outputs named (file stem)

Only the Python standard library is used.
"""

import math
import os
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def normalized(v):
    r = math.sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2])
    return (v[0] / r, v[1] / r, v[2] / r)


def icosahedron():
    """The regular icosahedron on the unit sphere: its vertices are the
    cyclic permutations of (0, +-1, +-phi), phi the golden ratio."""
    p = (1.0 + math.sqrt(5.0)) / 2.0
    vertices = [(-1, p, 0), (1, p, 0), (-1, -p, 0), (1, -p, 0),
                (0, -1, p), (0, 1, p), (0, -1, -p), (0, 1, -p),
                (p, 0, -1), (p, 0, 1), (-p, 0, -1), (-p, 0, 1)]
    triangles = [(0, 11, 5), (0, 5, 1), (0, 1, 7), (0, 7, 10), (0, 10, 11),
                 (1, 5, 9), (5, 11, 4), (11, 10, 2), (10, 7, 6), (7, 1, 8),
                 (3, 9, 4), (3, 4, 2), (3, 2, 6), (3, 6, 8), (3, 8, 9),
                 (4, 9, 5), (2, 4, 11), (6, 2, 10), (8, 6, 7), (9, 8, 1)]
    return [normalized(v) for v in vertices], triangles


def subdivide(vertices, triangles):
    """Split every triangle into four at its edge midpoints, pushed onto the
    unit sphere.  The new vertices follow the old ones in the order of their
    edges sorted by (lower, higher) vertex index, and each triangle
    (a, b, c) becomes (a, m0, m2), (m0, b, m1), (m2, m1, c), (m0, m1, m2),
    as in src/contact/icosphere.c, so that both give the same mesh."""
    edges = sorted({(min(t[k], t[(k + 1) % 3]), max(t[k], t[(k + 1) % 3]))
                    for t in triangles for k in range(3)})
    index = {e: len(vertices) + i for i, e in enumerate(edges)}
    vertices = vertices + [
        normalized(tuple(vertices[a][i] + vertices[b][i] for i in range(3)))
        for a, b in edges]
    split = []
    for t in triangles:
        m = [index[(min(t[k], t[(k + 1) % 3]), max(t[k], t[(k + 1) % 3]))]
             for k in range(3)]
        split += [(t[0], m[0], m[2]), (m[0], t[1], m[1]),
                  (m[2], m[1], t[2]), (m[0], m[1], m[2])]
    return vertices, split


def sphere():
    """Icosphere of radius 1 at the origin, 3 subdivisions: 642 vertices,
    1280 triangles."""
    vertices, triangles = icosahedron()
    for _ in range(3):
        vertices, triangles = subdivide(vertices, triangles)
    return vertices, triangles


OUTPUTS = [
    ("problems/meshes/sphere.obj",
     "icosphere, radius 1, centre 0, 3 subdivisions", sphere),
]


def write_obj(path, comment, vertices, triangles):
    with open(path, "w") as f:
        f.write("# %s\n# written by scripts/make-meshes.py\n" % comment)
        f.write("# %d vertices, %d triangles, counter-clockwise seen from "
                "outside\n" % (len(vertices), len(triangles)))
        for v in vertices:
            f.write("v %r %r %r\n" % v)
        for t in triangles:
            f.write("f %d %d %d\n" % (t[0] + 1, t[1] + 1, t[2] + 1))


def main(argv):
    names = {os.path.splitext(os.path.basename(p))[0] for p, _, _ in OUTPUTS}
    unknown = [a for a in argv if a not in names]
    if unknown:
        sys.exit("make-meshes.py: unknown mesh %s (known: %s)"
                 % (", ".join(unknown), ", ".join(sorted(names))))
    for path, comment, make in OUTPUTS:
        stem = os.path.splitext(os.path.basename(path))[0]
        if argv and stem not in argv:
            continue
        full = os.path.join(ROOT, path)
        os.makedirs(os.path.dirname(full), exist_ok=True)
        vertices, triangles = make()
        write_obj(full, comment, vertices, triangles)
        print("%s: %d vertices, %d triangles"
              % (path, len(vertices), len(triangles)))


if __name__ == "__main__":
    main(sys.argv[1:])
