#include "camera/camera.h"

#include <gtest/gtest.h>

namespace glint {
namespace {

// Seed 000 eq. 4.1: u = l + (r − l)(i + 0.5)/n_x, v = b + (t − b)(j + 0.5)/n_y; here rows run
// from the top, so v uses (n_y − j − 0.5).

TEST(Camera, PerspectiveRayMatchesSeedFormula) {
  CameraDesc d;
  d.eye = {0, 0, 0};
  d.lookAt = {0, 0, -1};
  d.vfovDegrees = 90;  // tan(45°) = 1: the image plane spans [−1, 1] at distance 1
  const Camera cam(d, 2, 2);
  // Pixel (0, 0) is top-left; its centre is at u = −0.5, v = +0.5, so d ∝ (−0.5, 0.5, −1).
  const Ray r = cam.generateRay(0.5f, 0.5f);
  const float inv = 1.0f / std::sqrt(1.5f);
  EXPECT_NEAR(r.d.x, -0.5f * inv, 1e-6);
  EXPECT_NEAR(r.d.y, 0.5f * inv, 1e-6);
  EXPECT_NEAR(r.d.z, -1.0f * inv, 1e-6);
  EXPECT_EQ(r.o, (Vec3f{0, 0, 0}));
}

TEST(Camera, PerspectiveAspectWidensHorizontally) {
  CameraDesc d;
  d.vfovDegrees = 90;
  const Camera cam(d, 4, 2);                  // aspect 2: u spans [−2, 2]
  const Ray r = cam.generateRay(0.0f, 1.0f);  // left edge, vertical middle
  EXPECT_NEAR(r.d.x / -r.d.z, -2.0f, 1e-6);
  EXPECT_NEAR(r.d.y, 0.0f, 1e-6);
}

TEST(Camera, OrthographicRaysAreParallelFromThePlane) {
  CameraDesc d;
  d.projection = Projection::Orthographic;
  d.eye = {1, 2, 3};
  d.lookAt = {1, 2, 0};
  d.orthoHeight = 2;  // v in [−1, 1]; width 4 px × 2 px → u in [−2, 2]
  const Camera cam(d, 4, 2);
  const Ray r = cam.generateRay(0.5f, 0.5f);
  // u = −2 + 4·0.5/4 = −1.5, v = 1 − 2·0.5/2 = 0.5 → o = eye + (−1.5, 0.5, 0)
  EXPECT_NEAR(r.o.x, -0.5f, 1e-6);
  EXPECT_NEAR(r.o.y, 2.5f, 1e-6);
  EXPECT_NEAR(r.o.z, 3.0f, 1e-6);
  EXPECT_EQ(r.d, (Vec3f{0, 0, -1}));
}

TEST(Camera, FrameFromEyeLookAtUp) {
  // Looking down −x with up = y: w = +x (backwards), u = up × w = −z, v = w × u = y.
  CameraDesc d;
  d.eye = {5, 0, 0};
  d.lookAt = {0, 0, 0};
  const Camera cam(d, 8, 8);
  EXPECT_NEAR(cam.w().x, 1, 1e-6);
  EXPECT_NEAR(cam.u().z, -1, 1e-6);
  EXPECT_NEAR(cam.v().y, 1, 1e-6);
}

TEST(Camera, DegenerateFramesAreRejected) {
  CameraDesc d;
  d.eye = d.lookAt = {1, 1, 1};
  EXPECT_THROW(Camera(d, 4, 4), std::invalid_argument);
  d.eye = {0, 5, 0};
  d.lookAt = {0, 0, 0};  // looking straight down the up vector
  EXPECT_THROW(Camera(d, 4, 4), std::invalid_argument);
}

}  // namespace
}  // namespace glint
