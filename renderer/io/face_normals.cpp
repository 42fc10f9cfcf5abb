#include "io/face_normals.h"

#include <assimp/SceneCombiner.h>

#include <algorithm>
#include <cstdint>
#include <map>
#include <utility>
#include <vector>

#include "core/error.h"

namespace glint {

namespace {

// Triangles alone, as Assimp's SortByPType leaves a mesh that has any (the triangulation may
// add its flag for polygons it split).
bool isTriangleMesh(const aiMesh& m) {
  return (m.mPrimitiveTypes & aiPrimitiveType_TRIANGLE) &&
         !(m.mPrimitiveTypes &
           (aiPrimitiveType_POINT | aiPrimitiveType_LINE | aiPrimitiveType_POLYGON));
}

// The values per corner of a per-vertex array (aiVector3D or aiColor4D), replacing it.
template <class T>
void perCorner(T*& values, const aiMesh& m, unsigned corners) {
  if (!values) return;
  T* out = new T[corners];
  for (unsigned f = 0; f < m.mNumFaces; ++f)
    for (unsigned c = 0; c < 3; ++c) out[3 * f + c] = values[m.mFaces[f].mIndices[c]];
  delete[] values;
  values = out;
}

void giveFlatNormals(aiMesh& m, const std::string& path) {
  if (uint64_t{3} * m.mNumFaces > UINT32_MAX)
    throw GlintError("mesh " + path + ": mesh " + std::string(m.mName.C_Str()) + " has " +
                     std::to_string(m.mNumFaces) + " triangles, more than Glint can give normals");
  const unsigned corners = 3 * m.mNumFaces;
  perCorner(m.mVertices, m, corners);
  perCorner(m.mTangents, m, corners);
  perCorner(m.mBitangents, m, corners);
  for (auto*& colours : m.mColors) perCorner(colours, m, corners);
  for (auto*& uvs : m.mTextureCoords) perCorner(uvs, m, corners);
  for (unsigned b = 0; b < m.mNumBones; ++b) delete m.mBones[b];
  delete[] m.mBones;
  m.mBones = nullptr;
  m.mNumBones = 0;
  for (unsigned a = 0; a < m.mNumAnimMeshes; ++a) delete m.mAnimMeshes[a];
  delete[] m.mAnimMeshes;
  m.mAnimMeshes = nullptr;
  m.mNumAnimMeshes = 0;
  m.mNumVertices = corners;
  m.mNormals = new aiVector3D[corners];
  for (unsigned f = 0; f < m.mNumFaces; ++f) {
    const aiVector3D* p = m.mVertices + 3 * f;
    aiVector3D n = (p[1] - p[0]) ^ (p[2] - p[0]);
    const ai_real length = n.Length();
    n = length > 0 ? n / length : aiVector3D();
    for (unsigned c = 0; c < 3; ++c) {
      m.mNormals[3 * f + c] = n;
      m.mFaces[f].mIndices[c] = 3 * f + c;
    }
  }
}

void reverseWinding(aiMesh& m) {
  for (unsigned f = 0; f < m.mNumFaces; ++f)
    if (m.mFaces[f].mNumIndices == 3) std::swap(m.mFaces[f].mIndices[1], m.mFaces[f].mIndices[2]);
}

}  // namespace

bool someMeshesLackNormals(const aiScene& s) {
  bool with = false, without = false;
  for (unsigned mi = 0; mi < s.mNumMeshes; ++mi)
    if (isTriangleMesh(*s.mMeshes[mi])) (s.mMeshes[mi]->mNormals ? with : without) = true;
  return with && without;
}

void giveFlatNormalsWhereMissing(aiScene& s, const std::string& path) {
  for (unsigned mi = 0; mi < s.mNumMeshes; ++mi)
    if (aiMesh& m = *s.mMeshes[mi]; isTriangleMesh(m) && !m.mNormals) giveFlatNormals(m, path);
}

void windMirroredTrianglesOutward(aiScene& s) {
  // Each mesh's placements: (node, slot in its mesh list), mirrored or not.
  struct Placement {
    aiNode* node;
    unsigned slot;
    bool mirrored;
  };
  std::vector<Placement> placements;
  std::vector<std::pair<aiNode*, aiMatrix4x4>> stack{{s.mRootNode, aiMatrix4x4()}};
  while (!stack.empty()) {
    const auto [node, parent] = stack.back();
    stack.pop_back();
    if (!node) continue;
    const aiMatrix4x4 world = parent * node->mTransformation;
    for (unsigned i = 0; i < node->mNumMeshes; ++i)
      placements.push_back({node, i, world.Determinant() < 0});
    for (unsigned c = 0; c < node->mNumChildren; ++c) stack.emplace_back(node->mChildren[c], world);
  }
  std::vector<int> mirroredUses(s.mNumMeshes, 0), plainUses(s.mNumMeshes, 0);
  for (const Placement& p : placements)
    if (const unsigned mi = p.node->mMeshes[p.slot]; mi < s.mNumMeshes)
      ++(p.mirrored ? mirroredUses : plainUses)[mi];
  // A mesh placed only mirrored is turned where it is; one placed both ways gets a turned copy
  // for its mirrored placements.
  std::map<unsigned, unsigned> turnedCopy;
  std::vector<aiMesh*> added;
  for (const Placement& p : placements) {
    const unsigned mi = p.node->mMeshes[p.slot];
    if (!p.mirrored || mi >= s.mNumMeshes) continue;
    if (plainUses[mi] == 0) {
      if (mirroredUses[mi] > 0) reverseWinding(*s.mMeshes[mi]);
      mirroredUses[mi] = 0;  // turned once
      continue;
    }
    auto [it, isNew] = turnedCopy.emplace(mi, s.mNumMeshes + static_cast<unsigned>(added.size()));
    if (isNew) {
      aiMesh* copy = nullptr;
      Assimp::SceneCombiner::Copy(&copy, s.mMeshes[mi]);
      reverseWinding(*copy);
      added.push_back(copy);
    }
    p.node->mMeshes[p.slot] = it->second;
  }
  if (added.empty()) return;
  auto** meshes = new aiMesh*[s.mNumMeshes + added.size()];
  std::copy(s.mMeshes, s.mMeshes + s.mNumMeshes, meshes);
  std::copy(added.begin(), added.end(), meshes + s.mNumMeshes);
  delete[] s.mMeshes;
  s.mMeshes = meshes;
  s.mNumMeshes += static_cast<unsigned>(added.size());
}

}  // namespace glint
