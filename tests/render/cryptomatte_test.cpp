// Cryptomatte: the hash and its float conversion against published values, and rendered files
// read back by the decoder of render/crypto_decoder.h, written from the specification.
#include <gtest/gtest.h>

#include <OpenImageIO/imageio.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <map>
#include <set>

#include "core/murmur_hash3.h"
#include "film/cryptomatte.h"
#include "render/crypto_decoder.h"
#include "test_util.h"

namespace glint {
namespace {

using test::bitsOf;
using test::CryptoFile;
using test::CryptoType;
using test::findType;
using test::readCryptoFile;

TEST(Cryptomatte, MurmurHash3MatchesPublishedVectors) {
  // MurmurHash3_x86_32 vectors as published with SMHasher's reference and collected in
  // https://stackoverflow.com/a/31929528 (Ian Boyd); each checked here against Psyop's pure-Python
  // pymmh3 (github.com/Psyop/Cryptomatte, nuke/pymmh3.py). Exact: a hash has no tolerance.
  EXPECT_EQ(murmurHash3_x86_32("", 0), 0x00000000u);
  EXPECT_EQ(murmurHash3_x86_32("", 1), 0x514e28b7u);
  EXPECT_EQ(murmurHash3_x86_32("", 0xffffffff), 0x81f16f39u);
  EXPECT_EQ(murmurHash3_x86_32(std::string_view("\0\0\0\0", 4), 0), 0x2362f9deu);
  EXPECT_EQ(murmurHash3_x86_32("aaaa", 0x9747b28c), 0x5a97808au);
  EXPECT_EQ(murmurHash3_x86_32("a", 0x9747b28c), 0x7fa09ea6u);    // 1-byte tail
  EXPECT_EQ(murmurHash3_x86_32("ab", 0x9747b28c), 0x74875592u);   // 2-byte tail
  EXPECT_EQ(murmurHash3_x86_32("abc", 0x9747b28c), 0xc84a62ddu);  // 3-byte tail
  EXPECT_EQ(murmurHash3_x86_32("abc", 0), 0xb3dd93fau);
  EXPECT_EQ(murmurHash3_x86_32("Hello, world!", 0x9747b28c), 0x24884cbau);
  EXPECT_EQ(murmurHash3_x86_32("The quick brown fox jumps over the lazy dog", 0x9747b28c),
            0x2fa826cdu);
  static_assert(murmurHash3_x86_32("abc") == 0xb3dd93fau, "usable at compile time");
}

TEST(Cryptomatte, IdsMatchTheSpecificationAndTheReferencePlugin) {
  // The specification's manifest examples (Cryptomatte specification, "Manifest" and "Metadata").
  EXPECT_EQ(cryptomatteHex(cryptomatteId("bunny")), "13851a76");
  EXPECT_EQ(cryptomatteHex(cryptomatteId("default")), "42c9679f");
  EXPECT_EQ(cryptomatteHex(cryptomatteId("bunny_porcelain_mat")), "b24b26d4");
  // The reference Nuke plugin's own test values (nuke/cryptomatte_utilities_tests.py,
  // CryptoHashing), UTF-8 names included; equal as float32 (the plugin compares them so).
  EXPECT_EQ(cryptomatteId("hello"), float(6.0705627102400005616e-17));
  EXPECT_EQ(cryptomatteId("cube"), float(-4.08461912519e+15));
  EXPECT_EQ(cryptomatteId("sphere"), float(2.79018604383e+15));
  EXPECT_EQ(cryptomatteId("plane"), float(3.66557617593e-11));
  EXPECT_EQ(cryptomatteId("\xd1\x80\xd0\xb0\xd0\xb2\xd0\xbd\xd0\xb8\xd0\xbd\xd0\xb0"),
            float(-1.3192631212399999468e-25));
  EXPECT_EQ(cryptomatteId("m\xc3\xa4"
                          "dchen"),
            float(6.2361298211599995797e+25));
  // Names whose hash has exponent 255 (a NaN pattern) and 0 (a denormal): hash from pymmh3,
  // converted by the plugin's mm3hash_float (bit 23 flipped).
  EXPECT_EQ(murmurHash3_x86_32("objects[83]"), 0x7fb1ac1au);
  EXPECT_EQ(cryptomatteHex(cryptomatteId("objects[83]")), "7f31ac1a");
  EXPECT_EQ(murmurHash3_x86_32("objects[294]"), 0x804c3b5du);
  EXPECT_EQ(cryptomatteHex(cryptomatteId("objects[294]")), "80cc3b5d");
  // Metadata keys: 7 hex digits of the type name's ID (the plugin's layer_hash).
  EXPECT_EQ(cryptomatteKey("CryptoObject"), "3ae39a5");
  EXPECT_EQ(cryptomatteKey("CryptoMaterial"), "be359d6");
}

TEST(Cryptomatte, ConversionIsTheSpecificationsRule) {
  // uint32_to_float32: the hash's bits, except that exponents 0 and 255 become 1 and 254 (the
  // lowest exponent bit flipped), so an ID is never zero, denormal, infinite or NaN.
  EXPECT_EQ(bitsOf(cryptomatteIdFromHash(0x00000000u)), 0x00800000u);  // zero → 2^-126
  EXPECT_EQ(bitsOf(cryptomatteIdFromHash(0x007fffffu)), 0x00ffffffu);  // denormal
  EXPECT_EQ(bitsOf(cryptomatteIdFromHash(0x80000001u)), 0x80800001u);  // negative denormal
  EXPECT_EQ(bitsOf(cryptomatteIdFromHash(0x7f800000u)), 0x7f000000u);  // +inf
  EXPECT_EQ(bitsOf(cryptomatteIdFromHash(0xffc00000u)), 0xff400000u);  // NaN
  EXPECT_EQ(bitsOf(cryptomatteIdFromHash(0x3f800000u)), 0x3f800000u);  // 1.0f: unchanged
  // Over a sweep of the 32-bit range (every 65521st value, a prime stride that visits every
  // exponent): always a normal float, equal to the hash but for bit 23 where the exponent was
  // 0 or 255.
  for (uint64_t h = 0; h <= 0xffffffffu; h += 65521) {
    const auto hash = static_cast<uint32_t>(h);
    const float id = cryptomatteIdFromHash(hash);
    ASSERT_TRUE(std::isnormal(id)) << std::hex << hash;
    const uint32_t exponent = hash >> 23 & 0xff;
    const uint32_t expected = exponent == 0 || exponent == 255 ? hash ^ 0x00800000u : hash;
    ASSERT_EQ(bitsOf(id), expected) << std::hex << hash;
  }
}

// Looking down −z at quads in z = 0, orthographic, one pixel per unit: pixel k spans
// x ∈ [k − 2, k − 1]. 16 regular samples per pixel at x offsets 0.125, 0.375, 0.625, 0.875
// (4 columns of 4). objects[0] (red) covers x < −0.75, objects[1] (red) −0.5 < x < 0.5,
// objects[2] (blue) 0.55 < x < 0.8; no edge falls on a sample column.
//   pixel 0: objects[0] all 16 samples → coverage 1
//   pixel 1: columns −0.875 objects[0], −0.375 and −0.125 objects[1], −0.625 background
//            → objects[1] 8/16, objects[0] 4/16; red 12/16
//   pixel 2: columns 0.125 and 0.375 objects[1], 0.625 objects[2], 0.875 background
//            → objects[1] 8/16, objects[2] 4/16; red 8/16, blue 4/16
//   pixel 3: background only
const char* kScene = R"({
  "render": {"width": 4, "height": 1, "spp": 16, "sampler": "regular", "ambient": [1,1,1],
             "transparent_background": true},
  "camera": {"type": "orthographic", "eye": [0,0,5], "look_at": [0,0,0], "height": 1},
  "materials": {"red": {"type": "phong", "ka": [1,0,0], "kd": [0,0,0]},
                "blue": {"type": "phong", "ka": [0,0,1], "kd": [0,0,0]},
                "unused": {"type": "phong"}},
  "objects": [
    {"type": "quad", "corner": [-3,-1,0], "edge1": [2.25,0,0], "edge2": [0,2,0], "material": "red"},
    {"type": "quad", "corner": [-0.5,-1,0], "edge1": [1,0,0], "edge2": [0,2,0], "material": "red"},
    {"type": "quad", "corner": [0.55,-1,0], "edge1": [0.25,0,0], "edge2": [0,2,0], "material": "blue"}]})";

