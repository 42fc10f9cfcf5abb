#include "integrator/aov.h"

#include <sstream>

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

}  // namespace glint
