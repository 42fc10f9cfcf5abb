// AOVs through the EXR round trip, with exact expected values.
#include <gtest/gtest.h>

#include <OpenImageIO/imageio.h>

#include <filesystem>
#include <limits>
#include <map>

#include "core/error.h"
#include "io/scene_loader.h"
#include "render/aov_accumulator.h"
#include "render/render_job.h"
#include "test_util.h"

namespace glint {
namespace {

// Reads every channel of every part by name, as float values (ids are exact below 2^24).
std::map<std::string, std::vector<float>> readChannels(
    const std::string& path, std::vector<std::string>* partNames = nullptr,
    std::map<std::string, OIIO::TypeDesc>* types = nullptr) {
  std::map<std::string, std::vector<float>> out;
  auto in = OIIO::ImageInput::open(path);
  EXPECT_TRUE(in) << path;
  for (int sub = 0; in && in->seek_subimage(sub, 0); ++sub) {
    const OIIO::ImageSpec& s = in->spec();
    if (partNames) partNames->push_back(s.get_string_attribute("name"));
    for (int c = 0; c < s.nchannels; ++c) {
      std::vector<float> v(size_t(s.width) * size_t(s.height));
      if (s.channelformat(c) == OIIO::TypeDesc::UINT) {
        // Read ids as integers: OIIO would normalise a uint read as float by 2^-32.
        std::vector<uint32_t> u(v.size());
        EXPECT_TRUE(in->read_image(sub, 0, c, c + 1, OIIO::TypeDesc::UINT, u.data()));
        std::copy(u.begin(), u.end(), v.begin());
      } else {
        EXPECT_TRUE(in->read_image(sub, 0, c, c + 1, OIIO::TypeDesc::FLOAT, v.data()));
      }
      out[s.channelnames[size_t(c)]] = v;
      if (types) (*types)[s.channelnames[size_t(c)]] = s.channelformat(c);
    }
  }
  return out;
}

// Looking straight down at a Lambert plane from y = 5: pixel centres at x = u ∈ {−1.5, −0.5,
// 0.5, 1.5}, z = −v with v ∈ {0.5, −0.5}. Light 0 is directional along (0,−1,−1)/√2 (cosθ = 1/√2),
// light 1 a point light at (0, 2, 0) of intensity 2 (cosθ = 2/√(x² + z² + 4)), no falloff.
const char* kScene = R"({
  "render": {"width": 4, "height": 2, "spp": 1, "sampler": "regular"},
  "camera": {"type": "orthographic", "eye": [0,5,0], "look_at": [0,0,0], "up": [0,0,-1], "height": 2},
  "materials": {"m": {"type": "phong", "kd": [0.5,0.4,0.2], "ka": [0,0,0]}},
  "lights": [{"type": "directional", "direction": [0,-1,-1]},
             {"type": "point", "position": [0,2,0], "intensity": [2,2,2]}],
  "objects": [{"type": "plane", "point": [0,0,0], "normal": [0,1,0], "material": "m"}]})";

TEST(Aov, EveryAovRoundTripsWithExactValues) {
  const std::string scene = test::writeTemp("aov.json", kScene);
  const std::string out = (test::tempDir() / "aov.exr").string();
  ASSERT_EQ(
      test::runGlint("render " + scene + " --quiet -o " + out +
                     " --aov depth,normal,albedo,position,objectid,direct,indirect,lights,variance")
          .exitCode,
      0);
  std::map<std::string, OIIO::TypeDesc> types;
  const auto ch = readChannels(out, nullptr, &types);
  // The object id as Blender's IndexOB pass: a float channel X of layer IndexOB (Blender drops
  // a channel named `id`; docs/output.md).
  EXPECT_EQ(types.count("id"), 0u);
  EXPECT_EQ(types["IndexOB.X"], OIIO::TypeDesc::FLOAT);
  EXPECT_EQ(types["Z"], OIIO::TypeDesc::FLOAT);
  const float kd[3] = {0.5f, 0.4f, 0.2f};
  const char* rgb[3] = {"R", "G", "B"};
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 4; ++x) {
      const size_t i = size_t(y) * 4 + size_t(x);
      const float px = -1.5f + float(x), pz = -(0.5f - float(y));
      EXPECT_FLOAT_EQ(ch.at("Z")[i], 5);
      EXPECT_FLOAT_EQ(ch.at("N.Y")[i], 1);
      EXPECT_FLOAT_EQ(ch.at("N.X")[i], 0);
      EXPECT_FLOAT_EQ(ch.at("P.X")[i], px);
      EXPECT_FLOAT_EQ(ch.at("P.Y")[i], 0);
      EXPECT_FLOAT_EQ(ch.at("P.Z")[i], pz);
      EXPECT_EQ(ch.at("IndexOB.X")[i], 1.0f);  // objects[0] + 1
      const float cos1 = 2 / std::sqrt(px * px + pz * pz + 4);
      for (int c = 0; c < 3; ++c) {
        const std::string C = rgb[c];
        const float l0 = kd[c] * std::sqrt(0.5f), l1 = kd[c] * 2 * cos1;
        EXPECT_FLOAT_EQ(ch.at("Albedo." + C)[i], kd[c]);
        EXPECT_NEAR(ch.at("light0." + C)[i], l0, 1e-6);
        EXPECT_NEAR(ch.at("light1." + C)[i], l1, 1e-6);
        EXPECT_NEAR(ch.at("direct." + C)[i], l0 + l1, 1e-6);
        EXPECT_NEAR(ch.at(C)[i], l0 + l1, 1e-6);  // the beauty is all direct here
        EXPECT_EQ(ch.at("indirect." + C)[i], 0.0f);
        EXPECT_EQ(ch.at("Variance." + C)[i], 0.0f);  // one sample: no variance estimate
      }
    }
}

