#include "io/ac3d_shading.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdlib>
#include <sstream>
#include <string>
#include <unordered_map>

namespace glint {

namespace {

// The object a SURF line belongs to: the last OBJECT line before it (an object's own lines
// come before its `kids` line and the children after it).
struct ObjectState {
  double crease = kDefaultAc3dCreaseDegrees;
  bool smooth = false;
};

}  // namespace

Ac3dShading readAc3dShading(std::istream& in) {
  Ac3dShading out;
  ObjectState object;
  bool any = false;
  const auto finish = [&] {
    if (!object.smooth) return;
    if (any && object.crease != out.creaseDegrees) out.creasesDiffer = true;
    out.creaseDegrees = any ? std::max(out.creaseDegrees, object.crease) : object.crease;
    any = true;
  };
  for (std::string line; std::getline(in, line);) {
    std::istringstream words(line);
    std::string token;
    if (!(words >> token)) continue;
    if (token == "OBJECT") {
      finish();
      object = ObjectState{};
    } else if (token == "crease") {
      double degrees = 0;
      // As Assimp reads it; a value that is not an angle leaves the default.
      if (words >> degrees && std::isfinite(degrees) && degrees >= 0 && degrees <= 180)
        object.crease = degrees;
    } else if (token == "SURF") {
      std::string flags;
      words >> flags;
      const unsigned long value = std::strtoul(flags.c_str(), nullptr, 0);
      const unsigned long type = value & 0xF;
      if (type == 1 || type == 2) continue;  // a closed or open line: no surface
      if (value & 0x10) {
        ++out.smoothSurfaces;
        object.smooth = true;
      } else {
        ++out.flatSurfaces;
      }
    }
  }
  finish();
  return out;
}

std::vector<Vec3f> creaseNormals(std::span<const Vec3f> positions,
                                 std::span<const uint32_t> triangles, double creaseDegrees,
                                 size_t& crowded) {
  std::vector<Vec3f> face(positions.size(), Vec3f{0, 0, 0});
  for (size_t t = 0; t + 2 < triangles.size(); t += 3) {
    const Vec3f &a = positions[triangles[t]], &b = positions[triangles[t + 1]],
                &c = positions[triangles[t + 2]];
    const Vec3f n = cross(b - a, c - a);
    const float len = length(n);
    // A polygon's triangles share its corners: the first triangle with an area names them.
    for (size_t k = 0; k < 3; ++k)
      if (len > 0 && std::isfinite(len) && face[triangles[t + k]] == Vec3f{0, 0, 0})
        face[triangles[t + k]] = n / len;
  }
  // The vertices at each position, by the bits of its coordinates (the reader copies each
  // corner from one vertex list, so shared corners are equal bit for bit).
  using Bits = std::array<uint32_t, 3>;
  struct Hash {
    size_t operator()(const Bits& b) const {
      return std::hash<uint64_t>()((uint64_t{b[0]} * 0x9E3779B97F4A7C15ull) ^
                                   (uint64_t{b[1]} << 21) ^ (uint64_t{b[2]} << 42) ^ b[2]);
    }
  };
  std::unordered_map<Bits, std::vector<uint32_t>, Hash> at;
  for (uint32_t v = 0; v < positions.size(); ++v) {
    const Vec3f& p = positions[v];
    at[{std::bit_cast<uint32_t>(p.x), std::bit_cast<uint32_t>(p.y), std::bit_cast<uint32_t>(p.z)}]
        .push_back(v);
  }
  const float cosCrease = static_cast<float>(std::cos(creaseDegrees * M_PI / 180));
  std::vector<Vec3f> out(face);
  crowded = 0;
  for (const auto& [position, corners] : at) {
    if (corners.size() > kMaxCornersCompared) {
      ++crowded;
      continue;
    }
    for (const uint32_t v : corners) {
      if (face[v] == Vec3f{0, 0, 0}) continue;
      Vec3f sum{0, 0, 0};
      for (const uint32_t w : corners)
        if (dot(face[w], face[v]) >= cosCrease) sum = sum + face[w];
      // Faces facing apart (a crease of 180 takes both sides of a sheet) may cancel.
      const float len = length(sum);
      out[v] = len > 1e-6f ? sum / len : face[v];
    }
  }
  return out;
}

}  // namespace glint
