// EXR frames written with OpenEXR (film/exr_output.h) read back by OpenImageIO's own tools, as
// a compositor's pipeline would: float, half, multi-part, crops and Glint's metadata.
#include "film/exr_output.h"

#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <gtest/gtest.h>

#include <array>
#include <cfloat>
#include <cmath>
#include <cstdio>
#include <random>
#include <regex>

#include "film/film.h"
#include "test_util.h"

namespace glint {
namespace {

using test::runGlint;

std::string tmp(const std::string& name) { return (test::tempDir() / name).string(); }

std::string commandOutput(const std::string& cmd) {
  std::string out;
  FILE* pipe = ::popen((cmd + " 2>&1").c_str(), "r");
  if (!pipe) return out;
  std::array<char, 4096> buf;
  size_t n;
  while ((n = std::fread(buf.data(), 1, buf.size(), pipe)) > 0) out.append(buf.data(), n);
  EXPECT_EQ(::pclose(pipe), 0) << cmd << "\n" << out;
  return out;
}

const char* kScene = R"({
  "render": {"width": 24, "height": 16, "spp": 2, "seed": 3},
  "camera": {"eye": [0,0,5], "look_at": [0,0,0], "vfov": 40},
  "materials": {"m": {"type": "phong", "kd": [0.6,0.4,0.3]}},
  "lights": [{"type": "point", "position": [2,3,4], "intensity": [40,40,40],
              "falloff": "inverse_square"}],
  "objects": [{"type": "sphere", "center": [0,0,0], "radius": 1, "material": "m"}]})";

TEST(ExrOutput, IinfoReadsFloatHalfCropsAndMetadata) {
  const std::string scene = test::writeTemp("roundtrip.json", kScene);
  ASSERT_EQ(runGlint("render " + scene + " --quiet -o " + tmp("roundtrip-float.exr")).exitCode, 0);
  ASSERT_EQ(runGlint("render " + scene + " --quiet --half --crop 4 20 2 10 -o " +
                     tmp("roundtrip-half-crop.exr"))
                .exitCode,
            0);
  const std::string f = commandOutput("iinfo -v " + tmp("roundtrip-float.exr"));
  EXPECT_NE(f.find("24 x   16, 4 channel, float openexr"), std::string::npos) << f;
  EXPECT_NE(f.find("channel list: R, G, B, A"), std::string::npos) << f;
  EXPECT_NE(f.find("compression: \"zip\""), std::string::npos) << f;
  EXPECT_NE(f.find("glint:spp: 2"), std::string::npos) << f;
  EXPECT_NE(f.find("glint:colorspace: \"lin_rec709\""), std::string::npos) << f;
  // Rec.709 primaries and D65 white, OpenEXR's chromaticities attribute.
  EXPECT_NE(f.find("chromaticities: 0.64, 0.33, 0.3, 0.6, 0.15, 0.06, 0.3127, 0.329"),
            std::string::npos)
      << f;
  EXPECT_TRUE(std::regex_search(f, std::regex("worldToCamera: [-0-9., ]+"))) << f;
  const std::string h = commandOutput("iinfo -v " + tmp("roundtrip-half-crop.exr"));
  EXPECT_NE(h.find("16 x    8, 4 channel, half openexr"), std::string::npos) << h;
  // The crop's data window inside the full 24 × 16 display window.
  EXPECT_NE(h.find("pixel data origin: x=4, y=2"), std::string::npos) << h;
  EXPECT_NE(h.find("full/display size: 24 x 16"), std::string::npos) << h;
}

TEST(ExrOutput, PixelChunksAreTheSameBytesForAnyOpenExrThreadCount) {
  // A render's frame is compressed on OpenEXR's pool of the render's threads (setExrThreads);
  // its compressed line blocks must not depend on how many, or the file would depend on
  // --threads. 200 x 120 noisy pixels, zip: 8 chunks of 16 lines.
  Film film(200, 120, PixelWindow{0, 200, 0, 120});
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> unit(0, 1);
  for (int y = 0; y < 120; ++y)
    for (int x = 0; x < 200; ++x) film.setPixel(x, y, unit(rng), unit(rng), unit(rng), 1);
  const auto chunks = [&](int threads) {
    setExrThreads(threads);
    const std::string path = tmp("exr-threads-" + std::to_string(threads) + ".exr");
    writeExr(path, film, {});
    Imf::InputFile in(path.c_str());
    EXPECT_EQ(in.header().compression(), Imf::ZIP_COMPRESSION);
    std::vector<std::string> out;
    for (int y = 0; y < 120; y += 16) {  // zip: a chunk of 16 lines
      const char* data = nullptr;
      int size = 0;
      in.rawPixelData(y, data, size);
      out.emplace_back(data, size_t(size));
    }
    return out;
  };
  const std::vector<std::string> alone = chunks(0);
  ASSERT_EQ(alone.size(), 8u);
  EXPECT_EQ(chunks(4), alone);
  setExrThreads(0);  // as the process started
}