TEST(Aov, VarianceOfAHalfCoveredPixel) {
  // One pixel, 2 × 2 regular samples at (±0.25, ±0.25); a white (ambient-only, L = 1) quad
  // covers x > 0, the background is 0. The render's two halves take alternate cells of the
  // grid: half 0 cells 0 and 2 (x < 0: 0, 0), half 1 cells 1 and 3 (x > 0: 1, 1). Mean 0.5;
  // the variance of the mean from the halves' means 0 and 1: (2·2/4²)·(0 − 1)² = 1/4. (A
  // regular grid has no randomness: this measures how its two interleaved grids disagree, and
  // the frame reports no estimated error.) Alpha 0.5; the id of the hits is 1.
  const std::string scene = test::writeTemp("var.json", R"({
    "render": {"width": 1, "height": 1, "spp": 4, "sampler": "regular", "ambient": [1,1,1],
               "transparent_background": true},
    "camera": {"type": "orthographic", "eye": [0,0,5], "look_at": [0,0,0], "height": 1},
    "materials": {"w": {"type": "phong", "ka": [1,1,1], "kd": [0,0,0]}},
    "objects": [{"type": "quad", "corner": [0,-1,0], "edge1": [1,0,0], "edge2": [0,2,0], "material": "w"}]})");
  const std::string out = (test::tempDir() / "var.exr").string();
  ASSERT_EQ(test::runGlint("render " + scene + " --quiet -o " + out + " --aov variance,objectid")
                .exitCode,
            0);
  const auto ch = readChannels(out);
  EXPECT_FLOAT_EQ(ch.at("R")[0], 0.5f);
  EXPECT_FLOAT_EQ(ch.at("A")[0], 0.5f);
  EXPECT_NEAR(ch.at("Variance.R")[0], 0.25, 1e-7);
  EXPECT_EQ(ch.at("IndexOB.X")[0], 1.0f);
}

TEST(Aov, DepthIsFarWhereNothingWasHitAndTheNearestHitWherePartlyCovered) {
  // Three pixels of 2 x 2 regular samples (at x = -1.25, -0.75; -0.25, 0.25; 0.75, 1.25),
  // orthographic from z = 5: a quad at z = 0 over x in [-1, -0.5] half covers the left pixel,
  // the middle one sees nothing, and the right one sees a quad at z = -3e10. Depth along the
  // view axis: a partly covered pixel keeps its nearest hit (5), not a blend with the
  // background; the empty pixel holds the far value 1e10 (kBackgroundDepth), never 0, which a
  // Z-combine would take as nearest; a hit beyond it (3e10 + 5) is written as 1e10 too, so the
  // background is never in front of it. Object ids: 1, 0 (background), 2.
  const std::string scene = test::writeTemp("far.json", R"({
    "render": {"width": 3, "height": 1, "spp": 4, "sampler": "regular",
               "transparent_background": true},
    "camera": {"type": "orthographic", "eye": [0,0,5], "look_at": [0,0,0], "height": 1},
    "materials": {"w": {"type": "phong", "ka": [1,1,1], "kd": [0,0,0]}},
    "objects": [{"type": "quad", "corner": [-1,-1,0], "edge1": [0.5,0,0], "edge2": [0,2,0],
                 "material": "w"},
                {"type": "quad", "corner": [0.5,-1,-3e10], "edge1": [1,0,0], "edge2": [0,2,0],
                 "material": "w"}]})");
  for (const char* flags : {"", " --multipart"}) {
    const std::string out = (test::tempDir() / "far.exr").string();
    const auto run =
        test::runGlint("render " + scene + " --quiet -o " + out + " --aov depth,objectid" + flags);
    ASSERT_EQ(run.exitCode, 0) << run.output;
    const auto ch = readChannels(out);
    EXPECT_FLOAT_EQ(ch.at("A")[0], 0.5f) << flags;  // the left pixel is half covered
    EXPECT_FLOAT_EQ(ch.at("Z")[0], 5.0f) << flags;
    EXPECT_EQ(ch.at("IndexOB.X")[0], 1.0f) << flags;
    EXPECT_EQ(ch.at("A")[1], 0.0f) << flags;
    EXPECT_EQ(ch.at("Z")[1], 1e10f) << flags;  // exact in float: 1e10 = 2^10 * 9765625
    EXPECT_EQ(double(ch.at("Z")[1]), kBackgroundDepth) << flags;
    EXPECT_EQ(ch.at("IndexOB.X")[1], 0.0f) << flags;
    EXPECT_EQ(ch.at("A")[2], 1.0f) << flags;
    EXPECT_EQ(ch.at("Z")[2], 1e10f) << flags;
    EXPECT_EQ(ch.at("IndexOB.X")[2], 2.0f) << flags;
  }
}

