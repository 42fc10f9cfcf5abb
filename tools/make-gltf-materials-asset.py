#!/usr/bin/env python3
"""Writes scenes/assets/gltf_materials/, the asset of scenes/gltf_materials.json: a glTF 2.0
file of four upright tiles, each showing one part of glTF's materials Glint renders, and its
PNG textures:
  - brushed: a metallic-roughness texture (blue: metal stripes; green: roughness rising down
    the tile) on an orange base colour;
  - occluded: an occlusion texture (red: darker towards the corners) at strength 0.8;
  - lamp: an emissive texture with KHR_materials_emissive_strength 3, read over (u, v) in
    [-0.5, 1.5]: its sampler clamps u to the edge and mirrors v;
  - decal: a base colour checker read through TEXCOORD_1 (texCoord 1), which tiles it 2 x 2,
    while TEXCOORD_0 spans the tile once.

Usage: tools/make-gltf-materials-asset.py [OUT_DIR]   (pure Python; its PNGs by tools/png_writer.py)
"""
import base64
import json
import math
import os
import struct
import sys

from png_writer import png

SIZE = 32  # texels per side of each texture


def image(texel):
    return png(SIZE, SIZE, [[v for x in range(SIZE) for v in texel(x, y)] for y in range(SIZE)])


def metal_rough(x, y):
    metal = 255 if (x // 4) % 2 else 0
    return [0, round(255 * y / (SIZE - 1)), metal]


def occlusion(x, y):
    cx, cy = (x + 0.5) / SIZE - 0.5, (y + 0.5) / SIZE - 0.5
    return [round(255 * max(0.0, 1 - 1.6 * (cx * cx + cy * cy))), 0, 0]


def glow(x, y):
    t = (x + 0.5) / SIZE
    ring = 0.5 + 0.5 * math.cos(2 * math.pi * (y + 0.5) / SIZE)
    return [round(255 * t), round(200 * ring), round(255 * (1 - t))]


def checker(x, y):
    return [230, 225, 210] if ((x // 8) + (y // 8)) % 2 else [40, 70, 140]


def asset():
    positions, indices = [], [0, 1, 2, 0, 2, 3]
    for i in range(4):  # tiles at x in [1.2 i, 1.2 i + 1], y in [0, 1]
        x0 = 1.2 * i
        positions.append([x0, 0, 0, x0 + 1, 0, 0, x0 + 1, 1, 0, x0, 1, 0])
    uv_unit = [0, 1, 1, 1, 1, 0, 0, 0]  # glTF's v runs down the image
    uv_wide = [-0.5, 1.5, 1.5, 1.5, 1.5, -0.5, -0.5, -0.5]
    uv_twice = [0, 2, 2, 2, 2, 0, 0, 0]
    blob, views, accessors = b"", [], []

    def add(data, fmt, count, kind, component, extra=None):
        nonlocal blob
        blob += b"\0" * (-len(blob) % 4)
        raw = struct.pack("<%d%s" % (len(data), fmt), *data)
        views.append({"buffer": 0, "byteOffset": len(blob), "byteLength": len(raw)})
        blob += raw
        accessor = {"bufferView": len(views) - 1, "componentType": component, "count": count,
                    "type": kind}
        accessor.update(extra or {})
        accessors.append(accessor)
        return len(accessors) - 1

    index = add(indices, "H", 6, "SCALAR", 5123)
    uvs = {name: add(uv, "f", 4, "VEC2", 5126)
           for name, uv in (("unit", uv_unit), ("wide", uv_wide), ("twice", uv_twice))}
    meshes = []
    for i, p in enumerate(positions):
        pos = add(p, "f", 4, "VEC3", 5126,
                  {"min": [min(p[0::3]), 0, 0], "max": [max(p[0::3]), 1, 0]})
        attributes = {"POSITION": pos, "TEXCOORD_0": uvs["wide" if i == 2 else "unit"]}
        if i == 3:
            attributes["TEXCOORD_1"] = uvs["twice"]
        meshes.append({"name": ["brushed", "occluded", "lamp", "decal"][i],
                       "primitives": [{"attributes": attributes, "indices": index,
                                       "material": i}]})
    materials = [
        {"name": "brushed", "pbrMetallicRoughness": {
            "baseColorFactor": [0.95, 0.55, 0.2, 1], "metallicFactor": 1, "roughnessFactor": 0.6,
            "metallicRoughnessTexture": {"index": 0}}},
        {"name": "occluded", "pbrMetallicRoughness": {
            "baseColorFactor": [0.7, 0.75, 0.8, 1], "metallicFactor": 0, "roughnessFactor": 0.5},
         "occlusionTexture": {"index": 1, "strength": 0.8}},
        {"name": "lamp", "pbrMetallicRoughness": {
            "baseColorFactor": [0.05, 0.05, 0.05, 1], "metallicFactor": 0},
         "emissiveFactor": [1, 1, 1], "emissiveTexture": {"index": 2},
         "extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": 3}}},
        {"name": "decal", "pbrMetallicRoughness": {
            "baseColorTexture": {"index": 3, "texCoord": 1}, "metallicFactor": 0,
            "roughnessFactor": 0.4}},
    ]
    return {
        "asset": {"version": "2.0", "generator": "tools/make-gltf-materials-asset.py"},
        "extensionsUsed": ["KHR_materials_emissive_strength"],
        "scene": 0, "scenes": [{"nodes": [0, 1, 2, 3]}],
        "nodes": [{"name": m["name"], "mesh": i} for i, m in enumerate(meshes)],
        "meshes": meshes, "materials": materials,
        "textures": [{"source": 0}, {"source": 1}, {"source": 2, "sampler": 0},
                     {"source": 3}],
        "samplers": [{"wrapS": 33071, "wrapT": 33648}],  # CLAMP_TO_EDGE, MIRRORED_REPEAT
        "images": [{"uri": n} for n in
                   ("metal_rough.png", "occlusion.png", "glow.png", "checker.png")],
        "accessors": accessors, "bufferViews": views,
        "buffers": [{"byteLength": len(blob), "uri": "data:application/octet-stream;base64," +
                     base64.b64encode(blob).decode()}],
    }


if __name__ == "__main__":
    out = sys.argv[1] if len(sys.argv) > 1 else "scenes/assets/gltf_materials"
    os.makedirs(out, exist_ok=True)
    for name, texel in (("metal_rough", metal_rough), ("occlusion", occlusion), ("glow", glow),
                        ("checker", checker)):
        with open(os.path.join(out, name + ".png"), "wb") as f:
            f.write(image(texel))
    with open(os.path.join(out, "tiles.gltf"), "w") as f:
        json.dump(asset(), f, indent=1)
        f.write("\n")
