#include "app/convergence_plot.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <string>

#include "film/atomic_file.h"

namespace glint {

namespace {

void leastSquares(const std::vector<double>& x, const std::vector<double>& y, double& slope,
                  double& intercept) {
  const double n = double(x.size());
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (size_t i = 0; i < x.size(); ++i)
    sx += x[i], sy += y[i], sxx += x[i] * x[i], sxy += x[i] * y[i];
  const double d = n * sxx - sx * sx;
  slope = n >= 2 && d > 0 ? (n * sxy - sx * sy) / d : std::nan("");
  intercept = (sy - slope * sx) / n;
}

std::string esc(const std::string& s) {
  std::string o;
  for (char c : s) o += c == '<' ? "&lt;" : c == '&' ? "&amp;" : std::string(1, c);
  return o;
}

}  // namespace

void fitSlopes(ConvergenceSeries& s) {
  std::vector<double> lt, le, ls, lse;  // (time, error) and (spp, error), logs of those above 0
  for (const auto& p : s.points) {
    if (!(p.rmse > 0)) continue;
    if (p.seconds > 0) lt.push_back(std::log10(p.seconds)), le.push_back(std::log10(p.rmse));
    if (p.spp > 0) ls.push_back(std::log10(double(p.spp))), lse.push_back(std::log10(p.rmse));
  }
  leastSquares(lt, le, s.slope, s.intercept);
  double unused;
  leastSquares(ls, lse, s.sppSlope, unused);
}

std::string slopeText(double slope) {
  if (!std::isfinite(slope)) return "n/a";
  char text[32];
  std::snprintf(text, sizeof text, "%.3f", slope);
  return text;
}

void writeConvergenceSvg(const std::string& path, const std::string& title,
                         const std::vector<ConvergenceSeries>& series) {
  static const char* kColours[] = {"#1f77b4", "#d62728", "#2ca02c",
                                   "#9467bd", "#ff7f0e", "#8c564b"};
  double tMin = 1e300, tMax = -1e300, eMin = 1e300, eMax = -1e300;
  for (const auto& s : series)
    for (const auto& p : s.points)
      if (p.rmse > 0 && p.seconds > 0) {
        tMin = std::min(tMin, std::log10(p.seconds));
        tMax = std::max(tMax, std::log10(p.seconds));
        eMin = std::min(eMin, std::log10(p.rmse));
        eMax = std::max(eMax, std::log10(p.rmse));
      }
  // A log-log plot cannot show a zero error or time (an empty scene converges exactly): with
  // no other point the axes keep a decade each and the plot says why it is empty.
  const bool empty = tMin > tMax;
  if (empty) tMin = -1, tMax = 0, eMin = -3, eMax = -2;
  tMin = std::floor(tMin * 2) / 2, tMax = std::ceil(tMax * 2) / 2;
  eMin = std::floor(eMin * 2) / 2, eMax = std::ceil(eMax * 2) / 2;
  if (tMax <= tMin) tMax = tMin + 1;
  if (eMax <= eMin) eMax = eMin + 1;
  const double W = 860, H = 480, L = 80, R = 340, T = 40, B = 60;
  const auto X = [&](double lt) { return L + (lt - tMin) / (tMax - tMin) * (W - L - R); };
  const auto Y = [&](double le) { return H - B - (le - eMin) / (eMax - eMin) * (H - T - B); };
  std::ostringstream o;
  o << "<svg xmlns='http://www.w3.org/2000/svg' width='" << W << "' height='" << H
    << "' font-family='sans-serif' font-size='12'>\n<rect width='100%' height='100%' "
       "fill='white'/>\n";
  o << "<text x='" << W / 2 << "' y='22' text-anchor='middle' font-size='15'>" << esc(title)
    << "</text>\n";
  // Decade grid and labels (logs of finite doubles lie within ±324: a few hundred decades).
  for (int v = int(std::ceil(tMin)); v <= int(std::floor(tMax)); ++v)
    o << "<line x1='" << X(v) << "' y1='" << T << "' x2='" << X(v) << "' y2='" << H - B
      << "' stroke='#ddd'/><text x='" << X(v) << "' y='" << H - B + 18
      << "' text-anchor='middle'>1e" << v << "</text>\n";
  for (int v = int(std::ceil(eMin)); v <= int(std::floor(eMax)); ++v)
    o << "<line x1='" << L << "' y1='" << Y(v) << "' x2='" << W - R << "' y2='" << Y(v)
      << "' stroke='#ddd'/><text x='" << L - 8 << "' y='" << Y(v) + 4 << "' text-anchor='end'>1e"
      << v << "</text>\n";
  if (empty)
    o << "<text x='" << (L + W - R) / 2 << "' y='" << (T + H - B) / 2
      << "' text-anchor='middle'>no point with an error and a time above zero</text>\n";
  o << "<rect x='" << L << "' y='" << T << "' width='" << W - L - R << "' height='" << H - T - B
    << "' fill='none' stroke='black'/>\n";
  o << "<text x='" << (L + W - R) / 2 << "' y='" << H - 15
    << "' text-anchor='middle'>wall-clock seconds</text>\n";
  o << "<text transform='translate(20," << (T + H - B) / 2
    << ") rotate(-90)' text-anchor='middle'>RMSE against the reference</text>\n";
  for (size_t i = 0; i < series.size(); ++i) {
    const auto& s = series[i];
    const char* col = kColours[i % 6];
    std::string pts;
    for (const auto& p : s.points)
      if (p.rmse > 0 && p.seconds > 0) {
        const double x = X(std::log10(p.seconds)), y = Y(std::log10(p.rmse));
        pts += std::to_string(x) + "," + std::to_string(y) + " ";
        o << "<circle cx='" << x << "' cy='" << y << "' r='3.5' fill='" << col << "'/>\n";
      }
    o << "<polyline points='" << pts << "' fill='none' stroke='" << col
      << "' stroke-width='1.5'/>\n";
    // The fitted line over the series' own time range, dashed.
    double lo = 1e300, hi = -1e300;
    for (const auto& p : s.points)
      if (p.rmse > 0 && p.seconds > 0)
        lo = std::min(lo, std::log10(p.seconds)), hi = std::max(hi, std::log10(p.seconds));
    if (hi > lo && std::isfinite(s.slope))
      o << "<line x1='" << X(lo) << "' y1='" << Y(s.intercept + s.slope * lo) << "' x2='" << X(hi)
        << "' y2='" << Y(s.intercept + s.slope * hi) << "' stroke='" << col
        << "' stroke-dasharray='5,4'/>\n";
    const std::string label =
        s.name + ": slope " + slopeText(s.slope) + " (" + slopeText(s.sppSlope) + " vs spp)";
    o << "<text x='" << W - R + 10 << "' y='" << T + 16 + 18 * double(i) << "' fill='" << col
      << "'>" << esc(label) << "</text>\n";
  }
  o << "</svg>\n";
  writeTextFileAtomically(path, o.str());
}

}  // namespace glint