TEST(Cryptomatte, DecodedCoverageMatchesTheKnownGeometry) {
  const std::string scene = test::writeTemp("crypto.json", kScene);
  const std::string out = (test::tempDir() / "crypto.exr").string();
  ASSERT_EQ(
      test::runGlint("render " + scene + " --quiet -o " + out + " --aov cryptomatte").exitCode, 0);
  const CryptoFile f = readCryptoFile(out);
  ASSERT_EQ(f.width, 4);
  const CryptoType objects = findType(f, "CryptoObject");
  const CryptoType materials = findType(f, "CryptoMaterial");
  // At least the specification's suggested 6 ranks (3 layers) per type.
  EXPECT_GE(objects.ranks, 6);
  EXPECT_GE(materials.ranks, 6);
  EXPECT_EQ(f.depth, objects.ranks);
  EXPECT_EQ(f.depth, materials.ranks);
  // The manifests list the scene's names: every object, every material (used or not).
  std::set<std::string> objectNames, materialNames;
  for (const auto& [name, id] : objects.manifest) objectNames.insert(name);
  for (const auto& [name, id] : materials.manifest) materialNames.insert(name);
  EXPECT_EQ(objectNames, (std::set<std::string>{"objects[0]", "objects[1]", "objects[2]"}));
  EXPECT_EQ(materialNames, (std::set<std::string>{"red", "blue", "unused"}));
  const uint32_t o0 = objects.manifest.at("objects[0]"), o1 = objects.manifest.at("objects[1]"),
                 o2 = objects.manifest.at("objects[2]");
  const uint32_t red = materials.manifest.at("red"), blue = materials.manifest.at("blue");

  // Coverages are k/16, exact in float, and the file stores them exactly: compared exactly.
  // Pixel 0: fully inside objects[0] and red.
  EXPECT_EQ(objects.coverage(f, 0, o0), 1.0);
  EXPECT_EQ(materials.coverage(f, 0, red), 1.0);
  // Pixel 1: an edge pixel; the background's quarter is not stored.
  EXPECT_EQ(objects.coverage(f, 1, o1), 0.5);
  EXPECT_EQ(objects.coverage(f, 1, o0), 0.25);
  EXPECT_EQ(materials.coverage(f, 1, red), 0.75);  // two objects of one material add up
  // Pixel 2: two objects, two materials.
  EXPECT_EQ(objects.coverage(f, 2, o1), 0.5);
  EXPECT_EQ(objects.coverage(f, 2, o2), 0.25);
  EXPECT_EQ(materials.coverage(f, 2, red), 0.5);
  EXPECT_EQ(materials.coverage(f, 2, blue), 0.25);
  // The covered samples of each pixel, counted from the geometry above.
  const double coveredFraction[4] = {1.0, 0.75, 0.75, 0.0};
  for (const CryptoType* type : {&objects, &materials})
    for (size_t i = 0; i < 4; ++i) {
      double sum = 0;
      for (int r = 0; r < type->ranks; ++r) {
        sum += type->coverageAt(f, i, r);
        // Ranks are sorted by coverage, most first; an empty rank is ID 0, coverage 0.
        if (r > 0) {
          EXPECT_LE(type->coverageAt(f, i, r), type->coverageAt(f, i, r - 1));
        }
        if (type->coverageAt(f, i, r) == 0) {
          EXPECT_EQ(type->idAt(f, i, r), 0.0f);
        }
      }
      EXPECT_EQ(sum, coveredFraction[i]) << type->name << " pixel " << i;
      // The beauty's alpha is the same share of samples.
      EXPECT_EQ(f.channels.at("A")[i], float(coveredFraction[i])) << i;
    }
  // The most covered object of pixel 1 is rank 0; the background pixel holds no ID at all.
  EXPECT_EQ(bitsOf(objects.idAt(f, 1, 0)), o1);
  EXPECT_EQ(bitsOf(objects.idAt(f, 1, 1)), o0);
  for (int r = 0; r < objects.ranks; ++r) EXPECT_EQ(objects.idAt(f, 3, r), 0.0f);
}

