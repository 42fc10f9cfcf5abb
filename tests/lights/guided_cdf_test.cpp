// The guided inversion of a cumulative table (lights/guided_cdf.h): the guide only shortens the
// search, so for every u it must return the cell, and the place within it, that a binary search
// of the whole table returns. That is what keeps the environment's samples, and every image
// lit by one, the same.
#include "lights/guided_cdf.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

namespace glint {
namespace {

// The definition the guide must reproduce: the last cell whose start is ≤ u, by a search of the
// whole table, and u's place in it.
int searchWhole(const std::vector<float>& cdf, float u, float& within) {
  const int n = static_cast<int>(cdf.size()) - 1;
  const auto above = std::upper_bound(cdf.begin() + 1, cdf.end(), u);
  const int i = std::clamp(static_cast<int>(above - cdf.begin()) - 1, 0, n - 1);
  const float width = cdf[i + 1] - cdf[i];
  within = width > 0 ? std::clamp((u - cdf[i]) / width, 0.0f, 0x1.fffffep-1f) : 0.5f;
  return i;
}

// A cumulative table of the weights, normalised as the environment's are (float of the running
// sum over the total in double, the last entry exactly 1; all 0 when the weights are).
std::vector<float> cumulative(const std::vector<double>& weight) {
  std::vector<float> cdf(weight.size() + 1, 0.0f);
  double total = 0;
  for (double w : weight) total += w;
  double running = 0;
  for (size_t i = 0; i < weight.size(); ++i) {
    running += weight[i];
    cdf[i + 1] = total > 0 ? static_cast<float>(running / total) : 0.0f;
  }
  if (total > 0) cdf.back() = 1;
  return cdf;
}

struct Guided {
  std::vector<float> cdf;
  std::vector<uint32_t> guide;
  GuidedCdf table;
  explicit Guided(std::vector<float> c) : cdf(std::move(c)) {
    const int n = static_cast<int>(cdf.size()) - 1;
    const int bins = guideBinsFor(n);
    guide.resize(static_cast<size_t>(bins) + 1);
    GuidedCdf::buildGuide(cdf.data(), n, bins, guide.data());
    table = {cdf.data(), n, guide.data(), bins};
  }
};

// Every u the test tries on a table: random ones, and the floats at and beside every table
// entry and every guide bin's edge, where an off-by-one would show; 0, the last float below 1,
// and (never drawn, but defined) 1, a negative u and a NaN.
std::vector<float> probes(const Guided& g, int random) {
  std::vector<float> u;
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> uniform(0.0f, 1.0f);
  for (int i = 0; i < random; ++i) u.push_back(uniform(rng));
  auto around = [&](float x) {
    for (float v : {std::nextafter(x, -1.0f), x, std::nextafter(x, 2.0f)}) u.push_back(v);
  };
  for (float c : g.cdf) around(c);
  for (int j = 0; j <= g.table.bins; ++j)
    around(static_cast<float>(j) / static_cast<float>(g.table.bins));
  for (float v : {0.0f, 0x1.fffffep-1f, 1.0f, -0.25f, std::nanf("")}) u.push_back(v);
  return u;
}

void expectSameAsWholeSearch(const Guided& g, int random) {
  for (float u : probes(g, random)) {
    float withinGuided = -1, withinWhole = -2;
    const int guided = g.table.find(u, withinGuided);
    const int whole = searchWhole(g.cdf, u, withinWhole);
    ASSERT_EQ(guided, whole) << "u = " << u;
    if (std::isnan(withinWhole))
      EXPECT_TRUE(std::isnan(withinGuided)) << "u = " << u;
    else
      ASSERT_EQ(withinGuided, withinWhole) << "u = " << u;
  }
}

TEST(GuidedCdf, BinsAreThePowerOfTwoAtOrBelowTheCells) {
  // A power of two makes the bins' edges and u·bins exact; no more bins than cells keeps the
  // guide no larger than its table.
  EXPECT_EQ(guideBinsFor(1), 1);
  EXPECT_EQ(guideBinsFor(2), 2);
  EXPECT_EQ(guideBinsFor(3), 2);
  EXPECT_EQ(guideBinsFor(128), 128);
  EXPECT_EQ(guideBinsFor(257), 256);
}

TEST(GuidedCdf, FindsWhatASearchOfTheWholeTableFinds) {
  // Weights from a sky: mostly dim, a few texels many thousand times brighter, and runs of
  // zero (cells no u may land in), at sizes that are and are not powers of two.
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> dim(0.0, 1.0);
  for (int n : {1, 2, 3, 7, 64, 100, 256, 257, 1000}) {
    std::vector<double> weight(static_cast<size_t>(n));
    for (int i = 0; i < n; ++i) {
      const double w = dim(rng);
      weight[static_cast<size_t>(i)] = i % 37 == 5 ? 5e4 * w : i % 11 < 3 ? 0 : w;
    }
    SCOPED_TRACE(n);
    expectSameAsWholeSearch(Guided(cumulative(weight)), 4000);
  }
}

TEST(GuidedCdf, AllBlackTableAnswersItsLastCell) {
  // No weight: the table stays 0 and every u lies past it; the last cell comes back, in its
  // middle (the environment then carries black).
  const Guided g(cumulative(std::vector<double>(9, 0.0)));
  float within = 0;
  EXPECT_EQ(g.table.find(0.3f, within), 8);
  EXPECT_EQ(within, 0.5f);
  expectSameAsWholeSearch(g, 200);
}

TEST(GuidedCdf, ASingleBrightCellTakesEveryU) {
  // One cell holds all the weight: every u in [0, 1) chooses it, spread evenly over it.
  std::vector<double> weight(300, 0.0);
  weight[123] = 2.5;
  const Guided g(cumulative(weight));
  float within = 0;
  for (float u : {0.0f, 0.25f, 0.5f, 0x1.fffffep-1f}) {
    EXPECT_EQ(g.table.find(u, within), 123) << u;
    EXPECT_EQ(within, u) << u;
  }
  expectSameAsWholeSearch(g, 200);
}

}  // namespace
}  // namespace glint
