#include "io/fbx_axes.h"

#include <optional>

namespace glint {

namespace {

std::optional<int> metadataInt(const aiScene& s, const char* key) {
  int32_t value = 0;
  if (!s.mMetaData || !s.mMetaData->Get(key, value)) return std::nullopt;
  return value;
}

}  // namespace

bool turnFbxAxesToGlints(aiScene& s) {
  if (!s.mRootNode) return false;
  // The file's right, up and front axes in its coordinates: each a signed unit axis.
  aiVector3D axes[3];
  const char* names[3][2] = {
      {"CoordAxis", "CoordAxisSign"}, {"UpAxis", "UpAxisSign"}, {"FrontAxis", "FrontAxisSign"}};
  bool used[3] = {false, false, false};
  for (int i = 0; i < 3; ++i) {
    const auto axis = metadataInt(s, names[i][0]), sign = metadataInt(s, names[i][1]);
    if (!axis || !sign || *axis < 0 || *axis > 2 || used[*axis] || (*sign != 1 && *sign != -1))
      return false;
    used[*axis] = true;
    axes[i][static_cast<unsigned>(*axis)] = static_cast<ai_real>(*sign);
  }
  // The rows of the turn are the file's axes: right·p, up·p and front·p become x, y and z.
  const aiMatrix4x4 turn(axes[0].x, axes[0].y, axes[0].z, 0, axes[1].x, axes[1].y, axes[1].z, 0,
                         axes[2].x, axes[2].y, axes[2].z, 0, 0, 0, 0, 1);
  if (turn.IsIdentity()) return false;
  s.mRootNode->mTransformation = turn * s.mRootNode->mTransformation;
  return true;
}

}  // namespace glint
