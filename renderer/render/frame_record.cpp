#include "render/frame_record.h"

#include <glint_version.h>

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFloatAttribute.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfIntAttribute.h>
#include <OpenEXR/ImfMatrixAttribute.h>
#include <OpenEXR/ImfMultiPartInputFile.h>
#include <OpenEXR/ImfStringAttribute.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <limits>
#include <nlohmann/json.hpp>

#include "camera/camera.h"
#include "core/affine.h"
#include "core/error.h"
#include "core/hash.h"
#include "core/json_memory.h"
#include "core/log.h"
#include "film/display.h"
#include "film/exr_input.h"
#include "scene/scene.h"

namespace glint {

namespace {

// The sampling options that change pixels, for the settings hash.
std::string samplingSettings(const SamplingRequest& r) {
  std::string s;
  const auto add = [&](const char* name, double v) {
    if (!(v > 0)) return;
    // The shortest text that reads back as v: to_string's six decimals read 2e-7 and 4e-7 as
    // one target.
    char text[32];
    const auto end = std::to_chars(text, text + sizeof text, v).ptr;
    s += std::string(" ") + name + " " + std::string(text, end);
  };
  add("target-rmse", r.target.rmse);
  add("target-relmse", r.target.relmse);
  add("time-limit", r.timeLimitSeconds);
  add("min-spp", r.minSpp);
  add("max-spp", r.maxSpp);
  return s;
}

// The sampling settings --resume must find unchanged: the targets and the first pass, not the
// sample counts or the time limit.
std::string resumedSampling(const SamplingRequest& sampling) {
  SamplingRequest targets = sampling;
  targets.maxSpp = 0;
  targets.timeLimitSeconds = 0;
  const std::string s = samplingSettings(targets);
  return s.empty() ? s : s.substr(1);  // without the separating space it opens with
}

// An estimate, or null where there is none (one sample, a regular grid).
nlohmann::json orNull(const std::optional<double>& v) {
  return v ? nlohmann::json(*v) : nlohmann::json();
}

// Reads the attributes of one header, each refused by name when it is there but is not what
// Glint writes.
class AttributeReader {
 public:
  AttributeReader(const std::string& path, const Imf::Header& header)
      : path_(path), header_(header) {}

  [[noreturn]] void refuse(const char* key, const std::string& problem) const {
    throw UsageError(path_ + ": " + key + " " + problem);
  }

  template <typename Attribute>
  const Attribute* find(const char* key, const char* type) const {
    const auto at = header_.find(key);
    if (at == header_.end()) return nullptr;
    const auto* typed = dynamic_cast<const Attribute*>(&at.attribute());
    if (!typed)
      refuse(key, std::string("is of type ") + at.attribute().typeName() + ", not " + type);
    return typed;
  }

  std::optional<std::string> text(const char* key) const {
    const auto* a = find<Imf::StringAttribute>(key, "string");
    return a ? std::optional<std::string>(a->value()) : std::nullopt;
  }

  // An int from `least` to `most`.
  std::optional<int> number(const char* key, int least, int most) const {
    const auto* a = find<Imf::IntAttribute>(key, "int");
    if (!a) return std::nullopt;
    if (a->value() < least || a->value() > most)
      refuse(key, "is " + std::to_string(a->value()) + ", not from " + std::to_string(least) +
                      " to " + std::to_string(most));
    return a->value();
  }

  // A float of 0 or more (a count, a time, an error: an estimate past float's range reads as
  // infinite, which Glint may write).
  std::optional<float> amount(const char* key) const {
    const auto* a = find<Imf::FloatAttribute>(key, "float");
    if (!a) return std::nullopt;
    if (!(a->value() >= 0)) refuse(key, "is " + std::to_string(a->value()) + ", not 0 or more");
    return a->value();
  }

