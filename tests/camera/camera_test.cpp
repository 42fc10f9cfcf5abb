#include "camera/camera.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <vector>

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

// Seed 000 eq. 4.1 with an off-centre window: pixel (i, j) of an n_x × n_y image (rows from the
// top) is at u = l + (r − l)(i + ½)/n_x, v = t − (t − b)(j + ½)/n_y.
TEST(Camera, OffCentreWindowFollowsEquationFourOne) {
  CameraDesc d;
  d.window = ImageWindow{-0.6f, 0.4f, -0.3f, 0.3f};
  const Camera cam(d, 10, 6);
  // Pixel (0, 0): u = −0.6 + 1·0.5/10 = −0.55, v = 0.3 − 0.6·0.5/6 = 0.25; d ∝ (u, v, −1).
  const Ray r = cam.generateRay(0.5f, 0.5f);
  EXPECT_NEAR(r.d.x / -r.d.z, -0.55f, 1e-6);
  EXPECT_NEAR(r.d.y / -r.d.z, 0.25f, 1e-6);
  // Pixel (9, 5): u = −0.6 + 9.5/10 = 0.35, v = 0.3 − 0.6·5.5/6 = −0.25.
  const Ray s = cam.generateRay(9.5f, 5.5f);
  EXPECT_NEAR(s.d.x / -s.d.z, 0.35f, 1e-6);
  EXPECT_NEAR(s.d.y / -s.d.z, -0.25f, 1e-6);
  // Orthographic: the same numbers are the ray origins' offsets, in scene units.
  d.projection = Projection::Orthographic;
  const Ray o = Camera(d, 10, 6).generateRay(9.5f, 5.5f);
  EXPECT_NEAR(o.o.x, 0.35f, 1e-6);
  EXPECT_NEAR(o.o.y, -0.25f, 1e-6);
  EXPECT_EQ(o.d, (Vec3f{0, 0, -1}));
}

// The image plane's normal n = (0, 0.2, 1)/|·| apart from the view direction d = (0, 0, −1):
// w = n (it faces the eye), u = up × w = (1, 0, 0), v = w × u = (0, 1, −0.2)/√1.04.
TEST(Camera, ObliquePerspectiveAndParallelViewsFollowSectionFourThree) {
  CameraDesc d;
  d.vfovDegrees = 90;  // window [−1, 1]²
  d.imagePlaneNormal = Vec3f{0, 0.2f, 1};
  const Camera cam(d, 2, 2);
  const float k = 1 / std::sqrt(1.04f);
  EXPECT_NEAR(cam.v().y, k, 1e-6);
  EXPECT_NEAR(cam.v().z, -0.2f * k, 1e-6);
  // Perspective (§4.3.2, −d·w replaced by d·d): pixel (0, 0) at u = −0.5, v = 0.5 gives
  // direction −0.5·u + 0.5·v + d = (−0.5, 0.5k, −1 − 0.1k).
  const Ray r = cam.generateRay(0.5f, 0.5f);
  const Vec3f expected = normalize(Vec3f{-0.5f, 0.5f * k, -1 - 0.1f * k});
  EXPECT_NEAR(r.d.x, expected.x, 1e-6);
  EXPECT_NEAR(r.d.y, expected.y, 1e-6);
  EXPECT_NEAR(r.d.z, expected.z, 1e-6);
  // The normal given the other way round is the same plane: the same rays.
  d.imagePlaneNormal = Vec3f{0, -0.2f, -1};
  EXPECT_EQ(Camera(d, 2, 2).generateRay(0.5f, 0.5f).d, r.d);
  // Parallel (§4.3.1, d in place of −w): every ray along d, from e + u·u + v·v.
  d.projection = Projection::Orthographic;
  d.orthoHeight = 2;
  const Ray o = Camera(d, 2, 2).generateRay(0.5f, 0.5f);
  EXPECT_EQ(o.d, (Vec3f{0, 0, -1}));
  EXPECT_NEAR(o.o.x, -0.5f, 1e-6);
  EXPECT_NEAR(o.o.y, 0.5f * k, 1e-6);
  EXPECT_NEAR(o.o.z, -0.1f * k, 1e-6);
  // A plane that would contain the view direction makes no image.
  d.imagePlaneNormal = Vec3f{1, 0, 0};
  EXPECT_THROW(Camera(d, 2, 2), std::invalid_argument);
}