TEST(Aov, ObjectIdsBeyondWhatAFloatHoldsExactlyAreRefused) {
  // A world whose last entry is objects[2^24] would write id 2^24 + 1, which a float channel
  // rounds to 2^24: a usage error naming the limit, not a wrong id.
  Scene scene;
  scene.groups.push_back({"world", {Geometry{GeomKind::Sphere, 0, 0, kMaxObjectIdAov}}});
  Film film(2, 2, PixelWindow{0, 2, 0, 2});
  try {
    AovLayout::create(AovSet::parse("objectid"), scene, film);
    ADD_FAILURE() << "no error";
  } catch (const UsageError& e) {
    EXPECT_NE(std::string(e.what()).find("16777217 object ids"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("up to 16777216"), std::string::npos) << e.what();
  }
  // One id fewer is written.
  scene.groups[0].geometries[0].objectId = kMaxObjectIdAov - 1;
  EXPECT_NE(AovLayout::create(AovSet::parse("objectid"), scene, film).objectId, SIZE_MAX);
}

TEST(Aov, ValuesBeyondTheirChannelTypeAreClampedNeverInfinite) {
  // The half-covered pixel above with L = 1e20: mean 5e19 (beyond half's 65504), variance of
  // the mean (1e20)²/4 = 2.5e39 (beyond float's 3.4e38). Written as they are, they would
  // be +Inf; each is clamped to its type's largest finite value, and counted.
  const std::string scene = test::writeTemp("hot.json", R"({
    "render": {"width": 1, "height": 1, "spp": 4, "sampler": "regular", "ambient": [1e20,1e20,1e20],
               "transparent_background": true},
    "camera": {"type": "orthographic", "eye": [0,0,5], "look_at": [0,0,0], "height": 1},
    "materials": {"w": {"type": "phong", "ka": [1,1,1], "kd": [0,0,0]}},
    "objects": [{"type": "quad", "corner": [0,-1,0], "edge1": [1,0,0], "edge2": [0,2,0], "material": "w"}]})");
  const std::string out = (test::tempDir() / "hot.exr").string();
  const std::string stats = (test::tempDir() / "hot.json.stats").string();
  const auto run = test::runGlint("render " + scene + " --quiet --half --aov variance -o " + out +
                                  " --stats-json " + stats);
  ASSERT_EQ(run.exitCode, 0) << run.output;
  const auto ch = readChannels(out);
  EXPECT_EQ(ch.at("R")[0], 65504.0f);  // half's largest finite value
  EXPECT_EQ(ch.at("A")[0], 0.5f);
  EXPECT_EQ(ch.at("Variance.G")[0], std::numeric_limits<float>::max());
  // R, G, B (half) and the three variance channels (float).
  auto in = OIIO::ImageInput::open(out);
  ASSERT_TRUE(in);
  EXPECT_EQ(in->spec().get_int_attribute("glint:clamped_values", -1), 6);
  EXPECT_NE(run.output.find("6 values beyond half-float's"), std::string::npos) << run.output;
  EXPECT_NE(test::readFile(stats).find("\"clamped_values\": 6"), std::string::npos);
}