  // A 64-bit hash as Glint writes it: 16 lowercase hex digits.
  std::optional<uint64_t> hash(const char* key) const {
    const std::optional<std::string> s = text(key);
    if (!s) return std::nullopt;
    uint64_t v = 0;
    const auto [end, error] = std::from_chars(s->data(), s->data() + s->size(), v, 16);
    if (s->size() != 16 || error != std::errc() || end != s->data() + s->size() ||
        hexDigits(v) != *s)
      refuse(key, "is " + inQuotes(excerpt(*s)) + ", not 16 lowercase hex digits");
    return v;
  }

  std::optional<Mat4> matrix(const char* key) const {
    const auto* a = find<Imf::M44fAttribute>(key, "m44f");
    if (!a) return std::nullopt;
    // Imath's row-vector convention: transposed from Glint's (film/exr_output.h).
    Mat4 m;
    for (int r = 0; r < 4; ++r)
      for (int c = 0; c < 4; ++c) m(r, c) = a->value()[c][r];
    return m;
  }

 private:
  const std::string& path_;
  const Imf::Header& header_;
};

// A whole decimal number of `text` (no sign, no spaces, no leading zeros), or none.
template <typename Int>
std::optional<Int> wholeNumber(const std::string& text) {
  Int v = 0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), v);
  if (error != std::errc() || end != text.data() + text.size() || std::to_string(v) != text)
    return std::nullopt;
  return v;
}

std::optional<PixelWindow> cropOf(const AttributeReader& read, const char* key) {
  const std::optional<std::string> s = read.text(key);
  if (!s) return std::nullopt;
  std::vector<int> v;
  size_t from = 0;
  while (v.size() < 4 && from <= s->size()) {
    const size_t space = std::min(s->find(' ', from), s->size());
    const std::optional<int> n = wholeNumber<int>(s->substr(from, space - from));
    if (!n) break;
    v.push_back(*n);
    from = space + 1;
  }
  if (v.size() != 4 || from != s->size() + 1 || v[0] >= v[1] || v[2] >= v[3])
    read.refuse(key, "is " + inQuotes(excerpt(*s)) +
                         ", not a window \"X0 X1 Y0 Y1\" of whole numbers with X0 < X1 and "
                         "Y0 < Y1");
  return PixelWindow{v[0], v[1], v[2], v[3]};
}

bool samePasses(const std::vector<PassRecord>& a, const std::vector<PassRecord>& b) {
  if (a.size() != b.size()) return false;
  for (size_t i = 0; i < a.size(); ++i)
    if (a[i].spp != b[i].spp || a[i].meanSpp != b[i].meanSpp || a[i].seconds != b[i].seconds ||
        a[i].estimated.rmse != b[i].estimated.rmse ||
        a[i].estimated.relmse != b[i].estimated.relmse || a[i].pixelsSampled != b[i].pixelsSampled)
      return false;
  return true;
}

bool sameWindow(const std::optional<PixelWindow>& a, const std::optional<PixelWindow>& b) {
  if (!a || !b) return !a && !b;
  return a->x0 == b->x0 && a->x1 == b->x1 && a->y0 == b->y0 && a->y1 == b->y1;
}

}  // namespace

bool FrameRecord::operator==(const FrameRecord& o) const {
  const bool passesEqual =
      passes && o.passes ? samePasses(*passes, *o.passes) : !passes && !o.passes;
  return version == o.version && scene == o.scene && sceneHash == o.sceneHash &&
         settingsHash == o.settingsHash && integrator == o.integrator && sampler == o.sampler &&
         passesEqual && resumeHash == o.resumeHash && resumeSampling == o.resumeSampling &&
         accel == o.accel && seed == o.seed && sameWindow(crop, o.crop) &&
         commandLine == o.commandLine && colorspace == o.colorspace && spp == o.spp &&
         maxSpp == o.maxSpp && timeLimitSeconds == o.timeLimitSeconds && maxDepth == o.maxDepth &&
         partial == o.partial && minPixelSpp == o.minPixelSpp && maxPixelSpp == o.maxPixelSpp &&
         frame == o.frame && renderSeconds == o.renderSeconds && rays == o.rays &&
         estimatedRmse == o.estimatedRmse && estimatedRelmse == o.estimatedRelmse &&
         worldToCamera == o.worldToCamera && worldToNdc == o.worldToNdc &&
         pixelAspectRatio == o.pixelAspectRatio && clampedValues == o.clampedValues &&
         mergedCrops == o.mergedCrops && resumeChecksum == o.resumeChecksum &&
         frameWidth == o.frameWidth && frameHeight == o.frameHeight && holdsState == o.holdsState;
}