// The render makes its camera rays four at a time (generateRays); each must be generateRay's
// ray to the bit, for every kind of camera: both projections, oblique and off-centre views,
// pinholes and thin lenses of both shapes, full blocks and a short last one, and rays written
// where `slot` sends them.
TEST(Camera, RaysSideBySideEqualOneRayAtATime) {
  for (const Projection projection : {Projection::Perspective, Projection::Orthographic})
    for (const bool oblique : {false, true})
      for (const float aperture : {0.0f, 0.05f})
        for (const LensShape shape : {LensShape::Disk, LensShape::Square}) {
          CameraDesc d;
          d.projection = projection;
          d.eye = {1, 2, 3};
          d.lookAt = {0, 1.5f, -1};
          if (oblique)
            d.imagePlaneNormal = Vec3f{0.3f, 0.4f, 1};
          else
            d.window = ImageWindow{-0.2f, 0.7f, -0.1f, 0.5f};
          d.apertureRadius = aperture;
          d.focusDistance = 3.5f;
          d.lensShape = shape;
          const Camera cam(d, 16, 9);
          const int n = 23;
          std::vector<Vec2f> film, lens;
          std::vector<int> slot;
          for (int i = 0; i < n; ++i) {
            const auto t = static_cast<float>(i);
            film.push_back({std::fmod(t * 3.7f, 16.0f), std::fmod(t * 1.3f, 9.0f)});
            // The lens's centre and corners, then points inside.
            lens.push_back(
                i < 5 ? Vec2f{i == 0 ? 0.5f : float(i & 1), i == 0 ? 0.5f : float(i >> 1 & 1)}
                      : Vec2f{std::fmod(t * 0.618f, 1.0f), std::fmod(t * 0.382f, 1.0f)});
            slot.push_back((i * 7) % n);
          }
          std::vector<Ray> rays(n);
          cam.generateRays(film.data(), lens.data(), n, rays.data(), slot.data());
          for (int i = 0; i < n; ++i) {
            Ray alone;
            alone.time = 0.5f;
            cam.generateRay(film[size_t(i)].x, film[size_t(i)].y, lens[size_t(i)], alone);
            const Ray& r = rays[size_t(slot[size_t(i)])];
            EXPECT_EQ(std::memcmp(&r, &alone, sizeof r), 0)
                << int(projection) << oblique << aperture << int(shape) << " ray " << i;
          }
        }
}

// worldToNDC (the EXR's) maps every point of a pixel's ray to that pixel's place in the image,
// for centred, off-centre and oblique cameras of both projections.
TEST(Camera, WorldToNdcAgreesWithTheRaysOfEveryCamera) {
  for (const Projection projection : {Projection::Perspective, Projection::Orthographic})
    for (const bool oblique : {false, true})
      for (const bool offCentre : {false, true}) {
        CameraDesc d;
        d.projection = projection;
        d.eye = {1, 2, 3};
        d.lookAt = {0, 1.5f, -1};
        if (oblique) d.imagePlaneNormal = Vec3f{0.3f, 0.4f, 1};
        if (offCentre) d.window = ImageWindow{-0.2f, 0.7f, -0.1f, 0.5f};
        const int width = 8, height = 5;
        const Camera cam(d, width, height);
        const Mat4 m = cam.worldToNdc();
        for (const Vec2f pixel : {Vec2f{0.5f, 0.5f}, Vec2f{7.25f, 1.5f}, Vec2f{3, 4.75f}}) {
          const Ray r = cam.generateRay(pixel.x, pixel.y);
          const Vec3f p = r.o + 3.0f * r.d;
          float out[4];
          for (int i = 0; i < 4; ++i)
            out[i] = m(i, 0) * p.x + m(i, 1) * p.y + m(i, 2) * p.z + m(i, 3);
          EXPECT_NEAR(out[0] / out[3], pixel.x / width, 1e-5)
              << int(projection) << oblique << offCentre;
          EXPECT_NEAR(out[1] / out[3], pixel.y / height, 1e-5)
              << int(projection) << oblique << offCentre;
        }
      }
}

}  // namespace
}  // namespace glint
