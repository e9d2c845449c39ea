#!/usr/bin/env python3
"""Writes sphere.obj: a unit UV sphere (48 segments around, 24 rings) with vertex normals, for the
environment map scene. Run: python3 make_sphere.py [out.obj]"""
import math
import sys

SEGMENTS, RINGS = 32, 16


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else "sphere.obj"
    lines = ["# A unit UV sphere, " + str(SEGMENTS) + " segments, " + str(RINGS) + " rings (make_sphere.py)"]
    for r in range(RINGS + 1):
        theta = math.pi * r / RINGS
        for s in range(SEGMENTS + 1):
            phi = 2.0 * math.pi * s / SEGMENTS
            x, y, z = math.sin(theta) * math.cos(phi), math.cos(theta), -math.sin(theta) * math.sin(phi)
            lines.append("v %.5f %.5f %.5f" % (x, y, z))
            lines.append("vn %.5f %.5f %.5f" % (x, y, z))
    row = SEGMENTS + 1
    for r in range(RINGS):
        for s in range(SEGMENTS):
            a, b = r * row + s + 1, (r + 1) * row + s + 1
            # Counter-clockwise seen from outside.
            if r != 0:
                lines.append("f %d//%d %d//%d %d//%d" % (a, a, b, b, a + 1, a + 1))
            if r != RINGS - 1:
                lines.append("f %d//%d %d//%d %d//%d" % (a + 1, a + 1, b, b, b + 1, b + 1))
    with open(out, "w") as f:
        f.write("\n".join(lines) + "\n")


if __name__ == "__main__":
    main()