uint64_t settingsHash(const Scene& scene, int spp, const std::string& accel,
                      const std::string& extras) {
  const RenderSettings& r = scene.render;
  // An animated scene's frames share its file but not its pixels.
  const std::string frame =
      scene.animation ? " frame " + std::to_string(scene.animation->frame) : "";
  return hashKey(scene.sourceHash, uint64_t(r.width), uint64_t(r.height), uint64_t(spp), r.seed,
                 uint64_t(r.sampler), uint64_t(r.maxDepth), uint64_t(r.transparentBackground),
                 hashBytes(accel), hashBytes(extras + frame));
}

uint64_t resumeHash(const Scene& scene, const FrameSettings& s, const PassPlan& plan,
                    uint64_t sampleRevision) {
  return hashKey(settingsHash(scene, 0, s.accel, s.integrator + " " + resumedSampling(s.sampling)),
                 uint64_t(plan.sampler), uint64_t(plan.progressive() ? 0 : plan.maxSpp),
                 sampleRevision);
}

std::string passesJson(const std::vector<PassRecord>& passes) {
  nlohmann::json list = nlohmann::json::array();
  for (const PassRecord& p : passes)
    list.push_back({{"spp", p.spp},
                    {"mean_spp", p.meanSpp},
                    {"seconds", p.seconds},
                    {"estimated_rmse", orNull(p.estimated.rmse)},
                    {"estimated_relmse", orNull(p.estimated.relmse)},
                    {"pixels_sampled", p.pixelsSampled}});
  return list.dump();
}

std::vector<PassRecord> parsePasses(const std::string& path, const std::string& key,
                                    const std::string& json) {
  checkJsonTreeFits(json, 0, 0, key + " of " + path);
  nlohmann::json list;
  try {
    list = nlohmann::json::parse(json);
  } catch (const nlohmann::json::parse_error& e) {
    throw UsageError(path + ": its " + key + " is not JSON (at byte " + std::to_string(e.byte) +
                     ")");
  } catch (const nlohmann::json::exception& e) {
    // A number past a double's range (1e999) is no parse error to nlohmann but out_of_range.
    throw UsageError(path + ": its " + key + " holds a value Glint cannot read (" +
                     excerpt(e.what()) + ")");
  }
  return parsePasses(path, key, list);
}

std::vector<PassRecord> parsePasses(const std::string& path, const std::string& key,
                                    const nlohmann::json& list) {
  if (!list.is_array()) throw UsageError(path + ": its " + key + " is not a list of passes");
  constexpr double kLargest = std::numeric_limits<double>::max();
  std::vector<PassRecord> passes;
  for (size_t i = 0; i < list.size(); ++i) {
    const nlohmann::json& pass = list[i];
    const std::string where = path + ": " + key + "[" + std::to_string(i) + "]";
    if (!pass.is_object()) throw UsageError(where + " is not an object");
    // A number from `least` to `most`; none for an estimate that is null.
    const auto number = [&](const char* field, double least, double most, const char* range,
                            bool whole) -> std::optional<double> {
      if (!pass.contains(field)) throw UsageError(where + " has no \"" + field + "\"");
      const nlohmann::json& v = pass[field];
      if (v.is_null() && std::string(field).rfind("estimated_", 0) == 0) return std::nullopt;
      if (!v.is_number()) throw UsageError(where + "." + field + " is not a number");
      const double x = v.get<double>();
      if (!(x >= least && x <= most))
        throw UsageError(where + "." + field + " is " + v.dump() + ", not " + range);
      if (whole && x != std::floor(x))
        throw UsageError(where + "." + field + " is not a whole number");
      return x;
    };
    PassRecord p{};
    p.spp = int(*number("spp", 1, double(kMaxSampleSet), "a sample count from 1 to 2^28", true));
    p.seconds = *number("seconds", 0, kLargest, "a time of 0 seconds or more", false);
    p.estimated.rmse = number("estimated_rmse", 0, kLargest, "an error of 0 or more", false);
    p.estimated.relmse = number("estimated_relmse", 0, kLargest, "an error of 0 or more", false);
    p.meanSpp = *number("mean_spp", 0, double(kMaxSampleSet), "a mean from 0 to 2^28", false);
    p.pixelsSampled =
        int64_t(*number("pixels_sampled", 0, 0x1p62, "a count of pixels from 0 to 2^62", true));
    passes.push_back(p);
  }
  return passes;
}

