#pragma once
// A log-log plot of error against run time, one series per sampler/backend with its fitted
// slope drawn and printed, written directly as SVG (no plotting library needed).
#include <string>
#include <vector>

namespace glint {

struct ConvergencePoint {
  int spp = 0;
  double seconds = 0, cpuSeconds = 0, rmse = 0, relmse = 0;
};

struct ConvergenceSeries {
  std::string name;
  std::vector<ConvergencePoint> points;
  // log10 rmse = intercept + slope · log10 seconds; NaN where fewer than two points with error,
  // time and spp above zero and apart in time (in spp for sppSlope) leave no line to fit.
  double slope = 0, intercept = 0;
  double sppSlope = 0;  // log10 rmse against log10 spp
};

// Least-squares fits of log10(rmse) against log10(seconds) and log10(spp).
void fitSlopes(ConvergenceSeries& s);
// "-0.512", or "n/a" for a slope that could not be fitted.
std::string slopeText(double slope);
void writeConvergenceSvg(const std::string& path, const std::string& title,
                         const std::vector<ConvergenceSeries>& series);

}  // namespace glint
