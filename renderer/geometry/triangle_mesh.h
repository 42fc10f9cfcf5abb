#pragma once
// Triangle mesh in the layout Embree shares without copying: packed float3 positions (with one
// float of tail padding, which Embree's 16-byte loads need) and uint32 index triples, with the
// per-vertex normals of a smooth-shaded mesh beside them.
#include <cstdint>
#include <vector>

#include "core/bounds.h"
#include "core/motion.h"
#include "core/rgb.h"
#include "core/vec.h"

namespace glint {

struct TriangleMesh {
  std::vector<Vec3f> positions;   // capacity ≥ size + 1: see padForEmbree()
  std::vector<uint32_t> indices;  // 3 per triangle
  // A deforming mesh: positions at K ≥ 2 keys spread evenly over [0, 1] (key 0 equals
  // `positions`). Empty for a static mesh.
  std::vector<std::vector<Vec3f>> positionKeys;
  // Per-vertex shading normals (unit, in the mesh's space), interpolated across each triangle;
  // empty for a mesh shaded flat from its triangles. A deforming mesh has none.
  std::vector<Vec3f> normals;
  // Per-vertex texture coordinates (u, v), origin at the image's bottom left; empty when the
  // mesh has none (its triangles then map (0,0), (1,0), (0,1) to their corners).
  std::vector<Vec2f> uvs;
  // A second set (glTF's TEXCOORD_1), as many as `uvs`, where the file has one; empty
  // otherwise (textures that ask for it then read the first).
  std::vector<Vec2f> uvs1;
  // Per-vertex colours (linear RGB), empty when the mesh has none.
  std::vector<Rgb> colors;
  // Per triangle, the object it belongs to, where a mesh file's parts name several (a file's
  // nodes merged per material): in a Scene the object id (Scene::objectNames), in a MeshFile
  // the index of the name in MeshFile::objectNames. Empty: the whole mesh is one object.
  std::vector<uint32_t> objectIds;
  // Per triangle corner (3 per triangle, as `indices`), the tangent normal maps are read in:
  // unit, along +u, in the mesh's space, with the sign that turns normal × tangent towards +v
  // (glTF's TANGENT w). From the file, or generated (geometry/tangents.h) for a mesh under a
  // normal map; empty otherwise. Per corner, not per vertex: generated tangents split where
  // the texture coordinates are mirrored or cut.
  struct Tangent {
    Vec3f direction;
    float sign = 1;
  };
  std::vector<Tangent> tangents;

  bool deforming() const { return !positionKeys.empty(); }
  bool smooth() const { return !normals.empty(); }
  bool hasUvs() const { return !uvs.empty(); }
  size_t triangleCount() const { return indices.size() / 3; }
  Vec3f vertex(uint32_t tri, int corner) const {
    return positions[indices[3 * tri + static_cast<uint32_t>(corner)]];
  }
  // Corner of a triangle at normalised time `time` (linear between keys, as Embree does).
  // The static case inlined at every hit; the keys' interpolation out of line.
  [[gnu::always_inline]] Vec3f vertexAt(uint32_t tri, int corner, float time) const {
    if (!deforming()) [[likely]]
      return vertex(tri, corner);
    return vertexBetweenKeys(tri, corner, time);
  }
  [[gnu::noinline]] Vec3f vertexBetweenKeys(uint32_t tri, int corner, float time) const {
    const uint32_t i = indices[3 * tri + static_cast<uint32_t>(corner)];
    size_t seg;
    float f;
    motionSegment(positionKeys.size(), time, seg, f);
    return (1 - f) * positionKeys[seg][i] + f * positionKeys[seg + 1][i];
  }
  // Bounds over the whole motion.
  Bounds3f bounds() const {
    Bounds3f b;
    for (const auto& p : positions) b.extend(p);
    for (const auto& key : positionKeys)
      for (const auto& p : key) b.extend(p);
    return b;
  }
  // Embree reads vertex buffers with 16-byte loads, so the last vertex needs 4 spare bytes.
  void padForEmbree() {
    positions.reserve(positions.size() + 1);
    for (auto& key : positionKeys) key.reserve(key.size() + 1);
  }
};

}  // namespace glint
