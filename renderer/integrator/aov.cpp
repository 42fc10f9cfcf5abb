#include "integrator/aov.h"

#include <algorithm>
#include <sstream>

#include "core/check.h"
#include "core/error.h"

namespace glint {

namespace {
const Aov kOrder[] = {Aov::Depth,  Aov::Normal,   Aov::Albedo, Aov::Position, Aov::ObjectId,
                      Aov::Direct, Aov::Indirect, Aov::Lights, Aov::Variance, Aov::Cryptomatte};
}

const std::vector<std::string>& AovSet::names() {
  static const std::vector<std::string> n = {"depth",    "normal",     "albedo",   "position",
                                             "objectid", "direct",     "indirect", "lights",
                                             "variance", "cryptomatte"};
  return n;
}

AovSet AovSet::parse(const std::string& list) {
  AovSet set;
  std::stringstream in(list);
  for (std::string name; std::getline(in, name, ',');) {
    if (name.empty()) continue;
    bool found = false;
    for (size_t i = 0; i < names().size(); ++i)
      if (names()[i] == name) {
        set.add(kOrder[i]);
        found = true;
      }
    if (!found) {
      std::string all;
      for (const auto& n : names()) all += (all.empty() ? "" : ", ") + n;
      throw UsageError("--aov: unknown AOV " + inQuotes(name) + "; known: " + all);
    }
  }
  return set;
}

namespace {

const std::vector<AovPlane>& fixedPlanes() {
  static const std::vector<AovPlane> planes = {
      {Aov::Depth, "depth", {"Z"}},
      {Aov::Normal, "normal", {"N.X", "N.Y", "N.Z"}},
      {Aov::Albedo, "albedo", rgbChannels("Albedo")},
      {Aov::Position, "position", {"P.X", "P.Y", "P.Z"}},
      // Blender's name for its object index pass (pass IndexOB, channel X), which its EXR
      // reader and compositor take as a float pass; a channel it cannot name it drops, and a
      // part left with none stops its reading of the parts after it.
      {Aov::ObjectId, "objectid", {"IndexOB.X"}},
      {Aov::Direct, "direct", rgbChannels("direct")},
      {Aov::Indirect, "indirect", rgbChannels("indirect")},
      {Aov::Variance, "variance", rgbChannels("Variance")},
  };
  return planes;
}

}  // namespace

std::vector<std::string> rgbChannels(const std::string& layer) {
  return {layer + ".R", layer + ".G", layer + ".B"};
}

const AovPlane& aovPlane(Aov aov) {
  const std::vector<AovPlane>& planes = fixedPlanes();
  const auto it =
      std::find_if(planes.begin(), planes.end(), [&](const AovPlane& p) { return p.aov == aov; });
  GLINT_CHECK(it != planes.end());
  return *it;
}

const AovPlane* aovPlaneWithChannels(const std::vector<std::string>& channels) {
  for (const AovPlane& p : fixedPlanes())
    if (p.channels == channels) return &p;
  return nullptr;
}

}  // namespace glint
