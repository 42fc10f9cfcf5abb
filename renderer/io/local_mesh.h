#pragma once
// The loader's meshes before they are placed, and the parsing shared by plain objects
// (object_loader.cpp) and CSG operands (csg_loader.cpp). Internal to io/.
#include <cstdint>
#include <string>
#include <vector>

#include "io/scene_builder.h"

namespace glint {

// A mesh in the object's local coordinates, kept in double until it is placed.
struct LocalMesh {
  std::vector<Vec3d> positions;
  std::vector<Vec3d> normals;                    // per vertex, for smooth shading; empty: flat
  std::vector<Vec2f> uvs;                        // per vertex texture coordinates; may be empty
  std::vector<Vec2f> uvs1;                       // a second set (glTF TEXCOORD_1); may be empty
  std::vector<Rgb> colors;                       // per vertex colours; may be empty
  std::vector<TriangleMesh::Tangent> tangents;   // per corner, from the file; may be empty
  std::vector<std::vector<Vec3d>> positionKeys;  // a deforming mesh's vertices per motion key
  std::vector<uint32_t> indices;
  // Per triangle, its object (TriangleMesh::objectIds); empty: one object.
  std::vector<uint32_t> objectIds;
};

// A mesh file's parts (one per material its triangles use), their materials and the names
// the parts' objectIds index (MeshFile::objectNames).
struct FileMesh {
  std::vector<LocalMesh> parts;
  std::vector<Material> materials;
  std::vector<std::string> objectNames;
};

// The material named by obj's "material" (an error naming the nearest name when there is none).
uint32_t materialOf(SceneBuilder& b, const JsonNode& obj);
// Appends a geometry entry to group `groupId`; returns its index in the group.
uint32_t push(Scene& s, uint32_t groupId, GeomKind kind, uint32_t index, uint32_t material,
              uint32_t objectId);
// At least `minCount` [x, y, z] points.
std::vector<Vec3d> parsePoints(const JsonNode& n, size_t minCount);
// The 12 triangles of a box, wound counter-clockwise seen from outside.
LocalMesh boxMesh(const Vec3d& lo, const Vec3d& hi);
// A mesh given inline: "positions", "indices", optional "normals" and "uvs".
LocalMesh inlineMesh(const JsonNode& obj);
// A mesh file's parts and materials; errors name `fileNode`.
FileMesh fileMesh(SceneBuilder& b, const JsonNode& fileNode);

}  // namespace glint
