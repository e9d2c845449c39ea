#!/usr/bin/env python3
"""Writes a UV sphere of radius 1 centred at the origin as an OBJ with normals and texture coordinates.

    python3 make-sphere.py SEGMENTS RINGS NAME > NAME.obj

SEGMENTS meridians around the y axis, RINGS bands from pole to pole. Each vertex's normal is its
position (the exact normal of the unit sphere), its texture coordinate (u, v) = (longitude / 360°,
latitude from the south pole / 180°). The pole rows repeat their vertex once per segment so that
each triangle at a pole has its own u. Faces are triangles, counter-clockwise seen from outside.
The bundled files: sphere.obj is 32 × 16, sphere-coarse.obj 8 × 4 (its big triangles show what
Gouraud shading does to a highlight).
"""
import math
import sys


def main():
    segments, rings, name = int(sys.argv[1]), int(sys.argv[2]), sys.argv[3]
    out = sys.stdout
    out.write(f"# A unit sphere, {segments} segments x {rings} rings, written by make-sphere.py\n")
    out.write(f"mtllib sphere.mtl\no {name}\n")
    # Rows from the north pole (i = 0) to the south pole (i = rings), columns j = 0..segments (the
    # last repeats the first, with u = 1).
    for i in range(rings + 1):
        theta = math.pi * i / rings  # from +y
        for j in range(segments + 1):
            phi = 2.0 * math.pi * j / segments
            x = math.sin(theta) * math.sin(phi)
            y = math.cos(theta)
            z = math.sin(theta) * math.cos(phi)
            out.write(f"v {x:.6f} {y:.6f} {z:.6f}\n")
    for i in range(rings + 1):
        theta = math.pi * i / rings
        for j in range(segments + 1):
            phi = 2.0 * math.pi * j / segments
            out.write(f"vn {math.sin(theta) * math.sin(phi):.6f} {math.cos(theta):.6f} "
                      f"{math.sin(theta) * math.cos(phi):.6f}\n")
    for i in range(rings + 1):
        for j in range(segments + 1):
            out.write(f"vt {j / segments:.6f} {1.0 - i / rings:.6f}\n")
    out.write("usemtl sphere\ns 1\n")

    def index(i, j):
        return i * (segments + 1) + j + 1

    def face(a, b, c):
        out.write(f"f {a}/{a}/{a} {b}/{b}/{b} {c}/{c}/{c}\n")

    for i in range(rings):
        for j in range(segments):
            a, b = index(i, j), index(i, j + 1)  # upper row
            c, d = index(i + 1, j), index(i + 1, j + 1)  # lower row
            if i != 0:
                face(a, c, b)
            if i != rings - 1:
                face(b, c, d)


if __name__ == "__main__":
    main()
