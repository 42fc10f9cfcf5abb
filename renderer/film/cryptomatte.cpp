#include "film/cryptomatte.h"

#include <nlohmann/json.hpp>

#include <cstdio>
#include <cstring>

#include "core/murmur_hash3.h"

namespace glint {

float cryptomatteIdFromHash(uint32_t hash) {
  const uint32_t exponent = hash >> 23 & 0xff;
  if (exponent == 0 || exponent == 0xff) hash ^= 1u << 23;
  float id;
  std::memcpy(&id, &hash, 4);
  return id;
}

float cryptomatteId(std::string_view name) {
  return cryptomatteIdFromHash(murmurHash3_x86_32(name, 0));
}

std::string cryptomatteHex(float id) {
  uint32_t bits;
  std::memcpy(&bits, &id, 4);
  char hex[9];
  std::snprintf(hex, sizeof hex, "%08x", bits);
  return hex;
}

std::string cryptomatteKey(std::string_view typeName) {
  return cryptomatteHex(cryptomatteId(typeName)).substr(0, 7);
}

std::string cryptomatteManifest(const std::vector<std::string>& names) {
  nlohmann::json manifest = nlohmann::json::object();  // keys sorted: the same text every run
  for (const std::string& name : names) manifest[name] = cryptomatteHex(cryptomatteId(name));
  // Names are the scene's, in any bytes: invalid UTF-8 is replaced rather than refused.
  return manifest.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
}

size_t addCryptomatteLayers(Film& film, const std::string& typeName,
                            const std::vector<std::string>& names) {
  size_t first = SIZE_MAX;
  for (int layer = 0; layer < (kCryptomatteRanks + 1) / 2; ++layer) {
    char suffix[3];
    std::snprintf(suffix, sizeof suffix, "%02d", layer);
    const std::string name = typeName + suffix;
    const size_t plane = film.addPlane(name, {name + ".R", name + ".G", name + ".B", name + ".A"});
    if (layer == 0) first = plane;
  }
  const std::string prefix = "cryptomatte/" + cryptomatteKey(typeName) + "/";
  film.addAttribute(prefix + "name", typeName);
  film.addAttribute(prefix + "hash", "MurmurHash3_32");
  film.addAttribute(prefix + "conversion", "uint32_to_float32");
  film.addAttribute(prefix + "manifest", cryptomatteManifest(names));
  // The specification has no key for the rank count (readers count the layers); Glint's own.
  film.addAttribute("glint:cryptomatte_depth", kCryptomatteRanks);
  return first;
}

}  // namespace glint
