// Seed 001 §8's camera: the eye and two opposite corners of the screen window, turned into the
// look_at + window form when the scene loads (camera/screen.h).
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "camera/screen.h"
#include "render/render_job.h"
#include "test_util.h"

namespace glint {
namespace {

// The eye 4 above the window's centre (2, 1, 0), looking down −z; up (4, 3, 0), so the window's
// right is u = (0.6, −0.8, 0) and its up v = (0.8, 0.6, 0). The window is 5 wide along u and 2.5
// high along v: corner_min = c − 2.5u − 1.25v, corner_max = c + 2.5u + 1.25v. Every number is
// exact in binary.
const Vec3f kEye{2, 1, 4}, kCentre{2, 1, 0}, kU{0.6f, -0.8f, 0}, kV{0.8f, 0.6f, 0};
const char* kCamera = R"("eye": [2, 1, 4], "up": [4, 3, 0])";
const char* kScreen = R"("screen": {"corner_min": [-0.5, 2.25, 0], "corner_max": [4.5, -0.25, 0]})";

std::string sceneWith(const std::string& camera) {
  return R"({"render": {"width": 40, "height": 20, "spp": 2, "seed": 5},
    "camera": {)" +
         camera + R"(},
    "materials": {"red": {"type": "phong", "kd": [0.8, 0.2, 0.1], "ks": [0.3, 0.3, 0.3]},
                  "floor": {"type": "phong", "kd": {"checker": {"scale": 0.5,
                            "a": [0.9, 0.9, 0.9], "b": [0.1, 0.1, 0.1]}}}},
    "lights": [{"type": "point", "position": [3, 2, 6], "intensity": [1, 1, 1]}],
    "objects": [{"type": "plane", "point": [0, 0, -1], "normal": [0, 0, 1], "material": "floor"},
                {"type": "sphere", "center": [2.5, 0.5, -0.3], "radius": 0.6, "material": "red"}]})";
}

TEST(ScreenCamera, RaysPassThroughTheScreensPoints) {
  const Scene scene = test::sceneFromText(sceneWith(std::string(kCamera) + ", " + kScreen));
  const Camera camera(scene.cameraDesc, 40, 20);
  // Film (x, y), y down from the top, lands on c + (−2.5 + 5x/40)·u + (1.25 − 2.5y/20)·v; the
  // ray from the eye (render space: the eye at the origin) points at it.
  const Vec2f films[] = {{0, 20}, {40, 0}, {0, 0}, {40, 20}, {20, 10}, {7.25f, 13.5f}};
  for (const auto [x, y] : films) {
    const Vec3f onScreen = kCentre + (-2.5f + 5 * x / 40) * kU + (1.25f - 2.5f * y / 20) * kV;
    const Vec3f expected = normalize(onScreen - kEye);
    const Ray ray = camera.generateRay(x, y);
    EXPECT_EQ(ray.o, (Vec3f{0, 0, 0}));
    EXPECT_NEAR(ray.d.x, expected.x, 1e-6) << x << ", " << y;
    EXPECT_NEAR(ray.d.y, expected.y, 1e-6) << x << ", " << y;
    EXPECT_NEAR(ray.d.z, expected.z, 1e-6) << x << ", " << y;
  }
  // corner_min, as given, is the bottom-left corner of the film: the dot product of two unit
  // float vectors is 1 to within a few ulps (2.4e-7 is two).
  const Vec3f toMin = normalize(Vec3f{-0.5f, 2.25f, 0} - kEye);
  EXPECT_NEAR(dot(camera.generateRay(0, 20).d, toMin), 1, 4e-7);
  // The focus distance is the window's: the eye's distance to its centre.
  EXPECT_EQ(scene.cameraDesc.focusDistance, 4.0f);
}

TEST(ScreenCamera, RendersTheSameBytesAsTheSameViewByLookAtAndWindow) {
  // At distance 1 the window spans ±2.5/4 along u and ±1.25/4 along v.
  const auto render = [](const std::string& camera) {
    const Scene scene = test::sceneFromText(sceneWith(camera));
    const auto accel = makeAccelerator(AccelKind::Embree, scene);
    RenderOptions opt;
    opt.progress = false;
    return renderScene(scene, *accel, opt).film.toFloatRgba();
  };
  const std::vector<float> screen = render(std::string(kCamera) + ", " + kScreen);
  EXPECT_EQ(screen,
            render(std::string(kCamera) +
                   R"(, "look_at": [2, 1, 0], "window": [-0.625, 0.625, -0.3125, 0.3125])"));
  // And not a view that merely looks alike: the window shifted by one pixel differs.
  EXPECT_NE(screen,
            render(std::string(kCamera) +
                   R"(, "look_at": [2, 1, 0], "window": [-0.59375, 0.65625, -0.3125, 0.3125])"));
}

TEST(ScreenCamera, ConversionRefusesWhatIsNoScreen) {
  const Vec3d eye{0, 0, 5};
  const Vec3f up{0, 1, 0};
  const auto refusal = [&](Vec3d eyeAt, Vec3d lo, Vec3d hi) -> std::string {
    try {
      viewThroughScreen(eyeAt, lo, hi, up);
    } catch (const std::invalid_argument& e) {
      return e.what();
    }
    return "";
  };
  EXPECT_EQ(refusal(eye, {-1, -1, 0}, {1, 1, 0}), "");
  // Distances √27 and √(4 + 4 + 25) differ by far more than 1 part in 10⁴.
  EXPECT_NE(refusal(eye, {-1, -1, 0}, {1, 1, 1}).find("not equidistant"), std::string::npos);
  // 5·10⁻⁵ relative apart passes; 2·10⁻⁴ does not.
  const double d = 5 * std::sqrt(1 + 1.0 / 25 + 1.0 / 25);
  const auto shifted = [&](double relative) {
    // corner_max moved along the line of sight so its distance grows by `relative`.
    const double z = 5 - std::sqrt(d * d * (1 + relative) * (1 + relative) - 2);
    return refusal(eye, {-1, -1, 0}, {1, 1, z});
  };
  EXPECT_EQ(shifted(5e-5), "");
  EXPECT_NE(shifted(2e-4).find("not equidistant"), std::string::npos);
  EXPECT_NE(refusal({0, 0, 0}, {-1, -1, 0}, {1, 1, 0}).find("lies in the window's plane"),
            std::string::npos);
  EXPECT_NE(refusal(eye, {1, 1, 0}, {-1, -1, 0}).find("lower-left"), std::string::npos);
  EXPECT_NE(refusal(eye, {-1, 1, 0}, {1, -1, 0}).find("lower-left"), std::string::npos);
  EXPECT_NE(refusal(eye, {1, 1, 0}, {1, 1, 0}).find("same point"), std::string::npos);
  // An eye off the window's centre but in the corners' plane, both corners 2 away: the
  // window stands perpendicular to the line of sight (1, −1, 0), so with up = +y its right is
  // ∓z, along which the corners do not differ: a window of no width.
  EXPECT_NE(refusal({1, -1, 0}, {-1, -1, 0}, {1, 1, 0}).find("the window has no width"),
            std::string::npos);
}

}  // namespace
}  // namespace glint
