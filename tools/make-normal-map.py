#!/usr/bin/env python3
"""Writes the textures of scenes/normal_maps.json into scenes/assets/normal_maps/: tiles_h.png,
the height of 4 x 4 square tiles with bevelled edges and a mortar groove between them (grey,
1 = a tile's top), and tiles_n.png, the same relief as a tangent-space normal map in glTF's
convention (+X right, +Y up the image, +Z out of the surface; texel = (n + 1) / 2), so the two
maps of one relief can be compared side by side.

Usage: tools/make-normal-map.py [OUT_DIR]   (pure Python; its PNGs by tools/png_writer.py)
"""
import math
import os
import sys

from png_writer import png

SIZE, TILES, BEVEL, GROOVE = 64, 4, 3.0, 1.0  # texels, tiles per side, bevel and groove widths
DEPTH = 2.0  # texels of relief per unit of height, for the normal map's slopes


def height(x, y):
    cell = SIZE / TILES
    edge = min((x + 0.5) % cell, cell - (x + 0.5) % cell, (y + 0.5) % cell,
               cell - (y + 0.5) % cell)
    return min(1.0, max(0.0, (edge - GROOVE) / BEVEL))


def normal(x, y):
    # Central differences with v up (image rows run down): dh/du = dh/dx, dh/dv = −dh/dy.
    dhdu = (height(x + 1, y) - height(x - 1, y)) / 2 * DEPTH
    dhdv = -(height(x, y + 1) - height(x, y - 1)) / 2 * DEPTH
    n = (-dhdu, -dhdv, 1.0)
    length = math.sqrt(sum(c * c for c in n))
    return [round(255 * (c / length + 1) / 2) for c in n]


if __name__ == "__main__":
    out = sys.argv[1] if len(sys.argv) > 1 else "scenes/assets/normal_maps"
    os.makedirs(out, exist_ok=True)
    heights = [[round(255 * height(x, y)) for x in range(SIZE) for _ in range(3)]
               for y in range(SIZE)]
    normals = [[c for x in range(SIZE) for c in normal(x, y)] for y in range(SIZE)]
    with open(os.path.join(out, "tiles_h.png"), "wb") as f:
        f.write(png(SIZE, SIZE, heights))
    with open(os.path.join(out, "tiles_n.png"), "wb") as f:
        f.write(png(SIZE, SIZE, normals))
