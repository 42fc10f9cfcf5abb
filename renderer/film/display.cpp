#include "film/display.h"

#include <OpenColorIO/OpenColorIO.h>
#include <glint_ocio_config.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <mutex>
#include <set>
#include <sstream>

#include "core/error.h"
#include "core/file_names.h"
#include "core/input_files.h"
#include "core/log.h"
#include "film/display_tag.h"
#include "film/image_file.h"
#include "film/image_format.h"
#include "film/ocio_cycles.h"
#include "film/ocio_files.h"

namespace OCIO = OCIO_NAMESPACE;

namespace glint {

namespace {

// `path`: a config file; empty: $OCIO, else the bundled config; "-": the bundled config.
// Every file the config reads is checked before any processor reads it (film/ocio_files.h),
// and its references for loops (film/ocio_cycles.h).
OCIO::ConstConfigRcPtr loadConfig(const std::string& path, std::string& source) {
  try {
    if (!path.empty() && path != "-") {
      checkInputFile(path, kMaxOcioConfigBytes, "OCIO config");
      source = path;
      const auto config = OCIO::Config::CreateFromFile(path.c_str());
      checkOcioConfigFiles(config, source);
      checkOcioReferenceCycles(config, source);
      return config;
    }
    if (const char* env = std::getenv("OCIO"); env && *env && path.empty()) {
      checkInputFile(env, kMaxOcioConfigBytes, "$OCIO's config");
      source = std::string("$OCIO = ") + env;
      const auto config = OCIO::Config::CreateFromFile(env);
      checkOcioConfigFiles(config, source);
      checkOcioReferenceCycles(config, source);
      return config;
    }
    source = "bundled (ocio/config.ocio)";
    std::istringstream in(kBundledOcioConfig);
    return OCIO::Config::CreateFromStream(in);
  } catch (const OCIO::Exception& e) {
    throw UsageError("cannot load the OCIO config " + source + ": " + e.what());
  }
}

// Appends to `group` what takes pixels from `source` into the config's scene_linear role and
// returns that role's name, or returns `source` itself where the config knows it (by name or
// alias). A studio config without Glint's rendering space is reached through both configs'
// interchange roles (aces_interchange): taking Rec.709 pixels as the config's scene_linear,
// say ACEScg, would show them oversaturated.
std::string sourceInConfig(const OCIO::ConstConfigRcPtr& config, const std::string& source,
                           OCIO::GroupTransformRcPtr& group) {
  if (source.empty()) return OCIO::ROLE_SCENE_LINEAR;
  if (config->getColorSpace(source.c_str())) return source;
  std::string bundledSource;
  const OCIO::ConstConfigRcPtr bundled = loadConfig("-", bundledSource);
  if (!bundled->getColorSpace(source.c_str()))
    throw UsageError("the image's colour space " + inQuotes(source) +
                     " is in neither the OCIO config nor Glint's bundled one");
  try {
    const auto toSceneLinear = OCIO::Config::GetProcessorFromConfigs(
        bundled, source.c_str(), config, OCIO::ROLE_SCENE_LINEAR);
    group->appendTransform(toSceneLinear->createGroupTransform());
  } catch (const OCIO::Exception& e) {
    throw UsageError("the OCIO config has no colour space " + inQuotes(source) +
                     " and Glint cannot convert to its scene_linear role (" + excerpt(e.what()) +
                     "): add an aces_interchange role to the config");
  }
  return OCIO::ROLE_SCENE_LINEAR;
}

}  // namespace

struct ToRenderingSpace::Impl {
  OCIO::ConstCPUProcessorRcPtr cpu;
};

ToRenderingSpace::ToRenderingSpace(const std::string& colorspace) : impl_(new Impl) {
  try {
    std::string source;
    OCIO::ConstConfigRcPtr config = loadConfig("", source);
    if (!config->getColorSpace(colorspace.c_str()) || !config->getColorSpace(kRenderingColorspace))
      config = loadConfig("-", source);
    if (!config->getColorSpace(colorspace.c_str()))
      throw UsageError("the colour space " + inQuotes(colorspace) +
                       " is in neither the OCIO config nor Glint's bundled one");
    const auto processor = config->getProcessor(colorspace.c_str(), kRenderingColorspace);
    identity_ = processor->isNoOp();
    impl_->cpu = processor->getDefaultCPUProcessor();
  } catch (const OCIO::Exception& e) {
    delete impl_;
    throw UsageError("OCIO cannot convert " + inQuotes(colorspace) + " to " + kRenderingColorspace +
                     ": " + excerpt(e.what()));
  } catch (...) {
    delete impl_;
    throw;
  }
}

ToRenderingSpace::~ToRenderingSpace() { delete impl_; }

void ToRenderingSpace::apply(float* rgb) const { impl_->cpu->applyRGB(rgb); }

struct DisplayTransform::Impl {
  OCIO::ConstCPUProcessorRcPtr cpu;
};

// The largest scene-linear value a view is given (half float's largest).
constexpr float kDisplayCeiling = 65504.0f;

DisplayTransform::DisplayTransform(const DisplaySettings& s) : impl_(new Impl) {
  try {
    const OCIO::ConstConfigRcPtr config = loadConfig(s.configPath, source_);
    const std::string display = s.display.empty() ? config->getDefaultDisplay() : s.display;
    std::string displays;
    bool knownDisplay = false;
    for (int d = 0; d < config->getNumDisplays(); ++d) {
      displays += (d ? ", " : "") + std::string(config->getDisplay(d));
      knownDisplay |= display == config->getDisplay(d);
    }
    if (!knownDisplay)
      throw UsageError("OCIO (" + source_ + "): no display " + inQuotes(display) +
                       "; displays: " + displays);
    const std::string view = s.view.empty() ? config->getDefaultView(display.c_str()) : s.view;
    std::string views;
    bool knownView = false;
    for (int v = 0; v < config->getNumViews(display.c_str()); ++v) {
      views += (v ? ", " : "") + std::string(config->getView(display.c_str(), v));
      knownView |= view == config->getView(display.c_str(), v);
    }
    if (!knownView)
      throw UsageError("OCIO (" + source_ + "): display " + inQuotes(display) + " has no view " +
                       inQuotes(view) + "; views: " + views);
    display_ = display;
    view_ = view;
    // A view whose colour space is data (Raw) encodes for no display: it gets no tag.
    const char* viewSpace = config->getDisplayViewColorSpaceName(display.c_str(), view.c_str());
    const auto viewColorSpace = viewSpace ? config->getColorSpace(viewSpace) : nullptr;
    if (!viewColorSpace || !viewColorSpace->isData()) {
      tag_ = colourTagForDisplay({viewSpace ? viewSpace : "", display});
      tagKnown_ = tag_.kind != ColourTag::Kind::None;
    }
    auto group = OCIO::GroupTransform::Create();
    if (s.toSource) {
      double m44[16] = {};
      for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) m44[4 * r + c] = (*s.toSource)[size_t(3 * r + c)];
      m44[15] = 1;
      const auto matrix = OCIO::MatrixTransform::Create();
      matrix->setMatrix(m44);
      group->appendTransform(matrix);
    }
    const std::string source = sourceInConfig(config, s.source, group);
    if (!s.look.empty()) {
      const auto look = OCIO::LookTransform::Create();
      look->setSrc(source.c_str());
      look->setDst(source.c_str());
      look->setLooks(s.look.c_str());
      group->appendTransform(look);
      // What the look gives is held to the ceiling the pixels were: a gain of 1e25 took ACES's
      // curve to NaN, a black image.
      const auto ceiling = OCIO::RangeTransform::Create();
      ceiling->setStyle(OCIO::RANGE_CLAMP);
      ceiling->setMinInValue(-kDisplayCeiling);
      ceiling->setMaxInValue(kDisplayCeiling);
      ceiling->setMinOutValue(-kDisplayCeiling);
      ceiling->setMaxOutValue(kDisplayCeiling);
      group->appendTransform(ceiling);
    }
    const auto dv = OCIO::DisplayViewTransform::Create();
    dv->setSrc(source.c_str());
    dv->setDisplay(display.c_str());
    dv->setView(view.c_str());
    group->appendTransform(dv);
    impl_->cpu = config->getProcessor(group)->getDefaultCPUProcessor();
  } catch (const OCIO::Exception& e) {
    delete impl_;
    throw UsageError("OCIO (" + source_ + "): " + excerpt(e.what()));
  } catch (...) {
    delete impl_;
    throw;
  }
}