TEST(Cryptomatte, CropsMergeWithTheLayersAndTheMetadata) {
  // The default scene at 48 × 32, 4 spp: a full render, and two crops rendered with other thread
  // counts and tile sizes, merged. Each pixel is accumulated by one task, so every channel
  // (beauty and Cryptomatte) and the manifests must be the same bytes.
  const std::string dir = test::tempDir().string();
  const std::string common = "render --quiet --width 48 --height 32 --spp 4 --aov cryptomatte ";
  ASSERT_EQ(test::runGlint(common + "--threads 2 -o " + dir + "/cm_full.exr").exitCode, 0);
  ASSERT_EQ(
      test::runGlint(common + "--threads 1 --tile-size 5 --crop 0 48 0 13 -o " + dir + "/cm_a.exr")
          .exitCode,
      0);
  ASSERT_EQ(test::runGlint(common +
                           "--threads 2 --tile-size 8 --tile-order row --crop 0 48 13 32 "
                           "-o " +
                           dir + "/cm_b.exr")
                .exitCode,
            0);
  ASSERT_EQ(test::runGlint("merge " + dir + "/cm_m.exr " + dir + "/cm_a.exr " + dir + "/cm_b.exr")
                .exitCode,
            0);
  const CryptoFile full = readCryptoFile(dir + "/cm_full.exr");
  const CryptoFile merged = readCryptoFile(dir + "/cm_m.exr");
  ASSERT_EQ(full.channels.size(), merged.channels.size());
  for (const auto& [name, values] : full.channels) {
    ASSERT_TRUE(merged.channels.count(name)) << name;
    const std::vector<float>& m = merged.channels.at(name);
    ASSERT_EQ(values.size(), m.size());
    EXPECT_EQ(std::memcmp(values.data(), m.data(), values.size() * sizeof(float)), 0) << name;
  }
  int cryptoAttributes = 0;
  for (const auto& [k, v] : full.attributes)
    if (k.rfind("cryptomatte/", 0) == 0) {
      ++cryptoAttributes;
      EXPECT_EQ(merged.attributes.count(k) ? merged.attributes.at(k) : "(missing)", v) << k;
    }
  EXPECT_EQ(cryptoAttributes, 8);  // name, hash, conversion, manifest × 2 types
  // Something in the frame was covered: the scene's objects are found by their names.
  const CryptoType objects = findType(merged, "CryptoObject");
  double covered = 0;
  for (size_t i = 0; i < size_t(merged.width) * size_t(merged.height); ++i)
    for (int r = 0; r < objects.ranks; ++r) covered += objects.coverageAt(merged, i, r);
  EXPECT_GT(covered, 0);
}