namespace {

// The part of a frame's record that the scene, the settings and the plan fix before any pass:
// what a resume compares.
FrameRecord settingsRecord(const Scene& scene, const FrameSettings& s, const PassPlan& plan) {
  FrameRecord r;
  r.sceneHash = hexDigits(scene.sourceHash);
  r.frameWidth = scene.render.width;
  r.frameHeight = scene.render.height;
  r.seed = scene.render.seed;
  r.sampler = plan.sampler;
  r.maxDepth = scene.render.maxDepth;
  r.accel = s.accel;
  r.integrator = s.integrator;
  r.resumeSampling = resumedSampling(s.sampling);
  r.spp = scene.render.spp;
  return r;
}

}  // namespace

FrameRecord frameRecord(const Scene& scene, const FrameSettings& s, const PassPlan& plan,
                        const RenderResult& result, bool partial) {
  const RenderStats& st = result.stats;
  const PixelWindow& w = result.film.window();
  const Camera camera(scene.cameraDesc, scene.render.width, scene.render.height);
  FrameRecord r = settingsRecord(scene, s, plan);
  r.version = GLINT_VERSION;
  r.scene = scene.sourcePath;
  r.settingsHash = hexDigits(settingsHash(
      scene, scene.render.spp, s.accel,
      s.aovs + (s.half ? " half" : "") + (s.integrator == "production" ? "" : " " + s.integrator) +
          samplingSettings(s.sampling)));
  r.passes = st.passes;
  r.resumeHash = resumeHash(scene, s, plan);
  r.crop = w;
  r.commandLine = s.commandLine;
  // The OCIO name of the rendering space in the bundled config.
  r.colorspace = kRenderingColorspace;
  r.partial = partial;
  r.minPixelSpp = st.minPixelSpp;
  r.maxPixelSpp = st.maxPixelSpp;
  if (plan.adaptive() || plan.timeLimitSeconds > 0) r.maxSpp = plan.maxSpp;
  if (plan.timeLimitSeconds > 0) r.timeLimitSeconds = static_cast<float>(plan.timeLimitSeconds);
  if (scene.animation) r.frame = scene.animation->frame;
  r.renderSeconds = static_cast<float>(st.seconds);
  r.rays = static_cast<float>(st.rays.total());
  if (st.estimated.rmse) {
    r.estimatedRmse = static_cast<float>(*st.estimated.rmse);
    r.estimatedRelmse = static_cast<float>(*st.estimated.relmse);
  }
  // The camera works in render space (world − worldOrigin); compositors want world space.
  const Vec3d toRender = Vec3d{} - scene.worldOrigin;
  r.worldToCamera = afterTranslation(camera.worldToCamera(), toRender);
  r.worldToNdc = afterTranslation(camera.worldToNdc(), toRender);
  // OpenEXR refuses a header whose ratio is outside [1e-6, 1e6]: a window a million times wider
  // than the image's aspect is written at the bound rather than lose the frame.
  r.pixelAspectRatio = float(std::clamp(camera.pixelAspectRatio(), 1e-6, 1e6));
  return r;
}