DisplayTransform::~DisplayTransform() { delete impl_; }

void DisplayTransform::apply(float* pixels, int width, int height, int channels) const {
  tbb::parallel_for(tbb::blocked_range<int>(0, height), [&](const tbb::blocked_range<int>& r) {
    for (int y = r.begin(); y != r.end(); ++y) {
      OCIO::PackedImageDesc row(pixels + size_t(y) * size_t(width) * size_t(channels), width, 1,
                                channels);
      impl_->cpu->apply(row);
    }
  });
}

namespace {

// Each message once per process: a sequence of frames would repeat it for every one.
void warnOnce(const std::string& message) {
  static std::mutex mutex;
  static std::set<std::string> warned;
  const std::lock_guard<std::mutex> lock(mutex);
  if (warned.insert(message).second) log::warning(message);
}

}  // namespace

void writeDisplayImage(const std::string& path, std::vector<float> rgba, int width, int height,
                       const DisplaySettings& settings, bool transparent) {
  const ImageFormat format = imageOutputFormat("display image", path, ImageOutput::Display);
  const bool alpha = transparent && hasAlphaChannel(format);
  // Straight alpha (PNG's only kind; TIFF marked so): the view develops the colour of what
  // covers the pixel, so it is un-premultiplied while still scene-linear, where coverage mixes
  // colours linearly. Developing the premultiplied colour would darken edges through the
  // view's curve, and dividing after it could not undo that. Alpha 0 has no colour to
  // develop: it stays 0 (RGB is 0 there in Glint's frames), never 0/0.
  // A non-finite alpha (an EXR from elsewhere) made its finite colour black: NaN and +∞ are
  // taken as opaque, −∞ as empty, and counted in the warning below.
  size_t nonFiniteAlpha = 0;
  if (alpha)
    for (size_t p = 0; p < rgba.size(); p += 4) {
      float& a = rgba[p + 3];
      if (!std::isfinite(a)) {
        ++nonFiniteAlpha;
        a = a < 0 ? 0.0f : 1.0f;
      }
      for (int c = 0; c < 3; ++c) rgba[p + size_t(c)] = a > 0 ? rgba[p + size_t(c)] / a : 0.0f;
    }
  // The view is given at most half float's largest value, 65504: far past white in every view
  // of the bundled config, where ACES's took 1e22 to NaN, a black pixel. A frame of Glint's
  // holds no NaN or infinity; an EXR from elsewhere may, and is told so.
  size_t nonFinite = 0;
  for (size_t p = 0; p < rgba.size(); p += 4)
    for (size_t c = 0; c < 3; ++c) {
      float& v = rgba[p + c];
      if (!std::isfinite(v)) ++nonFinite;
      v = std::isnan(v) ? 0.0f : std::clamp(v, -kDisplayCeiling, kDisplayCeiling);
    }
  if (nonFinite > 0)
    log::warning(path + ": " + std::to_string(nonFinite) +
                 " colour values are not finite; NaN is shown as 0, infinity as ±65504");
  if (nonFiniteAlpha > 0)
    log::warning(path + ": " + std::to_string(nonFiniteAlpha) +
                 " alpha values are not finite; NaN and +infinity are shown as opaque, "
                 "-infinity as empty");
  const DisplayTransform transform(settings);
  transform.apply(rgba.data(), width, height, 4);
  // Finite pixels in, yet a view can overflow (a colour space scaled by 1e38) and give infinity
  // or NaN, which a PNG shows as black: that view is refused and nothing is written.
  size_t shownNonFinite = 0;
  for (size_t p = 0; p < rgba.size(); p += 4)
    for (size_t c = 0; c < 3; ++c) shownNonFinite += std::isfinite(rgba[p + c]) ? 0 : 1;
  if (shownNonFinite > 0)
    throw UsageError(
        "OCIO (" + transform.configSource() + "): display " + inQuotes(transform.display()) +
        ", view " + inQuotes(transform.view()) + " gives " + std::to_string(shownNonFinite) +
        " colour values that are not finite from finite pixels; " + path + " is not written");
  if (format == ImageFormat::Png && !transform.tagKnown())
    warnOnce("the OCIO display " + inQuotes(transform.display()) +
             " is not one Glint knows a PNG colour tag for (sRGB, Display P3, Rec.1886 / Rec.709, "
             "Rec.2020, Rec.2100 PQ / HLG): its PNGs carry no colour chunk, and readers will "
             "take them as sRGB");
  if (transparent && !alpha)
    warnOnce(std::string(formatName(format)) +
             " has no alpha channel: the transparent frame is shown over black (PNG and TIFF "
             "keep its alpha)");
  // Display-referred code values: clamp to [0, 1] (NaN → 0). Without alpha the image is the
  // premultiplied beauty over black: the opaque background, or black on a transparent film
  // written as JPEG.
  const bool tiff = format == ImageFormat::Tiff;
  const double scale = tiff ? 65535.0 : 255.0;
  const auto code = [&](float v) {
    return static_cast<uint16_t>(std::lround(scale * (v > 0 ? std::min(v, 1.0f) : 0.0f)));
  };
  CodeImage image;
  image.width = width;
  image.height = height;
  image.channels = alpha ? 4 : 3;
  image.bits = tiff ? 16 : 8;
  if (format == ImageFormat::Png) image.tag = transform.colourTag();
  image.codes.resize(size_t(width) * size_t(height) * size_t(image.channels));
  for (size_t i = 0, p = 0; p < rgba.size(); p += 4) {
    const bool covered = !alpha || rgba[p + 3] > 0;
    for (int c = 0; c < 3; ++c) image.codes[i++] = covered ? code(rgba[p + size_t(c)]) : 0;
    if (alpha) image.codes[i++] = code(rgba[p + 3]);
  }
  writeCodeImage(path, image);
}

