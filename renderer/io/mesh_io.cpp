#include "io/mesh_io.h"

#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <assimp/Importer.hpp>
#include <cmath>
#include <filesystem>

#include "core/error.h"
#include "core/input_files.h"

namespace glint {

TriangleMesh loadMeshFile(const std::string& path) {
  if (!std::filesystem::is_regular_file(path)) throw GlintError("mesh file not found: " + path);
  noteInputFile(path);
  Assimp::Importer importer;
  // Meshes are shaded flat from their triangles for now, so normals and UVs are not imported.
  importer.SetPropertyInteger(AI_CONFIG_PP_RVC_FLAGS, aiComponent_NORMALS | aiComponent_COLORS |
                                                          aiComponent_TEXCOORDS |
                                                          aiComponent_MATERIALS);
  // Read with no processing but Assimp's own validation: its post-processing steps index
  // vertices through the faces before any check of ours, and a face naming a vertex that does
  // not exist made them read and write out of bounds.
  const aiScene* s = importer.ReadFile(path, aiProcess_ValidateDataStructure);
  if (!s || !s->mRootNode)
    throw GlintError("cannot read mesh " + path + ": " + excerpt(importer.GetErrorString()));
  for (unsigned mi = 0; mi < s->mNumMeshes; ++mi) {
    const aiMesh* m = s->mMeshes[mi];
    for (unsigned f = 0; f < m->mNumFaces; ++f)
      for (unsigned c = 0; c < m->mFaces[f].mNumIndices; ++c)
        if (m->mFaces[f].mIndices[c] >= m->mNumVertices)
          throw GlintError("mesh " + path + ": face " + std::to_string(f) + " of mesh " +
                           std::to_string(mi) + " names vertex " +
                           std::to_string(m->mFaces[f].mIndices[c]) + ", but there are only " +
                           std::to_string(m->mNumVertices));
  }
  // Check for NaN and Inf before Assimp joins vertices: its vertex welding compares positions
  // and would silently merge or drop non-finite ones.
  for (unsigned mi = 0; mi < s->mNumMeshes; ++mi)
    for (unsigned v = 0; v < s->mMeshes[mi]->mNumVertices; ++v) {
      const aiVector3D& p = s->mMeshes[mi]->mVertices[v];
      if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
        throw GlintError("mesh " + path + ": vertex " + std::to_string(v) + " of mesh " +
                         std::to_string(mi) + " is not finite (" + std::to_string(p.x) + ", " +
                         std::to_string(p.y) + ", " + std::to_string(p.z) + ")");
    }
  s = importer.ApplyPostProcessing(aiProcess_Triangulate | aiProcess_RemoveComponent |
                                   aiProcess_SortByPType);
  if (!s) throw GlintError("cannot process mesh " + path + ": " + importer.GetErrorString());
  s = importer.ApplyPostProcessing(aiProcess_JoinIdenticalVertices |
                                   aiProcess_PreTransformVertices);
  if (!s) throw GlintError("cannot process mesh " + path + ": " + importer.GetErrorString());
  TriangleMesh mesh;
  for (unsigned mi = 0; mi < s->mNumMeshes; ++mi) {
    const aiMesh* m = s->mMeshes[mi];
    if (!(m->mPrimitiveTypes & aiPrimitiveType_TRIANGLE)) continue;  // points and lines
    const auto base = static_cast<uint32_t>(mesh.positions.size());
    for (unsigned v = 0; v < m->mNumVertices; ++v) {
      const aiVector3D& p = m->mVertices[v];
      mesh.positions.push_back({p.x, p.y, p.z});
    }
    for (unsigned f = 0; f < m->mNumFaces; ++f) {
      const aiFace& face = m->mFaces[f];
      if (face.mNumIndices != 3) continue;
      for (int c = 0; c < 3; ++c) mesh.indices.push_back(base + face.mIndices[c]);
    }
  }
  if (mesh.indices.empty()) throw GlintError("mesh " + path + " has no triangles");
  return mesh;
}

}  // namespace glint
