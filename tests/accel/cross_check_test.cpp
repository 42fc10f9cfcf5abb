// What `glint validate` counts as agreement (accel/cross_check.h).
#include "accel/cross_check.h"

#include <gtest/gtest.h>

#include <utility>

namespace glint {
namespace {

// A backend that answers every ray with the same hit.
class FixedAnswer final : public Accelerator {
 public:
  explicit FixedAnswer(Hit hit) : hit_(hit) {}
  Hit intersect(const Ray&) const override { return hit_; }
  bool occluded(const Ray&) const override { return bool(hit_); }
  std::string_view name() const override { return "fixed"; }

 private:
  Hit hit_;
};

Hit hitAt(float t) { return Hit{t, 0, 0, 0, 7, kInvalidId}; }

TEST(CrossCheck, AHitAtTheRaysOriginAgainstAMissIsATieCountedApart) {
  // The origin's largest coordinate is 4, so a hit within 4·2⁻²⁰ = 3.8·10⁻⁶ of it is the
  // surface the ray starts on: t = 0 in exact arithmetic, a hit or a miss by rounding.
  const Ray ray{{4, 0.5f, -1}, {0, 0, 1}};
  const FixedAnswer miss(Hit{}), nearOrigin(hitAt(3e-6f)), beyond(hitAt(5e-6f));
  for (const auto& [first, second] : {std::pair{&miss, &nearOrigin}, {&nearOrigin, &miss}}) {
    const CrossCheck tie(*first, {second});
    tie.intersect(ray);
    tie.occluded(ray);
    EXPECT_EQ(tie.stats().hitAgree, 1u);
    EXPECT_EQ(tie.stats().primAgree, 1u);
    EXPECT_EQ(tie.stats().occlusionAgree, 1u);
    EXPECT_EQ(tie.stats().originTies, 2u);  // one closest-hit and one occlusion query
    EXPECT_TRUE(tie.stats().relDt.empty());
    EXPECT_TRUE(tie.stats().firstDisagreements.empty());
  }
  // Past the tolerance it is a disagreement, in both queries, whichever backend hits.
  for (const auto& [first, second] : {std::pair{&beyond, &miss}, {&miss, &beyond}}) {
    const CrossCheck apart(*first, {second});
    apart.intersect(ray);
    apart.occluded(ray);
    EXPECT_EQ(apart.stats().hitAgree, 0u);
    EXPECT_EQ(apart.stats().occlusionAgree, 0u);
    EXPECT_EQ(apart.stats().originTies, 0u);
    EXPECT_EQ(apart.stats().firstDisagreements.size(), 2u);
  }
}

TEST(CrossCheck, SeeingTheOriginsSurfaceOrTheNextOneIsATie) {
  // One backend sees the surface the ray starts on, the other the next one along it.
  const Ray ray{{0, 0, 0}, {1, 0, 0}};
  const FixedAnswer origin(hitAt(1e-7f)), next{Hit{2.5f, 0, 0, 3, 1, kInvalidId}};
  const CrossCheck check(origin, {&next});
  check.intersect(ray);
  EXPECT_EQ(check.stats().primAgree, 1u);
  EXPECT_EQ(check.stats().originTies, 1u);
}

}  // namespace
}  // namespace glint
