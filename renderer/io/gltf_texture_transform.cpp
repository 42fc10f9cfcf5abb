#include "io/gltf_texture_transform.h"

#include <nlohmann/json.hpp>

#include <cmath>
#include <optional>

#include "core/error.h"
#include "core/log.h"

namespace glint {

namespace {

using nlohmann::json;

// `v` as a number, where it is a finite one within kMaxGltfUvTransformValue.
std::optional<double> boundedNumber(const json& v) {
  if (!v.is_number()) return std::nullopt;
  const double x = v.get<double>();
  if (!std::isfinite(x) || std::fabs(x) > kMaxGltfUvTransformValue) return std::nullopt;
  return x;
}

std::optional<Vec2f> boundedPair(const json& v) {
  if (!v.is_array() || v.size() != 2) return std::nullopt;
  const auto a = boundedNumber(v[0]), b = boundedNumber(v[1]);
  if (!a || !b) return std::nullopt;
  return Vec2f{float(*a), float(*b)};
}

}  // namespace

UvTransform uvTransformFromGltf(Vec2f offset, float rotation, Vec2f scale) {
  // A = T·R·S has the matrix M = R·S = [[c·su, s·sv], [−s·su, c·sv]] and the offset o. With
  // F(p) = D·p + e, D = diag(1, −1), e = (0, 1): F∘A∘F(p) = D·M·D·p + D·M·e + D·o + e, that is
  // the matrix [[c·su, −s·sv], [s·su, c·sv]] (a counter-clockwise turn by the same angle, now
  // that v runs up) and the offset (o_u + s·sv, 1 − o_v − c·sv). In double: sin and cos of
  // large angles, and the offset's sum, keep their digits.
  const double c = std::cos(double(rotation)), s = std::sin(double(rotation));
  const double su = scale.x, sv = scale.y;
  UvTransform t;
  t.m00 = float(c * su);
  t.m01 = float(-s * sv);
  t.m10 = float(s * su);
  t.m11 = float(c * sv);
  t.offset = {float(offset.x + s * sv), float(1 - offset.y - c * sv)};
  return t;
}

UvTransform gltfTextureTransform(const json& extension, const std::string& where, int uvSet) {
  UvTransform identity;
  identity.uvSet = uint8_t(uvSet);
  if (extension.is_null()) return identity;
  const std::string what = where + ": KHR_texture_transform";
  const auto ignored = [&](const std::string& why) {
    log::warning(what + " ignored (the texture is read untransformed): " + why);
    return identity;
  };
  if (!extension.is_object()) return ignored("it is not a JSON object");
  const std::string bounded =
      "finite, of magnitude at most " + std::to_string(int(kMaxGltfUvTransformValue));
  Vec2f offset{0, 0}, scale{1, 1};
  float rotation = 0;
  for (const char* key : {"offset", "scale"})
    if (const auto it = extension.find(key); it != extension.end()) {
      const auto pair = boundedPair(*it);
      if (!pair)
        return ignored(std::string("its ") + key + " " + excerpt(it->dump()) +
                       " is not two numbers, each " + bounded);
      (std::string(key) == "offset" ? offset : scale) = *pair;
    }
  if (const auto it = extension.find("rotation"); it != extension.end()) {
    const auto radians = boundedNumber(*it);
    if (!radians)
      return ignored("its rotation " + excerpt(it->dump()) + " is not a number " + bounded);
    rotation = float(*radians);
  }
  if (const auto it = extension.find("texCoord"); it != extension.end()) {
    if (it->is_number_unsigned() && it->get<uint64_t>() <= 1)
      uvSet = it->get<int>();
    else
      log::warning(what + "'s texCoord " + excerpt(it->dump()) +
                   " is not read (Glint reads TEXCOORD_0 and TEXCOORD_1): the transform applies "
                   "to TEXCOORD_" +
                   std::to_string(uvSet));
  }
  UvTransform t = uvTransformFromGltf(offset, rotation, scale);
  t.uvSet = uint8_t(uvSet);
  return t;
}

}  // namespace glint