void writeFrameRecord(const FrameRecord& r, ExrMetadata& m) {
  const auto text = [&](const char* key, const std::optional<std::string>& v) {
    if (v) m.strings.emplace_back(key, *v);
  };
  const auto number = [&](const char* key, const std::optional<int>& v) {
    if (v) m.ints.emplace_back(key, *v);
  };
  const auto amount = [&](const char* key, const std::optional<float>& v) {
    if (v) m.floats.emplace_back(key, *v);
  };
  const auto hash = [&](const char* key, const std::optional<uint64_t>& v) {
    if (v) m.strings.emplace_back(key, hexDigits(*v));
  };
  if (r.version) text("Software", "Glint " + *r.version);
  text("glint:version", r.version);
  text("glint:scene", r.scene);
  text("glint:scene_hash", r.sceneHash);
  text("glint:settings_hash", r.settingsHash);
  text("glint:integrator", r.integrator);
  if (r.sampler) text("glint:sampler", std::string(samplerName(*r.sampler)));
  if (r.passes) text("glint:passes", passesJson(*r.passes));
  hash("glint:resume_hash", r.resumeHash);
  text("glint:resume_sampling", r.resumeSampling);
  text("glint:accel", r.accel);
  if (r.seed) text("glint:seed", std::to_string(*r.seed));
  if (r.crop)
    text("glint:crop", std::to_string(r.crop->x0) + " " + std::to_string(r.crop->x1) + " " +
                           std::to_string(r.crop->y0) + " " + std::to_string(r.crop->y1));
  text("glint:commandline", r.commandLine);
  text("glint:colorspace", r.colorspace);
  number("glint:spp", r.spp);
  number("glint:max_spp", r.maxSpp);
  amount("glint:time_limit_seconds", r.timeLimitSeconds);
  number("glint:max_depth", r.maxDepth);
  if (r.partial) number("glint:partial", *r.partial ? 1 : 0);
  number("glint:min_pixel_spp", r.minPixelSpp);
  number("glint:max_pixel_spp", r.maxPixelSpp);
  number("glint:frame", r.frame);
  amount("glint:render_seconds", r.renderSeconds);
  amount("glint:rays", r.rays);
  amount("glint:estimated_rmse", r.estimatedRmse);
  amount("glint:estimated_relmse", r.estimatedRelmse);
  if (r.worldToCamera) m.matrices.emplace_back("worldToCamera", *r.worldToCamera);
  if (r.worldToNdc) m.matrices.emplace_back("worldToNDC", *r.worldToNdc);
  if (r.pixelAspectRatio) m.pixelAspectRatio = *r.pixelAspectRatio;
}

void writeResumeState(Film& film, ExrMetadata& metadata, std::span<const PixelEstimate> estimates,
                      const PassPosition& position, const FrameRecord& record) {
  addResumeState(film, metadata, estimates, position,
                 record.resumeHash ? hexDigits(*record.resumeHash) : std::string());
}

