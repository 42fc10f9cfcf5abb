#!/usr/bin/env python3
"""Writes scenes/assets/cutouts/lattice.png, the cut-out texture of scenes/cutouts.json: a
64 x 64 RGBA lattice of wood-coloured bars (alpha 1) around 4 x 4 round holes (alpha 0), with
the holes' rims anti-aliased as an image editor would (alpha between 0 and 1 over one texel).

Usage: tools/make-cutout-texture.py [OUT.png]   (pure Python; its PNGs by tools/png_writer.py)
"""
import math
import sys

from png_writer import png

SIZE, CELLS, RADIUS = 64, 4, 5.5  # texels, holes per side, hole radius in texels


def texel(x, y):
    cell = SIZE / CELLS
    cx, cy = (x + 0.5) % cell - cell / 2, (y + 0.5) % cell - cell / 2
    alpha = min(1.0, max(0.0, math.hypot(cx, cy) - RADIUS + 0.5))
    grain = 0.85 + 0.15 * math.sin(0.9 * y + 0.3 * math.sin(0.5 * x))
    rgb = [round(255 * c * grain) for c in (0.55, 0.35, 0.18)]
    return rgb + [round(255 * alpha)]


if __name__ == "__main__":
    out = sys.argv[1] if len(sys.argv) > 1 else "scenes/assets/cutouts/lattice.png"
    rows = [[v for x in range(SIZE) for v in texel(x, y)] for y in range(SIZE)]
    with open(out, "wb") as f:
        f.write(png(SIZE, SIZE, rows, channels=4))
