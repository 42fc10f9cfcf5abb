// The environment light through both integrators (trace_both.h): what a diffuse surface in the
// open reads (k_d·π·L under a uniform sky), what rays that miss see, and what a mirror sphere
// reflects of a lat-long image, in the orientation docs/scene-format.md states; and the scene
// mistakes it can be given.
#include <gtest/gtest.h>

#include <OpenImageIO/imageio.h>

#include <cmath>
#include <limits>

#include "trace_both.h"

namespace glint {
namespace {

using test::load;
using test::rayTo;

// A float RGB EXR of width × height in the temporary folder, texel (x, y) from `texel`.
template <class F>
std::string writeExr(const std::string& name, int width, int height, F texel) {
  const std::string path = (test::tempDir() / name).string();
  std::vector<float> data;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const Rgb c = texel(x, y);
      data.insert(data.end(), {c.r, c.g, c.b});
    }
  OIIO::ImageSpec spec(width, height, 3, OIIO::TypeDesc::FLOAT);
  auto out = OIIO::ImageOutput::create(path);
  EXPECT_TRUE(out && out->open(path, spec) &&
              out->write_image(OIIO::TypeDesc::FLOAT, data.data()) && out->close());
  return path;
}

// 8 × 2: four columns per half of φ, the top row above the horizon and the bottom one below;
// texel (x, y) is (x + 1, y + 1, 0), so every region of the sphere has its own colour.
std::string columnsImage() {
  static const std::string path = writeExr("env_columns.exr", 8, 2, [](int x, int y) {
    return Rgb{float(x + 1), float(y + 1), 0};
  });
  return path;
}

std::string environment(const std::string& keys) {
  return R"("lights": [{"type": "environment", )" + keys + "}], ";
}

TEST(Environment, UniformSkyLightsALoneDiffuseSphereWithKdPiL) {
  // Every shadow ray leaves a convex sphere unblocked, and a uniform sky is drawn by a cosine
  // warp about the normal, so every sample's k_d·cos θ·L/pdf is k_d·π·L: the estimator has no
  // variance, and the mean of 16 samples differs from k_d·π·L by float rounding (1e-5 relative).
  const auto t =
      load(environment(R"("radiance": [0.2, 0.4, 0.8], "samples": 16)") +
           R"("materials": {"m": {"type": "phong", "kd": [0.5, 0.5, 0.5], "ks": [0,0,0]}},
    "objects": [{"type": "sphere", "center": [0,0,-5], "radius": 1, "material": "m"}])");
  for (const Vec3f aim : {Vec3f{0, 0, -4}, Vec3f{0.5f, 0.3f, -4.2f}, Vec3f{-0.7f, -0.6f, -4.6f}}) {
    const Rgb L = t.trace(rayTo({0, 0, 0}, aim));
    EXPECT_NEAR(L.r, 0.5 * kPi * 0.2, 0.5 * kPi * 0.2 * 1e-5);
    EXPECT_NEAR(L.g, 0.5 * kPi * 0.4, 0.5 * kPi * 0.4 * 1e-5);
    EXPECT_NEAR(L.b, 0.5 * kPi * 0.8, 0.5 * kPi * 0.8 * 1e-5);
  }
}

TEST(Environment, ConstantImageLightsTheSphereWithKdPiLWithinItsNoise) {
  // An image of constant 0.5 is drawn in proportion to sin θ, uniformly over the sphere: one
  // sample's k_d·cos θ·L/pdf is 4π·k_d·L·max(0, cos θ), of mean π·k_d·L and standard deviation
  // √(5/3)·π·k_d·L = 1.29 of it. 64 camera samples (separate sample sets) of 256 light samples
  // each: at most 1.29/√16384 = 1.0 % (stratification only lowers it); 4 % is four deviations.
  const std::string sky = writeExr("env_grey.exr", 16, 8, [](int, int) {
    return Rgb{0.5f, 0.5f, 0.5f};
  });
  const auto t =
      load(environment(R"("image": ")" + sky + R"(", "samples": 256)") +
           R"("materials": {"m": {"type": "phong", "kd": [0.6, 0.6, 0.6], "ks": [0,0,0]}},
    "objects": [{"type": "sphere", "center": [0,0,-5], "radius": 1, "material": "m"}])");
  double sum = 0;
  for (int px = 0; px < 64; ++px)
    sum += t.trace(rayTo({0, 0, 0}, {0.2f, 0.4f, -4}), kDefaultMinThroughput, px).g;
  const double expected = 0.6 * kPi * 0.5;
  EXPECT_NEAR(sum / 64, expected, 0.04 * expected);
}

TEST(Environment, CameraRaysThatMissSeeIt) {
  const auto uniform = load(environment(R"("radiance": [0.2, 0.4, 0.8])") + R"("objects": [])");
  EXPECT_EQ(uniform.trace(rayTo({0, 0, 0}, {0.3f, -0.2f, 1})), (Rgb{0.2f, 0.4f, 0.8f}));
  const auto image = load(environment(R"("image": ")" + columnsImage() + R"(", "intensity": 2)") +
                          R"("objects": [])");
  // Just right of and above the image's centre (−Z): column 4, top: (5, 1, 0) · 2.
  EXPECT_EQ(image.trace(rayTo({0, 0, 0}, {0.1f, 0.1f, -1})), (Rgb{10, 2, 0}));
}

// A mirror sphere (k_m = 1) at (0, 0, −5), radius 1, seen from the origin looking along −Z, in
// the columns image turned by `rotation`. A camera ray that meets it where its normal is n
// reflects about n; towards the viewer the sphere shows the environment behind the camera
// (+Z), its right half what lies to +X.
test::Traced mirrorSphere(int rotation) {
  return load(environment(R"("image": ")" + columnsImage() + R"(", "rotation": )" +
                          std::to_string(rotation)) +
              R"("materials": {"m": {"type": "mirror", "km": [1, 1, 1]}},
    "objects": [{"type": "sphere", "center": [0,0,-5], "radius": 1, "material": "m"}])");
}

Rgb atNormal(const test::Traced& t, Vec3f n) {
  return t.trace(rayTo({0, 0, 0}, Vec3f{0, 0, -5} + normalize(n)));
}

TEST(Environment, MirrorSphereReflectsTheImageInTheStatedOrientation) {
  // The reflected directions, r = d − 2(d·n)n, worked out for each point (φ = atan2(r.x, −r.z)
  // is 0 at the image's centre, u = 0.5 + φ/360°, column ⌊8u⌋; above the horizon: row 0):
  const auto t = mirrorSphere(0);
  // n ∝ (0.3, 0.3, 1): r = (0.553, 0.553, 0.623), φ = 138°, u = 0.88: column 7, top.
  EXPECT_EQ(atNormal(t, {0.3f, 0.3f, 1}), (Rgb{8, 1, 0}));
  // n ∝ (−0.3, 0.3, 1): r = (−0.553, 0.553, 0.623), φ = −138°, u = 0.12: column 0, top.
  EXPECT_EQ(atNormal(t, {-0.3f, 0.3f, 1}), (Rgb{1, 1, 0}));
  // n ∝ (0.3, −0.3, 1): below the horizon: column 7, bottom.
  EXPECT_EQ(atNormal(t, {0.3f, -0.3f, 1}), (Rgb{8, 2, 0}));
  // n ∝ (−0.6, −0.2, 1): r = (−0.902, −0.301, 0.310), φ = −109°, u = 0.20: column 1, bottom.
  EXPECT_EQ(atNormal(t, {-0.6f, -0.2f, 1}), (Rgb{2, 2, 0}));
  // n ∝ (0.9, 0.2, 0.4), near the rim: r = (0.569, 0.126, −0.813) runs on past the sphere,
  // φ = 35°, u = 0.60: column 4, top.
  EXPECT_EQ(atNormal(t, {0.9f, 0.2f, 0.4f}), (Rgb{5, 1, 0}));
}

TEST(Environment, RotationByNinetyDegreesMovesTheImageAsStated) {
  // Turned 90° counter-clockwise seen from above, the image point at φ is seen at φ − 90°: a
  // direction at φ shows the image at φ + 90°.
  const auto t = mirrorSphere(90);
  // φ = 138° + 90° = 228° = −132°: u = 0.13, column 1, top (column 7 unturned).
  EXPECT_EQ(atNormal(t, {0.3f, 0.3f, 1}), (Rgb{2, 1, 0}));
  // A miss along (−1, 0.3, −1), φ = −45°: column 3 unturned, u = 0.625 (column 5) turned.
  EXPECT_EQ(mirrorSphere(0).trace(rayTo({0, 0, 0}, {-1, 0.3f, -1})), (Rgb{4, 1, 0}));
  EXPECT_EQ(t.trace(rayTo({0, 0, 0}, {-1, 0.3f, -1})), (Rgb{6, 1, 0}));
}

TEST(Environment, PastTheDepthLimitARaySeesItAsItWouldTheBackground) {
  // Trace returns the background past d_max; with an environment, what the ray would see
  // leaving along its direction. max_depth 0: the mirror's reflection is not traced.
  const auto t =
      load(R"("render": {"max_depth": 0}, )" + environment(R"("radiance": [0.25, 0.5, 1])") +
           R"("materials": {"m": {"type": "mirror", "km": [0.5, 0.5, 0.5]}},
    "objects": [{"type": "sphere", "center": [0,0,-5], "radius": 1, "material": "m"}])");
  EXPECT_EQ(t.trace(rayTo({0, 0, 0}, {0, 0, -1})), (Rgb{0.125f, 0.25f, 0.5f}));
}

// Lines:        1
const char* kHead = "{\"camera\": {\"eye\": [0,0,5], \"look_at\": [0,0,0]}, \"objects\": [],\n";

TEST(Environment, SceneMistakesNameTheirPlace) {
  const auto error = [](const std::string& lights, const std::string& render = "") {
    return test::sceneErrorOf(std::string(kHead) + render + "\"lights\": [\n" + lights + "]}");
  };
  EXPECT_EQ(error(R"({"type": "environment", "image": "no_such_sky.exr"})"),
            "scene.json:3: lights[0].image: texture not found: " + std::string(GLINT_SCENES_DIR) +
                "/no_such_sky.exr");
  EXPECT_EQ(error("{\"type\": \"environment\", \"radiance\": [1, 1, 1]},\n"
                  "{\"type\": \"environment\", \"radiance\": [1, 1, 1]}"),
            "scene.json:4: lights[1]: a second environment light: a scene has at most one "
            "(lights[0])");
  EXPECT_EQ(error(R"({"type": "environment", "radiance": [1, -1, 1]})"),
            "scene.json:3: lights[0].radiance[1]: must be >= 0, got -1");
  EXPECT_EQ(error(R"({"type": "environment"})"),
            "scene.json:3: lights[0]: needs one of \"radiance\" (a uniform sky) and \"image\" (a "
            "lat-long image)");
  EXPECT_EQ(error(R"({"type": "environment", "radiance": [1, 1, 1], "rotation": 30})"),
            "scene.json:3: lights[0].rotation: applies to an environment \"image\" only");
  EXPECT_EQ(error(R"({"type": "environment", "radiance": [1, 1, 1]})",
                  "\"render\": {\"background\": [1, 0, 0]},\n"),
            "scene.json:2: render.background: rays that miss see the environment (lights[0]); "
            "remove \"background\", or the environment");
  const std::string nan = writeExr("env_nan.exr", 4, 2, [](int x, int y) {
    return x == 3 && y == 1 ? Rgb{1, std::numeric_limits<float>::quiet_NaN(), 1} : Rgb{1, 1, 1};
  });
  // A NaN is refused where any texture is read (io/texture_file.cpp), a negative texel here.
  EXPECT_EQ(error(R"({"type": "environment", "image": ")" + nan + "\"}"),
            "scene.json:3: lights[0].image: cannot read texture " + nan +
                ": texel (3, 1) holds NaN in channel 1; a texture's values must be finite");
  const std::string negative = writeExr("env_negative.exr", 4, 2, [](int x, int) {
    return Rgb{x == 2 ? -0.5f : 1, 1, 1};
  });
  EXPECT_EQ(error(R"({"type": "environment", "image": ")" + negative + "\"}"),
            "scene.json:3: lights[0].image: texel (2, 0) is (-0.5, 1, 1): an environment's "
            "radiance must be finite and >= 0");
}

}  // namespace
}  // namespace glint