TEST(Aov, MultipartWritesOnePartPerAovWithItsOwnType) {
  const std::string scene = test::writeTemp("mp.json", kScene);
  const std::string out = (test::tempDir() / "mp.exr").string();
  ASSERT_EQ(test::runGlint("render " + scene + " --quiet --half -o " + out +
                           " --aov depth,objectid,lights --multipart")
                .exitCode,
            0);
  std::vector<std::string> parts;
  std::map<std::string, OIIO::TypeDesc> types;
  const auto ch = readChannels(out, &parts, &types);
  EXPECT_EQ(parts, (std::vector<std::string>{"rgba", "depth", "objectid", "light0", "light1"}));
  EXPECT_EQ(types["R"], OIIO::TypeDesc::HALF);
  EXPECT_EQ(types["Z"], OIIO::TypeDesc::FLOAT);
  EXPECT_EQ(types["IndexOB.X"], OIIO::TypeDesc::FLOAT);  // Blender's IndexOB, in part objectid
  EXPECT_EQ(ch.at("IndexOB.X")[0], 1.0f);
  EXPECT_FLOAT_EQ(ch.at("Z")[0], 5);
  // An unknown AOV is a usage error that lists the known ones.
  const auto bad = test::runGlint("render " + scene + " --quiet -o " + out + " --aov depth,motion");
  EXPECT_EQ(bad.exitCode, 2);
  EXPECT_NE(bad.output.find("unknown AOV \"motion\""), std::string::npos) << bad.output;
  // So is a list that names none: "" and "," rendered the beauty alone, exit 0.
  for (const char* none : {"''", ",", ",,"}) {
    const auto empty = test::runGlint("render " + scene + " --quiet -o " + out + " --aov " + none);
    EXPECT_EQ(empty.exitCode, 2) << none;
    EXPECT_NE(empty.output.find("--aov: must name at least one AOV"), std::string::npos)
        << empty.output;
  }
}

TEST(Aov, AskingForAovsChangesNoBeautyPixel) {
  // AOV records are filled by the same kernel that shades the beauty: every bundled scene's
  // beauty must be the same bytes with every AOV asked for and with none.
  int scenes = 0;
  for (const auto& e : std::filesystem::directory_iterator(GLINT_SCENES_DIR)) {
    if (e.path().extension() != ".json") continue;
    Scene scene = loadSceneFile(e.path().string());
    scene.render.width = 32;
    scene.render.height = 24;
    scene.render.spp = 2;
    const auto accel = makeAccelerator(AccelKind::Embree, scene);
    RenderOptions opt;
    opt.progress = false;
    const std::vector<float> plain = renderScene(scene, *accel, opt).film.toFloatRgba();
    opt.aovs = AovSet::parse(
        "depth,normal,albedo,position,objectid,direct,indirect,lights,variance,cryptomatte");
    const RenderResult withAovs = renderScene(scene, *accel, opt);
    EXPECT_EQ(plain, withAovs.film.toFloatRgba()) << e.path();
    EXPECT_GE(withAovs.film.planes().size(), 8u) << e.path();
    ++scenes;
  }
  EXPECT_GE(scenes, 14);
}

TEST(Aov, DirectAndIndirectAddUpToTheBeautyEvenWhereTheBackgroundIsSeen) {
  // indirect is the beauty less the direct light: where a camera sample missed (the background,
  // the sky of an environment light, an antialiased silhouette) both were 0, and comp's rebuilt
  // beauty lacked the sky. Each plane is a mean of the same samples in double, so they differ
  // from the beauty by their float rounding alone.
  for (const char* name : {"whitted", "sky", "transparent_shadows_on"}) {
    Scene scene = loadSceneFile(std::string(GLINT_SCENES_DIR) + "/" + name + ".json");
    scene.render.width = 32;
    scene.render.height = 24;
    scene.render.spp = 4;
    const auto accel = makeAccelerator(AccelKind::Embree, scene);
    RenderOptions opt;
    opt.progress = false;
    opt.aovs = AovSet::parse("direct,indirect");
    const Film film = renderScene(scene, *accel, opt).film;
    const FilmPlane *direct = nullptr, *indirect = nullptr;
    for (const FilmPlane& p : film.planes()) {
      if (p.name == "direct") direct = &p;
      if (p.name == "indirect") indirect = &p;
    }
    ASSERT_TRUE(direct && indirect) << name;
    int background = 0;
    for (int y = 0; y < 24; ++y)
      for (int x = 0; x < 32; ++x) {
        const size_t i = 3 * (size_t(y) * 32 + size_t(x));
        background += direct->values[i] == 0 && film.pixel(x, y)[0] > 0;
        for (int c = 0; c < 3; ++c) {
          const double d = direct->values[i + size_t(c)], n = indirect->values[i + size_t(c)];
          const double beauty = film.pixel(x, y)[c];
          EXPECT_NEAR(d + n, beauty, 1e-6 * (std::fabs(d) + std::fabs(n) + beauty) + 1e-9)
              << name << " pixel " << x << "," << y << " channel " << c;
        }
      }
    EXPECT_GT(background, 0) << name << ": the test needs pixels where the background is seen";
  }
}

}  // namespace
}  // namespace glint