void writeDisplayImage(const std::string& path, const Film& film, const DisplaySettings& settings,
                       bool transparent) {
  writeDisplayImage(path, film.toFloatRgba(), film.window().width(), film.window().height(),
                    settings, transparent);
}

std::vector<std::string> ocioColorSpaces(const std::string& configPath) {
  std::string source;
  const OCIO::ConstConfigRcPtr config = loadConfig(configPath, source);
  std::vector<std::string> names;
  for (int c = 0; c < config->getNumColorSpaces(); ++c)
    names.emplace_back(config->getColorSpaceNameByIndex(c));
  return names;
}

bool ocioHasColorSpace(const std::string& configPath, const std::string& name) {
  std::string source;
  return loadConfig(configPath, source)->getColorSpace(name.c_str()) != nullptr;
}

std::string describeOcioConfig(const std::string& configPath) {
  std::string source;
  const OCIO::ConstConfigRcPtr config = loadConfig(configPath, source);
  std::ostringstream out;
  out << "OCIO config  " << source << "\n";
  out << "scene_linear " << config->getColorSpace(OCIO::ROLE_SCENE_LINEAR)->getName() << "\n";
  for (int d = 0; d < config->getNumDisplays(); ++d) {
    const char* display = config->getDisplay(d);
    out << "display      " << display
        << (std::string(display) == config->getDefaultDisplay() ? " (default)" : "") << "\n";
    for (int v = 0; v < config->getNumViews(display); ++v) {
      const char* view = config->getView(display, v);
      out << "  view       " << view
          << (std::string(view) == config->getDefaultView(display) ? " (default)" : "") << "\n";
    }
  }
  out << "colorspaces ";
  for (int c = 0; c < config->getNumColorSpaces(); ++c)
    out << (c ? ", " : " ") << config->getColorSpaceNameByIndex(c);
  out << "\nlooks       ";
  for (int l = 0; l < config->getNumLooks(); ++l)
    out << (l ? ", " : " ") << config->getLookNameByIndex(l);
  if (config->getNumLooks() == 0) out << " (none)";
  out << "\n";
  return out.str();
}

}  // namespace glint