FrameRecord readFrameRecord(const std::string& path) {
  const auto file = openExr(path);
  const Imf::Header& header = file->header(0);
  const AttributeReader read(path, header);
  constexpr int kMostInt = std::numeric_limits<int>::max();
  constexpr int kLeastInt = std::numeric_limits<int>::min();
  FrameRecord r;
  r.version = read.text("glint:version");
  r.scene = read.text("glint:scene");
  r.sceneHash = read.text("glint:scene_hash");
  r.settingsHash = read.text("glint:settings_hash");
  r.integrator = read.text("glint:integrator");
  if (r.integrator && *r.integrator != "production" && *r.integrator != "reference")
    read.refuse("glint:integrator",
                "is " + inQuotes(excerpt(*r.integrator)) + ", not production or reference");
  if (const std::optional<std::string> name = read.text("glint:sampler")) {
    SamplerKind kind;
    if (!parseSamplerKind(*name, kind))
      read.refuse("glint:sampler",
                  "is " + inQuotes(excerpt(*name)) + ", not regular, random, stratified or sobol");
    r.sampler = kind;
  }
  if (const std::optional<std::string> list = read.text("glint:passes"))
    r.passes = parsePasses(path, "glint:passes", *list);
  r.resumeHash = read.hash("glint:resume_hash");
  r.resumeSampling = read.text("glint:resume_sampling");
  r.accel = read.text("glint:accel");
  if (const std::optional<std::string> seed = read.text("glint:seed")) {
    r.seed = wholeNumber<uint64_t>(*seed);
    if (!r.seed)
      read.refuse("glint:seed",
                  "is " + inQuotes(excerpt(*seed)) + ", not a whole number from 0 to 2^64 - 1");
  }
  r.crop = cropOf(read, "glint:crop");
  r.commandLine = read.text("glint:commandline");
  r.colorspace = read.text("glint:colorspace");
  r.spp = read.number("glint:spp", 1, kMostInt);
  r.maxSpp = read.number("glint:max_spp", 1, kMostInt);
  r.timeLimitSeconds = read.amount("glint:time_limit_seconds");
  r.maxDepth = read.number("glint:max_depth", 0, kMostInt);
  if (const std::optional<int> partial = read.number("glint:partial", 0, 1)) r.partial = *partial;
  r.minPixelSpp = read.number("glint:min_pixel_spp", 0, kMostInt);
  r.maxPixelSpp = read.number("glint:max_pixel_spp", 0, kMostInt);
  r.frame = read.number("glint:frame", kLeastInt, kMostInt);
  r.renderSeconds = read.amount("glint:render_seconds");
  r.rays = read.amount("glint:rays");
  r.estimatedRmse = read.amount("glint:estimated_rmse");
  r.estimatedRelmse = read.amount("glint:estimated_relmse");
  r.worldToCamera = read.matrix("worldToCamera");
  r.worldToNdc = read.matrix("worldToNDC");
  r.pixelAspectRatio = read.amount("pixelAspectRatio");
  r.clampedValues = read.number("glint:clamped_values", 0, kMostInt);
  r.mergedCrops = read.number("glint:merged_crops", 1, kMostInt);
  r.resumeChecksum = read.hash(kResumeChecksumKey);
  // The state's position is read with its channels (readResumeState); of another type it is
  // refused here, by name, with the rest of the record.
  read.number(kResumeFinishedEndKey, kLeastInt, kMostInt);
  read.number(kResumeCutEndKey, kLeastInt, kMostInt);
  const ExrWindow w = exrWindow(path, header);
  r.frameWidth = w.fullWidth;
  r.frameHeight = w.fullHeight;
  r.holdsState = header.channels().findChannel(std::string(kResumeLayer) + ".00") != nullptr;
  return r;
}

std::string resumeDifferences(const FrameRecord& frame, const FrameRecord& render,
                              bool sppLaysOutSets) {
  std::string out;
  const auto differs = [&](const char* what, const std::optional<std::string>& theirs,
                           const std::optional<std::string>& ours) {
    if (!theirs || *theirs == ours.value_or("")) return;
    out += (out.empty() ? "" : "; ") + std::string(what) + ": the frame's " +
           (theirs->empty() ? "none" : *theirs) + ", this render's " +
           (ours.value_or("").empty() ? "none" : *ours);
  };
  const auto number = [](const auto& v) -> std::optional<std::string> {
    return v ? std::optional<std::string>(std::to_string(*v)) : std::nullopt;
  };
  const auto sampler = [](const std::optional<SamplerKind>& v) -> std::optional<std::string> {
    return v ? std::optional<std::string>(samplerName(*v)) : std::nullopt;
  };
  if (frame.sceneHash && frame.sceneHash != render.sceneHash)
    out += "the bytes of the scene file or of a file it reads (a mesh, a texture, an image)";
  differs("size", std::to_string(frame.frameWidth) + "x" + std::to_string(frame.frameHeight),
          std::to_string(render.frameWidth) + "x" + std::to_string(render.frameHeight));
  differs("seed", number(frame.seed), number(render.seed));
  differs("sampler", sampler(frame.sampler), sampler(render.sampler));
  differs("max depth", number(frame.maxDepth), number(render.maxDepth));
  differs("backend", frame.accel, render.accel);
  differs("integrator", frame.integrator, render.integrator);
  differs("targets and first pass", frame.resumeSampling, render.resumeSampling);
  if (sppLaysOutSets)
    differs("spp its stratified sets are laid out for", number(frame.spp), number(render.spp));
  return out;
}

