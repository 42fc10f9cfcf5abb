// The interior list's crossings: which indices of refraction meet at a dielectric surface.
#include "integrator/medium_stack.h"

#include <gtest/gtest.h>

#include <vector>

namespace glint {
namespace {

TEST(MediumStack, LeavingAnObjectUsesTheMaterialItWasEnteredWith) {
  // A CSG solid is one object whose surfaces may name different dielectrics: entered through
  // glass (η 1.5), it is left through a surface that names water (η 1.33). Inside was glass
  // (Beer's law used it), so leaving goes from η 1.5 to the outside's 1.
  std::vector<Material> materials(2);
  materials[0].dielectric.ior = 1.5f;
  materials[1].dielectric.ior = 1.33f;
  const Hit hit{1, 0, 0, /*geomId*/ 3, /*primId*/ 7, kInvalidId};
  const Vec3f d{0, 0, -1};
  const MediumStack outside{};
  const Crossing in = crossingAt(outside, hit, 0, d, {0, 0, 1}, materials);
  ASSERT_TRUE(in.entering);
  EXPECT_EQ(in.etaI, 1.0f);
  EXPECT_EQ(in.etaT, 1.5f);
  const Crossing out = crossingAt(in.across, hit, 1, d, {0, 0, -1}, materials);
  ASSERT_FALSE(out.entering);
  EXPECT_EQ(out.etaI, 1.5f);
  EXPECT_EQ(out.etaT, 1.0f);
  EXPECT_TRUE(out.across.empty());
  // An object left without having been entered (a ray that starts inside it) takes the
  // surface's own material.
  EXPECT_EQ(crossingAt(outside, hit, 1, d, {0, 0, -1}, materials).etaI, 1.33f);
}

}  // namespace
}  // namespace glint
