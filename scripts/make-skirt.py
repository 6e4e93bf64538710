#!/usr/bin/env python3
"""Write problems/meshes/skirt.obj: a circular skirt for a mesh cloth.

The skirt of Zischg, Chea and Aigner ("Cloth Simulation") is a Blender mesh
draped over a body: here a flat annulus in the plane y = 0, centred on the
y axis, with a waist hole of radius 0.15 m and an outer radius of 1.0 m.
It is triangulated in rings: RINGS + 1 circles of vertices evenly spaced
in radius, each with as many vertices as make its triangles close to
equilateral (so the segments grow from the waist to the hem, about 48 on
average, and every triangle has about the same size: no slivers); two
neighbouring circles are zipped together by always advancing along the
circle whose next vertex comes first in angle.  Every triangle is
counter-clockwise seen from +y (its normal points up).

Usage: scripts/make-skirt.py [OUTPUT]   (default problems/meshes/skirt.obj)
Standard library only; prints the vertex and triangle counts, the smallest
angle and the ratio of the largest to the smallest triangle area.
"""

import math
import os
import sys

R_WAIST = 0.15
R_HEM = 1.0
RINGS = 12


def circles():
    """The vertex circles, waist first: (radius, count, angle offset)."""
    dr = (R_HEM - R_WAIST) / RINGS
    side = 2.0 * dr / math.sqrt(3.0)  # equilateral: height dr
    out = []
    for k in range(RINGS + 1):
        r = R_WAIST + k * dr
        n = max(3, round(2.0 * math.pi * r / side))
        out.append((r, n, 0.5 * (k % 2)))
    return out


def build():
    verts, tris, first = [], [], []
    circ = circles()
    for r, n, off in circ:
        first.append(len(verts))
        for j in range(n):
            t = 2.0 * math.pi * (j + off) / n
            verts.append((r * math.cos(t), 0.0, r * math.sin(t)))
    for k in range(RINGS):
        (_, ni, oi), (_, no, oo) = circ[k], circ[k + 1]
        a = b = 0
        while a < ni or b < no:
            ia, ia1 = first[k] + a % ni, first[k] + (a + 1) % ni
            ob, ob1 = first[k + 1] + b % no, first[k + 1] + (b + 1) % no
            if b == no or (a < ni and (a + 1 + oi) / ni <= (b + 1 + oo) / no):
                tris.append((ia, ia1, ob))
                a += 1
            else:
                tris.append((ia, ob1, ob))
                b += 1
    return verts, [counter_clockwise(verts, t) for t in tris]


def normal_y(verts, t):
    (ax, _, az), (bx, _, bz), (cx, _, cz) = (verts[i] for i in t)
    return (bz - az) * (cx - ax) - (bx - ax) * (cz - az)


def counter_clockwise(verts, t):
    """t ordered so that its normal points to +y."""
    return t if normal_y(verts, t) > 0 else (t[0], t[2], t[1])


def quality(verts, tris):
    """Smallest angle (degrees) and largest / smallest area."""
    amin, areas = 180.0, []
    for t in tris:
        p = [verts[i] for i in t]
        for m in range(3):
            u = [p[(m + 1) % 3][d] - p[m][d] for d in range(3)]
            v = [p[(m + 2) % 3][d] - p[m][d] for d in range(3)]
            c = sum(x * y for x, y in zip(u, v)) / math.hypot(*u) / \
                math.hypot(*v)
            amin = min(amin, math.degrees(math.acos(max(-1.0, min(1.0, c)))))
        areas.append(0.5 * normal_y(verts, t))
    return amin, max(areas) / min(areas)


def main():
    path = sys.argv[1] if len(sys.argv) > 1 else os.path.normpath(
        os.path.join(os.path.dirname(os.path.abspath(__file__)), "..",
                     "problems", "meshes", "skirt.obj"))
    verts, tris = build()
    os.makedirs(os.path.dirname(os.path.abspath(path)), exist_ok=True)
    with open(path, "w") as f:
        f.write("# circular skirt: annulus in y = 0, waist radius %g m, "
                "hem radius %g m,\n# %d rings, %d vertices, %d triangles "
                "(scripts/make-skirt.py)\n"
                % (R_WAIST, R_HEM, RINGS, len(verts), len(tris)))
        for x, y, z in verts:
            f.write("v %.9f %.9f %.9f\n" % (x, y, z))
        for t in tris:
            f.write("f %d %d %d\n" % (t[0] + 1, t[1] + 1, t[2] + 1))
    amin, ratio = quality(verts, tris)
    print("%s: %d vertices, %d triangles, smallest angle %.1f deg, "
          "area ratio %.2f" % (path, len(verts), len(tris), amin, ratio))


if __name__ == "__main__":
    main()
