#include "film/input_colorspace.h"

#include <cmath>
#include <cstdio>

#include "core/error.h"

namespace glint {

namespace {

using Mat3 = std::array<double, 9>;

Mat3 multiply(const Mat3& a, const Mat3& b) {
  Mat3 m{};
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c)
      for (int k = 0; k < 3; ++k)
        m[size_t(3 * r + c)] += a[size_t(3 * r + k)] * b[size_t(3 * k + c)];
  return m;
}

std::optional<Mat3> inverse(const Mat3& m) {
  const double det = m[0] * (m[4] * m[8] - m[5] * m[7]) - m[1] * (m[3] * m[8] - m[5] * m[6]) +
                     m[2] * (m[3] * m[7] - m[4] * m[6]);
  if (!std::isfinite(det) || std::fabs(det) < 1e-12) return std::nullopt;
  const double s = 1 / det;
  return Mat3{(m[4] * m[8] - m[5] * m[7]) * s, (m[2] * m[7] - m[1] * m[8]) * s,
              (m[1] * m[5] - m[2] * m[4]) * s, (m[5] * m[6] - m[3] * m[8]) * s,
              (m[0] * m[8] - m[2] * m[6]) * s, (m[2] * m[3] - m[0] * m[5]) * s,
              (m[3] * m[7] - m[4] * m[6]) * s, (m[1] * m[6] - m[0] * m[7]) * s,
              (m[0] * m[4] - m[1] * m[3]) * s};
}

std::array<double, 3> transformed(const Mat3& m, const std::array<double, 3>& v) {
  return {m[0] * v[0] + m[1] * v[1] + m[2] * v[2], m[3] * v[0] + m[4] * v[1] + m[5] * v[2],
          m[6] * v[0] + m[7] * v[1] + m[8] * v[2]};
}

std::array<double, 3> xyzOf(double x, double y) { return {x / y, 1.0, (1 - x - y) / y}; }

// The spaces of the bundled config a file's chromaticities may name: red, green, blue, white.
struct KnownSpace {
  const char* name;
  std::array<double, 8> rgbw;
};
constexpr KnownSpace kKnownSpaces[] = {
    {"lin_rec709", {0.64, 0.33, 0.30, 0.60, 0.15, 0.06, 0.3127, 0.3290}},
    // ACES AP0 and AP1, with the ACES white (about D60).
    {"ACES2065-1", {0.7347, 0.2653, 0.0, 1.0, 0.0001, -0.077, 0.32168, 0.33767}},
    {"ACEScg", {0.713, 0.293, 0.165, 0.830, 0.128, 0.044, 0.32168, 0.33767}},
};
// Closer than this in every coordinate is the same space: files store them as float, and
// D60 and D65 are 0.009 apart.
constexpr double kSameChromaticity = 1e-3;

// Bradford's cone response (Lam 1985), the adaptation the bundled config's Rec.709 ↔ AP0 matrix
// and ACES use.
constexpr Mat3 kBradford = {0.8951, 0.2664, -0.1614, -0.7502, 1.7135,
                            0.0367, 0.0389, -0.0685, 1.0296};

// XYZ under white `from` → XYZ under white `to` (both with Y = 1).
Mat3 bradford(const std::array<double, 3>& from, const std::array<double, 3>& to) {
  const std::array<double, 3> a = transformed(kBradford, from), b = transformed(kBradford, to);
  const Mat3 scale = {b[0] / a[0], 0, 0, 0, b[1] / a[1], 0, 0, 0, b[2] / a[2]};
  return multiply(*inverse(kBradford), multiply(scale, kBradford));
}

std::string chromaticityText(const std::array<double, 8>& c) {
  char text[160];
  std::snprintf(text, sizeof text,
                "red (%.4g, %.4g), green (%.4g, %.4g), blue (%.4g, %.4g), white (%.4g, %.4g)", c[0],
                c[1], c[2], c[3], c[4], c[5], c[6], c[7]);
  return text;
}

}  // namespace

std::optional<std::array<double, 9>> rgbToXyz(const std::array<double, 8>& c) {
  for (double v : c)
    if (!std::isfinite(v)) return std::nullopt;
  if (c[1] == 0 || c[3] == 0 || c[5] == 0 || c[7] == 0) return std::nullopt;
  const auto r = xyzOf(c[0], c[1]), g = xyzOf(c[2], c[3]), b = xyzOf(c[4], c[5]);
  const Mat3 primaries = {r[0], g[0], b[0], r[1], g[1], b[1], r[2], g[2], b[2]};
  const std::optional<Mat3> inv = inverse(primaries);
  if (!inv) return std::nullopt;
  // Each primary's share of white: S = P⁻¹·W, M = P·diag(S).
  const std::array<double, 3> s = transformed(*inv, xyzOf(c[6], c[7]));
  Mat3 m = primaries;
  for (int row = 0; row < 3; ++row)
    for (int col = 0; col < 3; ++col) m[size_t(3 * row + col)] *= s[size_t(col)];
  for (double v : m)
    if (!std::isfinite(v)) return std::nullopt;
  return m;
}

InputColorspace inputColorspace(const Image& image, const std::string& path,
                                const std::string& named) {
  if (!named.empty()) return {named, std::nullopt, "--input-colorspace " + inQuotes(named)};
  if (!image.colorspace.empty())
    return {image.colorspace, std::nullopt, "its glint:colorspace " + inQuotes(image.colorspace)};
  if (!image.chromaticities)
    return {"", std::nullopt,
            "the OCIO config's scene_linear: it names no colour space and has no chromaticities"};
  std::array<double, 8> c{};
  for (size_t i = 0; i < c.size(); ++i) c[i] = (*image.chromaticities)[i];
  for (const KnownSpace& k : kKnownSpaces) {
    bool same = true;
    for (size_t i = 0; i < c.size(); ++i) same &= std::fabs(c[i] - k.rgbw[i]) < kSameChromaticity;
    if (same)
      return {k.name, std::nullopt, std::string(k.name) + ", which its chromaticities name"};
  }
  // Chromaticities define a linear RGB space exactly (OpenEXR's ImfChromaticities.h): through
  // XYZ, adapted to D65 as the bundled config adapts, into Glint's rendering space.
  const std::optional<Mat3> fileToXyz = rgbToXyz(c);
  if (!fileToXyz)
    throw UsageError(path + ": its chromaticities describe no RGB space (" + chromaticityText(c) +
                     "): name its colour space with --input-colorspace");
  const std::array<double, 8> rec709 = kKnownSpaces[0].rgbw;
  const Mat3 xyzToRec709 = *inverse(*rgbToXyz(rec709));
  const Mat3 toRec709 = multiply(
      xyzToRec709, multiply(bradford(xyzOf(c[6], c[7]), xyzOf(rec709[6], rec709[7])), *fileToXyz));
  return {kRenderingColorspace, toRec709,
          "its chromaticities (" + chromaticityText(c) + "), converted to " + kRenderingColorspace +
              " by the matrix they define"};
}

}  // namespace glint
