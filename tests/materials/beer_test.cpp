// Absorption inside a dielectric (materials/beer.h): Beer's law a^s, with no NaN at the edges.
#include "materials/beer.h"

#include <gtest/gtest.h>

#include <cstring>

#include "core/vec.h"

namespace glint {
namespace {

TEST(Beer, KeepsAToThePowerOfTheDistance) {
  EXPECT_NEAR(beerChannel(0.5f, 2), 0.25f, 1e-7);  // 0.5² over two units
  EXPECT_NEAR(beerChannel(0.9f, 0.5f), std::sqrt(0.9f), 1e-7);
  const Rgb T = beer({0.5f, 0.8f, 1}, 3);
  EXPECT_NEAR(T.r, 0.125f, 1e-7);
  EXPECT_NEAR(T.g, 0.512f, 1e-6);
  EXPECT_EQ(T.b, 1.0f);
}

TEST(Beer, NeverProducesNaN) {
  EXPECT_EQ(beerChannel(1, kInfinity), 1.0f);  // clear medium, infinite path: ln 1·∞ avoided
  EXPECT_EQ(beerChannel(0.5f, kInfinity), 0.0f);
  EXPECT_EQ(beerChannel(0, 0.001f), 0.0f);  // ln 0 = −∞ avoided
  EXPECT_EQ(beerChannel(0, 0), 1.0f);       // no distance, no absorption
}

// A medium takes its logarithms once (BeerMedium); that must change no bit of what beer()
// gives, at the edges (a of 0 or 1, no distance, infinite distance) and in between.
TEST(Beer, MediumGivesBeerBitForBit) {
  const float as[] = {0, 1e-30f, 0.01f, 0.5f, 0.92f, 0.999999f, 1};
  const float ss[] = {0, 1e-6f, 0.37f, 1, 12.5f, 1e4f, kInfinity};
  for (const float r : as)
    for (const float g : as) {
      const Rgb a{r, g, 0.5f};
      const BeerMedium medium(a);
      EXPECT_TRUE(medium.absorbs());  // the blue channel keeps half per unit
      for (const float s : ss) {
        const Rgb once = medium.transmittance(s), each = beer(a, s);
        EXPECT_TRUE(std::memcmp(&once, &each, sizeof(Rgb)) == 0)
            << "a (" << r << ", " << g << ") s " << s << ": " << once.r << " " << once.g
            << " against " << each.r << " " << each.g;
      }
    }
  EXPECT_FALSE(BeerMedium({1, 1, 1}).absorbs());
}

}  // namespace
}  // namespace glint