// Every part of a multipart file: its name, its compression and its channels' values.
struct PartOf {
  std::string compression;
  std::map<std::string, std::vector<float>> channels;
};
std::map<std::string, PartOf> readParts(const std::string& path) {
  std::map<std::string, PartOf> parts;
  auto in = OIIO::ImageInput::open(path);
  EXPECT_TRUE(in) << path;
  for (int k = 0; in && in->seek_subimage(k, 0); ++k) {
    const OIIO::ImageSpec& s = in->spec();
    PartOf& part = parts[s.get_string_attribute("name")];
    part.compression = s.get_string_attribute("compression");
    for (int c = 0; c < s.nchannels; ++c) {
      std::vector<float> v(size_t(s.width) * size_t(s.height));
      EXPECT_TRUE(in->read_image(k, 0, c, c + 1, OIIO::TypeDesc::FLOAT, v.data()));
      part.channels[s.channelnames[size_t(c)]] = std::move(v);
    }
  }
  return parts;
}

TEST(Cryptomatte, ACompressionThatRoundsFloatsNeverReachesTheIds) {
  // With --compression dwaa every ID was altered (0x6a2fb100 for 6a2fb16e) and no matte matched
  // its manifest, exit 0. In one part the frame is now refused before any work; multipart, its
  // Cryptomatte parts are compressed with zip and hold the IDs a zip frame holds, bit for bit.
  const std::string dir = test::tempDir().string();
  const std::string common = "render --quiet --width 24 --height 16 --spp 2 --aov cryptomatte ";
  const auto onePart = test::runGlint(common + "--compression dwaa -o " + dir + "/cm_dwaa.exr");
  EXPECT_EQ(onePart.exitCode, 2) << onePart.output;
  EXPECT_NE(onePart.output.find("compression dwaa rounds floats and would destroy the "
                                "Cryptomatte IDs: write the frame multipart"),
            std::string::npos)
      << onePart.output;
  EXPECT_FALSE(std::filesystem::exists(dir + "/cm_dwaa.exr"));
  ASSERT_EQ(test::runGlint(common + "--multipart -o " + dir + "/cm_zip_parts.exr").exitCode, 0);
  const auto exact = readParts(dir + "/cm_zip_parts.exr");
  for (const std::string compression : {"dwaa", "pxr24"}) {
    const std::string lossy = dir + "/cm_" + compression + "_parts.exr";
    ASSERT_EQ(test::runGlint(common + "--multipart --compression " + compression + " -o " + lossy)
                  .exitCode,
              0);
    const auto parts = readParts(lossy);
    ASSERT_EQ(parts.size(), exact.size());
    EXPECT_EQ(parts.at("rgba").compression, compression);
    int idParts = 0;
    for (const auto& [name, part] : parts) {
      if (name.rfind("Crypto", 0) != 0) continue;
      ++idParts;
      EXPECT_EQ(part.compression, "zip") << name;
      for (const auto& [channel, values] : part.channels) {
        const std::vector<float>& want = exact.at(name).channels.at(channel);
        ASSERT_EQ(values.size(), want.size());
        EXPECT_EQ(std::memcmp(values.data(), want.data(), values.size() * sizeof(float)), 0)
            << name << " " << channel;
      }
    }
    EXPECT_EQ(idParts, 6) << compression;  // 3 ranks' layers of objects and of materials
  }
}

}  // namespace
}  // namespace glint