ResumedFrame readResumable(const std::string& path, const Scene& scene,
                           const FrameSettings& settings, const PassPlan& plan,
                           const PixelWindow& window) {
  const RenderSettings& r = scene.render;
  const uint64_t expected = resumeHash(scene, settings, plan);
  const FrameRecord frame = readFrameRecord(path);
  // A frame without a state cannot be continued, whatever its settings; one whose state has
  // no checksum was left by an older Glint, whose hash was made otherwise and whose state
  // lacks where its passes stood.
  if (!frame.holdsState)
    throw UsageError(path +
                     " holds no resume state: only a frame Glint wrote with --resumable, or a "
                     "partial, preview or time-limited one, can be resumed");
  if (frame.resumeHash && !frame.resumeChecksum)
    throw UsageError(path +
                     " was left by an older Glint, whose resume state did not keep where its "
                     "passes stood: render it again");
  if (frame.resumeHash && *frame.resumeHash != expected)
    for (uint64_t revision = 1; revision < kSampleRevision; ++revision)
      if (*frame.resumeHash == resumeHash(scene, settings, plan, revision))
        throw UsageError(path +
                         " was left by a Glint that draws or shades samples otherwise "
                         "(sample revision " +
                         std::to_string(revision) + ", this Glint's " +
                         std::to_string(kSampleRevision) + "): render it again");
  if (!frame.resumeHash || *frame.resumeHash != expected) {
    std::string differences;
    if (frame.resumeHash) {
      differences =
          resumeDifferences(frame, settingsRecord(scene, settings, plan), !plan.progressive());
    }
    throw UsageError(path +
                     (!frame.resumeHash ? " has no glint:resume_hash: it was not written by this "
                                          "Glint"
                      : differences.empty()
                          ? " was rendered from another scene, or with other settings or a "
                            "stratified sampler laid out for another spp"
                          : " differs from this render (" + differences + ")") +
                     ": --resume continues a frame with the scene and every setting but --spp / "
                     "--max-spp / --time-limit / --aov variance / --half the same (render with "
                     "--resumable to continue a frame to any spp)" +
                     (frame.sampler == SamplerKind::Stratified && plan.progressive()
                          ? "; a time limit, an error target or --resumable draws from the Sobol "
                            "sequence, which cannot continue the frame's stratified sets: resume "
                            "it without them"
                          : ""));
  }
  ResumedFrame out;
  if (frame.passes) out.passes = *frame.passes;
  const std::string expectedHex = hexDigits(expected);
  out.state = readResumeState(path, window, r.width, r.height, plan.maxSpp, &expectedHex);
  log::info("resuming " + path + " to " + std::to_string(plan.maxSpp) + " spp");
  return out;
}

CropRecord cropRecord(const std::string& path) {
  const FrameRecord r = readFrameRecord(path);
  CropRecord c;
  c.path = path;
  c.settingsHash = r.settingsHash.value_or("");
  c.sceneHash = r.sceneHash.value_or("");
  c.partial = r.partial.value_or(false);
  c.renderSeconds = r.renderSeconds.value_or(0.0f);
  c.rays = r.rays.value_or(0.0f);
  c.clampedValues = r.clampedValues.value_or(0);
  c.estimatedRmse = r.estimatedRmse;
  c.estimatedRelmse = r.estimatedRelmse;
  c.minPixelSpp = r.minPixelSpp;
  c.maxPixelSpp = r.maxPixelSpp;
  return c;
}

}  // namespace glint
