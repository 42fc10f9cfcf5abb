#!/usr/bin/env python3
"""Writes scenes/sky.hdr, the bundled environment: a 256 x 128 lat-long (equirectangular)
Radiance .hdr of a clear sky with a sun, in pure Python (no numpy).

Orientation as Glint reads it (docs/scene-format.md, "Environment light"): row 0 looks along
+Y, the image's centre along -Z, +X to its right. The sky runs from a deep blue zenith to a pale
horizon, the ground below is a dull brown, and a sun disc 2.5 degrees in radius stands 40
degrees above the horizon towards +Z and +X (u = 0.875): behind a camera that looks along -Z,
to its right, so that it lights the faces the camera sees and shows in a mirror in front of it.
Its radiance, 400, makes it give a surface facing it several times the sky's irradiance from
0.6 % of the sphere: a sun-dominated image, which importance sampling must find.

Usage: tools/make-sky.py [OUT.hdr]   (default: scenes/sky.hdr beside this script's folder)
"""
import math
import os
import sys

WIDTH, HEIGHT = 256, 128
SUN_ELEVATION = math.radians(40)
SUN_AZIMUTH = 2 * math.pi * (0.875 - 0.5)  # phi, 0 along -Z, positive towards +X
SUN_RADIUS = math.radians(2.5)
SUN_RADIANCE = (400.0, 380.0, 340.0)
ZENITH = (0.12, 0.25, 0.75)
HORIZON = (0.75, 0.82, 0.95)
GROUND = (0.16, 0.13, 0.10)


def direction(u, v):
    """The unit direction of image point (u, v), as Glint maps it."""
    theta, phi = math.pi * v, 2 * math.pi * (u - 0.5)
    return (math.sin(theta) * math.sin(phi), math.cos(theta), -math.sin(theta) * math.cos(phi))


def radiance(d, sun):
    cos_sun = sum(a * b for a, b in zip(d, sun))
    if cos_sun >= math.cos(SUN_RADIUS):
        return SUN_RADIANCE
    if d[1] < 0:
        return GROUND
    t = d[1] ** 0.5  # most of the blue high up, a wide pale band near the horizon
    return tuple(h + (z - h) * t for h, z in zip(HORIZON, ZENITH))


def rgbe(c):
    """Greg Ward's shared-exponent encoding of one colour."""
    v = max(c)
    if v < 1e-32:
        return bytes(4)
    m, e = math.frexp(v)
    scale = m * 256.0 / v
    return bytes([min(255, int(x * scale)) for x in c] + [e + 128])


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    out = sys.argv[1] if len(sys.argv) > 1 else os.path.join(here, "..", "scenes", "sky.hdr")
    ce, se = math.cos(SUN_ELEVATION), math.sin(SUN_ELEVATION)
    sun = (ce * math.sin(SUN_AZIMUTH), se, -ce * math.cos(SUN_AZIMUTH))
    body = bytearray()
    for y in range(HEIGHT):
        for x in range(WIDTH):
            # The mean of 4 x 4 points over the texel, so the sun's edge is antialiased.
            acc = [0.0, 0.0, 0.0]
            for j in range(4):
                for i in range(4):
                    c = radiance(direction((x + (i + 0.5) / 4) / WIDTH,
                                           (y + (j + 0.5) / 4) / HEIGHT), sun)
                    acc = [a + b / 16 for a, b in zip(acc, c)]
            body += rgbe(acc)
    header = "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y %d +X %d\n" % (HEIGHT, WIDTH)
    # Flat (not run-length encoded) scanlines: every reader of the format accepts them.
    with open(out + ".tmp", "wb") as f:
        f.write(header.encode("ascii") + bytes(body))
    os.replace(out + ".tmp", out)


if __name__ == "__main__":
    main()
