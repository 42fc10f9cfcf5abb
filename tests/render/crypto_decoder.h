#pragma once
// A Cryptomatte decoder written from the specification (not from film/cryptomatte.cpp): it
// finds a type's layers through the metadata, a name's ID through the manifest, and sums that
// ID's coverage over the ranks, as a compositor's Cryptomatte node does.
#include <gtest/gtest.h>

#include <OpenImageIO/imageio.h>
#include <nlohmann/json.hpp>

#include <cstdio>
#include <cstring>
#include <map>
#include <string>
#include <vector>

namespace glint::test {

inline uint32_t bitsOf(float f) {
  uint32_t u;
  std::memcpy(&u, &f, 4);
  return u;
}

struct CryptoFile {
  std::map<std::string, std::string> attributes;       // every string attribute
  std::map<std::string, std::vector<float>> channels;  // by channel name
  int width = 0, height = 0;
  int depth = 0;  // glint:cryptomatte_depth
};

inline CryptoFile readCryptoFile(const std::string& path) {
  CryptoFile f;
  auto in = OIIO::ImageInput::open(path);
  EXPECT_TRUE(in) << path;
  if (!in) return f;
  const OIIO::ImageSpec& s = in->spec();
  f.width = s.width;
  f.height = s.height;
  for (const OIIO::ParamValue& p : s.extra_attribs)
    if (p.type() == OIIO::TypeDesc::STRING) f.attributes[p.name().string()] = p.get_string();
  f.depth = s.get_int_attribute("glint:cryptomatte_depth", 0);
  for (int c = 0; c < s.nchannels; ++c) {
    std::vector<float> v(size_t(s.width) * size_t(s.height));
    EXPECT_TRUE(in->read_image(0, 0, c, c + 1, OIIO::TypeDesc::FLOAT, v.data()));
    f.channels[s.channelnames[size_t(c)]] = std::move(v);
  }
  return f;
}

// One Cryptomatte type of a file: its layer name, its manifest (name → ID bits), and its ranks
// per pixel (ID bits, coverage), in layer order {type}00.R/G, {type}00.B/A, {type}01.R/G, ...
struct CryptoType {
  std::string key, name;
  std::map<std::string, uint32_t> manifest;
  int ranks = 0;

  // Sums the coverage of `id` over every rank of pixel i, as a keyer does.
  double coverage(const CryptoFile& f, size_t i, uint32_t id) const {
    double sum = 0;
    for (int r = 0; r < ranks; ++r)
      if (bitsOf(idAt(f, i, r)) == id) sum += coverageAt(f, i, r);
    return sum;
  }
  float idAt(const CryptoFile& f, size_t i, int rank) const {
    return f.channels.at(channel(rank, 0))[i];
  }
  float coverageAt(const CryptoFile& f, size_t i, int rank) const {
    return f.channels.at(channel(rank, 1))[i];
  }
  std::string channel(int rank, int coverage) const {
    char layer[8];
    std::snprintf(layer, sizeof layer, "%02d", rank / 2);
    const char* rgba[] = {"R", "G", "B", "A"};
    return name + layer + "." + rgba[2 * (rank % 2) + coverage];
  }
};

inline CryptoType findType(const CryptoFile& f, const std::string& typeName) {
  CryptoType t;
  for (const auto& [k, v] : f.attributes) {
    // cryptomatte/KEY/name = TYPE
    if (k.rfind("cryptomatte/", 0) != 0 || k.size() < 5 || k.substr(k.size() - 5) != "/name" ||
        v != typeName)
      continue;
    t.key = k.substr(12, k.size() - 17);
    t.name = v;
  }
  EXPECT_FALSE(t.key.empty()) << "no cryptomatte/*/name = " << typeName;
  if (t.key.empty()) return t;
  const std::string prefix = "cryptomatte/" + t.key + "/";
  EXPECT_EQ(f.attributes.at(prefix + "hash"), "MurmurHash3_32");
  EXPECT_EQ(f.attributes.at(prefix + "conversion"), "uint32_to_float32");
  const auto manifest = nlohmann::json::parse(f.attributes.at(prefix + "manifest"));
  for (const auto& [name, hex] : manifest.items()) {
    EXPECT_EQ(hex.get<std::string>().size(), 8u) << name;
    t.manifest[name] = static_cast<uint32_t>(std::stoul(hex.get<std::string>(), nullptr, 16));
  }
  while (f.channels.count(t.channel(t.ranks, 0)) && f.channels.count(t.channel(t.ranks, 1)))
    ++t.ranks;
  return t;
}

}  // namespace glint::test
