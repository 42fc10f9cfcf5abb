#include "film/display_tag.h"

#include <cctype>

namespace glint {

namespace {

// ITU-T H.273 code points (the values cICP stores).
constexpr uint8_t kPrimariesRec709 = 1, kPrimariesRec2020 = 9, kPrimariesP3D65 = 12;
constexpr uint8_t kTransferRec709 = 1, kTransferSrgb = 13, kTransferPq = 16, kTransferHlg = 18;

// White, red, green, blue (x, y): D65 white for all three.
constexpr std::array<double, 8> kRec709 = {0.3127, 0.3290, 0.64, 0.33, 0.30, 0.60, 0.15, 0.06};
constexpr std::array<double, 8> kP3D65 = {0.3127, 0.3290, 0.680, 0.320, 0.265, 0.690, 0.150, 0.060};
constexpr std::array<double, 8> kRec2020 = {0.3127, 0.3290, 0.708, 0.292,
                                            0.170,  0.797,  0.131, 0.046};

// Lower-case letters and digits only, without a trailing "display" ("sRGB - Display" → "srgb").
std::string normalised(const std::string& name) {
  std::string s;
  for (unsigned char c : name)
    if (std::isalnum(c)) s += char(std::tolower(c));
  const std::string suffix = "display";
  if (s.size() > suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0)
    s.resize(s.size() - suffix.size());
  return s;
}

ColourTag cicp(uint8_t primaries, uint8_t transfer, const std::array<double, 8>& chromaticities,
               double encodingGamma) {
  ColourTag t;
  t.kind = ColourTag::Kind::Cicp;
  t.primaries = primaries;
  t.transfer = transfer;
  t.chromaticities = chromaticities;
  t.encodingGamma = encodingGamma;
  return t;
}

ColourTag tagFor(const std::string& name) {
  const std::string n = normalised(name);
  if (n == "srgb") {
    ColourTag t;
    t.kind = ColourTag::Kind::Srgb;
    return t;
  }
  // The sRGB piecewise curve; gAMA approximates it by 1/2.2, as the sRGB chunk's gAMA does.
  if (n == "displayp3") return cicp(kPrimariesP3D65, kTransferSrgb, kP3D65, 1 / 2.2);
  // BT.1886 is the display's inverse of the BT.709 signal: H.273 tags such video as
  // transfer 1 (BT.709), and gAMA states the 2.4 power the encoding applies.
  if (n == "rec1886" || n == "rec1886rec709" || n == "bt1886" || n == "rec709")
    return cicp(kPrimariesRec709, kTransferRec709, kRec709, 1 / 2.4);
  if (n == "rec1886rec2020" || n == "rec2020")
    return cicp(kPrimariesRec2020, kTransferRec709, kRec2020, 1 / 2.4);
  // No power law describes PQ or HLG: no gAMA (0), which old readers would misapply.
  if (n == "rec2100pq" || n == "st2084") return cicp(kPrimariesRec2020, kTransferPq, kRec2020, 0);
  if (n == "rec2100hlg") return cicp(kPrimariesRec2020, kTransferHlg, kRec2020, 0);
  return {};
}

}  // namespace

ColourTag colourTagForDisplay(const std::vector<std::string>& names) {
  for (const std::string& name : names)
    if (const ColourTag t = tagFor(name); t.kind != ColourTag::Kind::None) return t;
  return {};
}

}  // namespace glint
