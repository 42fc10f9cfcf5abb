// The fits and the SVG of `glint converge` (app/convergence_plot.h): slopes from points on an
// exact power law, no slope where there is no line to fit, and a plot of a frame that converged
// exactly (every error 0), which once never finished.
#include "app/convergence_plot.h"

#include <gtest/gtest.h>

#include <cmath>

#include "test_util.h"

namespace glint {
namespace {

ConvergenceSeries series(std::initializer_list<ConvergencePoint> points) {
  ConvergenceSeries s;
  s.name = "test";
  s.points = points;
  return s;
}

TEST(ConvergencePlot, SlopesOfAnExactPowerLaw) {
  // rmse = 0.1 / √spp, seconds = 0.01 · spp: log rmse falls by ½ per decade of spp and of time;
  // the intercept is log10(0.1 / √(1/0.01)) = log10(0.01) = −2.
  ConvergenceSeries s =
      series({{4, 0.04, 0.04, 0.05, 0}, {16, 0.16, 0.16, 0.025, 0}, {64, 0.64, 0.64, 0.0125, 0}});
  fitSlopes(s);
  EXPECT_NEAR(s.slope, -0.5, 1e-12);
  EXPECT_NEAR(s.sppSlope, -0.5, 1e-12);
  EXPECT_NEAR(s.intercept, -2.0, 1e-12);
  EXPECT_EQ(slopeText(s.slope), "-0.500");
}

TEST(ConvergencePlot, NoSlopeWithoutTwoPointsAboveZero) {
  // Errors of 0 (a frame that converged exactly) and a single point leave nothing to fit; times
  // of 0 leave the spp slope, which does not need them (rmse halves per 4× spp: −0.5).
  ConvergenceSeries zero = series({{1, 0.1, 0.1, 0, 0}, {2, 0.2, 0.2, 0, 0}});
  fitSlopes(zero);
  EXPECT_TRUE(std::isnan(zero.slope));
  EXPECT_TRUE(std::isnan(zero.sppSlope));
  EXPECT_EQ(slopeText(zero.slope), "n/a");
  ConvergenceSeries one = series({{4, 0.1, 0.1, 0.05, 0}});
  fitSlopes(one);
  EXPECT_TRUE(std::isnan(one.slope));
  ConvergenceSeries untimed = series({{4, 0, 0, 0.05, 0}, {16, 0, 0, 0.025, 0}});
  fitSlopes(untimed);
  EXPECT_TRUE(std::isnan(untimed.slope));
  EXPECT_NEAR(untimed.sppSlope, -0.5, 1e-12);
}

TEST(ConvergencePlot, AFrameWithEveryErrorZeroIsPlottedAndSaysWhyItIsEmpty) {
  // Its axes once spanned 1e300 to 1e300 + 1, and the decade loop never ended.
  ConvergenceSeries s = series({{1, 0.1, 0.1, 0, 0}, {2, 0.2, 0.2, 0, 0}});
  fitSlopes(s);
  const std::string path = (test::tempDir() / "converged-exactly.svg").string();
  writeConvergenceSvg(path, "exact", {s});
  const std::string svg = test::readFile(path);
  EXPECT_NE(svg.find("no point with an error and a time above zero"), std::string::npos);
  EXPECT_NE(svg.find("test: slope n/a (n/a vs spp)"), std::string::npos);
  EXPECT_NE(svg.rfind("</svg>"), std::string::npos);
}

}  // namespace
}  // namespace glint
