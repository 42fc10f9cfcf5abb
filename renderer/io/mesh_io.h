#pragma once
// Triangle meshes from files through Assimp (or Glint's PLY reader): the mesh formats of
// io/scene_formats.h's table only, each checked before Assimp reads it (io/mesh_limits.h). The
// file's meshes are placed by their node transforms and merged per material: one triangle mesh
// for each material its triangles use, with that material mapped onto Glint's
// (io/mesh_materials.h); vertex normals are kept when every mesh has them. Each triangle keeps
// the name of the node that placed it.
#include <string>
#include <vector>

#include "geometry/triangle_mesh.h"
#include "io/file_scene_info.h"
#include "materials/material.h"

namespace glint {

struct MeshFile {
  std::vector<TriangleMesh> parts;  // at least one, each with triangles
  std::vector<Material> materials;  // materials[i] is parts[i]'s, named "FILE:NAME"
  // The names the file gives its triangles, which parts[i].objectIds index: each triangle's
  // node's name, else its mesh's (names a reader made up do not count: io/object_names.h), ""
  // for a triangle without one. Empty, and the parts without objectIds, when none has a name.
  std::vector<std::string> objectNames;
};

// Throws GlintError naming the path tried and the reason (Glint's or Assimp's).
// `readTextures` false leaves the image textures materials name unread (their slots keep their
// factors): the mesh fuzzer tests Glint's and Assimp's readers, not OpenImageIO's decoders.
MeshFile loadMeshFile(const std::string& path, bool readTextures = true);

// The cameras and lights of a mesh file of the table's MeshScene kind (Collada, FBX, ...), read
// through Assimp with the same checks (io/assimp_scene_info.h); throws UsageError naming the
// path and what is wrong.
FileSceneInfo readMeshFileSceneInfo(const std::string& path);

}  // namespace glint
