#!/usr/bin/env python3
"""Writes sky.png, the bundled equirectangular environment map: a sky gradient with a sun, a horizon
haze and a checkered ground, 8-bit sRGB, 256x128 texels. The texel at column i, row j (from the top)
shows the direction at u = (i + 1/2)/256, v = 1 - (j + 1/2)/128 with Facet's mapping
(src/shading/environment.h): phi = 2 pi (u - 1/2), theta = pi (v - 1/2),
d = (cos theta sin phi, sin theta, -cos theta cos phi). Run: python3 make_sky.py [out.png]"""
import math
import struct
import sys
import zlib

WIDTH, HEIGHT = 256, 128
SUN = (math.radians(45.0), math.radians(30.0))  # azimuth (phi), elevation (theta)


def direction(phi, theta):
    return (math.cos(theta) * math.sin(phi), math.sin(theta), -math.cos(theta) * math.cos(phi))


def mix(a, b, t):
    return tuple(x + (y - x) * t for x, y in zip(a, b))


def radiance(phi, theta):
    d = direction(phi, theta)
    y = d[1]
    if y >= 0.0:
        horizon, zenith = (0.70, 0.80, 0.95), (0.10, 0.25, 0.70)
        color = mix(horizon, zenith, math.sqrt(y))
        s = direction(*SUN)
        cosine = sum(a * b for a, b in zip(d, s))
        angle = math.acos(max(-1.0, min(1.0, cosine)))
        if angle < math.radians(5.0):
            return (1.0, 0.97, 0.85)
        glow = math.exp(-angle / math.radians(12.0)) * 0.5
        return tuple(min(1.0, c + glow * k) for c, k in zip(color, (1.0, 0.9, 0.6)))
    # The ground: a checkerboard of 16 columns and 4 rows of latitude, darker towards the nadir.
    column = int((phi + math.pi) / (2.0 * math.pi) * 16.0) % 16
    row = int(-theta / (math.pi / 2.0) * 4.0)
    base = (0.30, 0.22, 0.12) if (column + row) % 2 == 0 else (0.12, 0.20, 0.08)
    return mix(base, (0.04, 0.04, 0.04), -y * 0.6)


def encode(c):
    c = max(0.0, min(1.0, c))
    s = 12.92 * c if c <= 0.0031308 else 1.055 * c ** (1.0 / 2.4) - 0.055
    return int(round(s * 255.0))


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else "sky.png"
    rows = bytearray()
    for j in range(HEIGHT):
        rows.append(0)  # filter: none
        v = 1.0 - (j + 0.5) / HEIGHT
        for i in range(WIDTH):
            u = (i + 0.5) / WIDTH
            rows.extend(encode(c) for c in radiance(2.0 * math.pi * (u - 0.5), math.pi * (v - 0.5)))

    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data))

    png = b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", WIDTH, HEIGHT, 8, 2, 0, 0, 0))
    png += chunk(b"IDAT", zlib.compress(bytes(rows), 9)) + chunk(b"IEND", b"")
    with open(out, "wb") as f:
        f.write(png)


if __name__ == "__main__":
    main()
