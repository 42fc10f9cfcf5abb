#!/usr/bin/env python3
"""Writes a large PLY mesh for measuring mesh loading (docs/performance.md, "Loading big meshes").

A torus tessellated into an N x N grid of quads, each split into two triangles: N*N vertices and
exactly 2*N*N triangles, closed, none degenerate, every vertex shared by six triangles (as in a
real scanned or subdivided mesh, unlike a triangle soup). N = 1000 gives 1 000 000 vertices and
2 000 000 triangles.

  tools/make-big-ply.py /tmp/torus-2m.ply                    # 2M triangles, binary LE, x y z
  tools/make-big-ply.py /tmp/torus-2m-n.ply --normals        # with nx ny nz
  tools/make-big-ply.py /tmp/t.ply --grid 100 --format ascii # 20 000 triangles, ASCII

Only the standard library: the rows are packed with struct, a few seconds for N = 1000.
"""
import argparse
import math
import struct
import sys


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("out")
    ap.add_argument("--grid", type=int, default=1000, help="N: N*N vertices, 2*N*N triangles")
    ap.add_argument("--normals", action="store_true", help="add float nx ny nz per vertex")
    ap.add_argument("--format", default="binary_little_endian",
                    choices=["binary_little_endian", "binary_big_endian", "ascii"])
    args = ap.parse_args()
    n = args.grid
    if n < 3:
        sys.exit("--grid must be at least 3")
    props = ["x", "y", "z"] + (["nx", "ny", "nz"] if args.normals else [])
    header = "ply\nformat %s 1.0\ncomment tools/make-big-ply.py --grid %d\n" % (args.format, n)
    header += "element vertex %d\n" % (n * n)
    header += "".join("property float %s\n" % p for p in props)
    header += "element face %d\n" % (2 * n * n)
    header += "property list uchar int vertex_indices\nend_header\n"
    big, small = 2.0, 0.6  # torus radii
    cos = [math.cos(2 * math.pi * i / n) for i in range(n)]
    sin = [math.sin(2 * math.pi * i / n) for i in range(n)]
    ascii = args.format == "ascii"
    endian = ">" if args.format == "binary_big_endian" else "<"
    with open(args.out, "wb") as out:
        out.write(header.encode())
        vfmt = endian + "f" * len(props) * n
        for i in range(n):  # around the big circle
            row = []
            for j in range(n):  # around the tube
                nx, ny, nz = cos[i] * cos[j], sin[i] * cos[j], sin[j]
                row += [(big + small * cos[j]) * cos[i], (big + small * cos[j]) * sin[i],
                        small * sin[j]]
                if args.normals:
                    row += [nx, ny, nz]
            if ascii:
                k = len(props)
                out.write("".join(" ".join("%.7g" % v for v in row[p:p + k]) + "\n"
                                  for p in range(0, len(row), k)).encode())
            else:
                out.write(struct.pack(vfmt, *row))
        ffmt = endian + "Biii" * (2 * n)
        for i in range(n):
            i1 = (i + 1) % n
            row = []
            for j in range(n):
                j1 = (j + 1) % n
                a, b, c, d = i * n + j, i1 * n + j, i1 * n + j1, i * n + j1
                row += [3, a, b, c, 3, a, c, d]
            if ascii:
                out.write("".join("3 %d %d %d\n" % tuple(row[p + 1:p + 4])
                                  for p in range(0, len(row), 4)).encode())
            else:
                out.write(struct.pack(ffmt, *row))


if __name__ == "__main__":
    main()