TEST(ExrOutput, AFloatCropIsWrittenAsTheFilmHoldsItAndOnlyValuesPastFloatAreClamped) {
  // A float beauty is read by OpenEXR straight from the film, a channel holding a value past
  // float's range through a clamped copy: the file must hold the film's floats exactly, in the
  // crop's place, with each value past the range (an infinity, a double just above float's
  // largest value, which rounding to nearest would make that value) clamped and counted, and
  // NaN written as 0.
  const PixelWindow window{3, 7, 2, 5};
  Film film(10, 8, window);
  const double justAbove = double(FLT_MAX) * (1 + 1e-9);  // within half a float unit above
  for (int y = window.y0; y < window.y1; ++y)
    for (int x = window.x0; x < window.x1; ++x)
      film.setPixel(x, y, 0.1 * x + 0.01 * y, 1.0 / 3 + y, -0.25 * x, 0.5);
  film.setPixel(4, 3, 1e39, std::nan(""), -justAbove, 0.5);
  const std::string path = tmp("direct-crop.exr");
  EXPECT_EQ(writeExr(path, film, {}), 3u);
  const Image img = readImage(path);
  ASSERT_EQ(img.channelNames, (std::vector<std::string>{"R", "G", "B", "A"}));
  ASSERT_EQ(img.width, 4);
  ASSERT_EQ(img.height, 3);
  EXPECT_EQ(img.x, 3);
  EXPECT_EQ(img.y, 2);
  for (int y = window.y0; y < window.y1; ++y)
    for (int x = window.x0; x < window.x1; ++x) {
      const float* in = &img.pixels[(size_t(y - 2) * 4 + size_t(x - 3)) * 4];
      const float* held = film.pixel(x, y);
      if (x == 4 && y == 3) {
        EXPECT_EQ(in[0], FLT_MAX);
        EXPECT_EQ(in[1], 0.0f);
        EXPECT_EQ(in[2], -FLT_MAX);
        EXPECT_EQ(in[3], 0.5f);
        continue;
      }
      for (int c = 0; c < 4; ++c) EXPECT_EQ(in[c], held[c]) << x << "," << y << " " << c;
    }
}

TEST(ExrOutput, OiiotoolStatsSeeEveryPartOfAMultiPartFrame) {
  const std::string scene = test::writeTemp("multipart.json", kScene);
  ASSERT_EQ(runGlint("render " + scene + " --quiet --multipart --aov depth,normal -o " +
                     tmp("roundtrip-multipart.exr"))
                .exitCode,
            0);
  const std::string stats = commandOutput("oiiotool --stats -a " + tmp("roundtrip-multipart.exr"));
  // Three parts (beauty, depth, normal), each with its statistics.
  size_t parts = 0;
  for (size_t at = stats.find("Stats Min"); at != std::string::npos;
       at = stats.find("Stats Min", at + 1))
    ++parts;
  EXPECT_EQ(parts, 3u) << stats;
  // Depth along the view axis of the unit sphere 5 units away: 4 at the centre, at most 5 at
  // the silhouette; misses are the far value 1e10 (docs/output.md). So the part's minimum lies
  // in [4, 5] and its maximum is 1e10.
  const std::string info = commandOutput("iinfo -v -a " + tmp("roundtrip-multipart.exr"));
  EXPECT_NE(info.find("subimage  1"), std::string::npos) << info;
  EXPECT_NE(info.find("name: \"depth\""), std::string::npos) << info;
  const auto depthStat = [&](const char* which) {
    std::smatch r;
    const std::regex pattern(std::string("subimage +1:[\\s\\S]*?Stats ") + which +
                             ": ([0-9.e+-]+)");
    EXPECT_TRUE(std::regex_search(stats, r, pattern)) << stats;
    return r.size() == 2 ? std::stod(r[1].str()) : -1.0;
  };
  const double minDepth = depthStat("Min"), maxDepth = depthStat("Max");
  EXPECT_GE(minDepth, 4.0);
  EXPECT_LE(minDepth, 5.0 + 1e-5);
  EXPECT_EQ(maxDepth, 1e10);
}

}  // namespace
}  // namespace glint
