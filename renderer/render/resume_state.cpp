#include "render/resume_state.h"

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfIntAttribute.h>
#include <OpenEXR/ImfMultiPartInputFile.h>
#include <OpenEXR/ImfStringAttribute.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdio>

#include "core/error.h"
#include "core/hash.h"
#include "core/sampler.h"
#include "film/exr_input.h"
#include "film/image_limits.h"

namespace glint {

namespace {

constexpr int kDoublesPerHalf = 4;                  // mean ×3, alpha
constexpr int kCountChannel = 2 * kDoublesPerHalf;  // after their words
constexpr int kRaysChannel = kCountChannel + 1;     // 64 bits in two words
constexpr int kChannelsPerHalf = kRaysChannel + 2;
constexpr int kCutChosenChannel = 2 * kChannelsPerHalf;
constexpr int kChannels = kCutChosenChannel + 1;
// A Glint before the rays channels wrote .00 to .17 (its halves without them): a file that has
// those and lacks the next was likely written by it.
constexpr int kChannelsOfOlderGlint = 2 * kCountChannel + 2;
// The most rays a half may have traced: their sum over both halves must fit in 64 bits, and no
// render traces 2^62 rays in one pixel.
constexpr uint64_t kMaxRaysOfHalf = uint64_t{1} << 62;

void splitWords(uint64_t bits, double* out) {
  out[0] = double(bits >> 32);
  out[1] = double(bits & 0xffffffffu);
}

uint64_t joinWords(const uint32_t* in) { return uint64_t{in[0]} << 32 | in[1]; }

std::string channelName(int i) {
  char name[32];
  std::snprintf(name, sizeof name, "%s.%02d", kResumeLayer, i);
  return name;
}

double* doublesOf(HalfEstimate& h, int k) { return k < 3 ? &h.mean[k] : &h.alpha; }

// Every word the state holds, in file order, with the position and the frame's resume hash.
std::string checksumOf(std::span<const PixelEstimate> estimates, const PassPosition& position,
                       const std::string& resumeHash) {
  uint64_t h =
      hashKey(hashBytes(resumeHash), uint64_t(position.finishedEnd), uint64_t(position.cutEnd));
  for (size_t p = 0; p < estimates.size(); ++p) {
    PixelEstimate e = estimates[p];
    for (HalfEstimate& half : e.half) {
      for (int k = 0; k < kDoublesPerHalf; ++k)
        h = hashCombine(h, std::bit_cast<uint64_t>(*doublesOf(half, k)));
      h = hashCombine(h, uint64_t(uint32_t(half.count)));
      h = hashCombine(h, half.rays);
    }
    const auto& chosen = position.cutChosen;
    h = hashCombine(h, p < chosen.size() ? chosen[p] : 0);
  }
  return hexDigits(h);
}

}  // namespace

size_t resumeStateBytesPerPixel() {
  return kChannels * (sizeof(double) + sizeof(uint32_t)) + 4 * sizeof(float);
}

void addResumeState(Film& film, ExrMetadata& metadata, std::span<const PixelEstimate> estimates,
                    const PassPosition& position, const std::string& resumeHash) {
  const std::vector<uint8_t>& chosen = position.cutChosen;
  std::vector<std::string> names;
  for (int i = 0; i < kChannels; ++i) names.push_back(channelName(i));
  const size_t plane = film.addPlane(kResumeLayer, names, true);
  const PixelWindow& w = film.window();
  size_t p = 0;
  for (int y = w.y0; y < w.y1; ++y)
    for (int x = w.x0; x < w.x1; ++x, ++p) {
      PixelEstimate e = estimates[p];
      double v[kChannels];
      for (int h = 0; h < 2; ++h) {
        double* out = v + h * kChannelsPerHalf;
        for (int k = 0; k < kDoublesPerHalf; ++k)
          splitWords(std::bit_cast<uint64_t>(*doublesOf(e.half[h], k)), out + 2 * k);
        out[kCountChannel] = double(e.half[h].count);
        splitWords(e.half[h].rays, out + kRaysChannel);
      }
      v[kCutChosenChannel] = p < chosen.size() ? chosen[p] : 0;
      film.setPlanePixel(plane, x, y, v);
    }
  metadata.ints.emplace_back(kResumeFinishedEndKey, position.finishedEnd);
  metadata.ints.emplace_back(kResumeCutEndKey, position.cutEnd);
  metadata.strings.emplace_back(kResumeChecksumKey, checksumOf(estimates, position, resumeHash));
}

ResumeState readResumeState(const std::string& path, const PixelWindow& window, int fullWidth,
                            int fullHeight, int64_t maxSamples, const std::string* resumeHash) {
  // Not noted as an input file: -o may name the partial itself, which the continued frame
  // replaces atomically once it is complete.
  const auto file = openExr(path);
  const Imf::Header& header = file->header(0);
  const ExrWindow w = exrWindow(path, header);
  if (w.x != window.x0 || w.y != window.y0 || w.width != window.width() ||
      w.height != window.height() || w.fullWidth != fullWidth || w.fullHeight != fullHeight)
    throw UsageError(path + " covers pixels [" + std::to_string(w.x) + "," +
                     std::to_string(w.x + w.width) + ") x [" + std::to_string(w.y) + "," +
                     std::to_string(w.y + w.height) + ") of a " + std::to_string(w.fullWidth) +
                     "x" + std::to_string(w.fullHeight) + " frame: --resume continues the same " +
                     "frame and crop only");
  std::vector<ExrSlice> slices;
  for (int i = 0; i < kChannels; ++i) {
    const Imf::Channel* c = header.channels().findChannel(channelName(i));
    // Bits in UINT channels: a tool that rewrote them as float (oiiotool does) rounded them.
    if (c && c->type != Imf::UINT)
      throw UsageError(path + "'s resume state is altered: its channel " + channelName(i) + " is " +
                       (c->type == Imf::HALF ? "half" : "float") +
                       ", not UINT (a tool that converts its words to float rounds them): "
                       "continue the frame Glint wrote");
    if (!c)
      throw UsageError(
          path + " holds no resume state (" + channelName(i) +
          "): only a frame Glint wrote with --resumable, or a partial, preview "
          "or time-limited one, can be resumed" +
          (i == kChannelsOfOlderGlint ? " (a Glint before the rays channels wrote fewer)"
           : i == kCutChosenChannel
               ? " (a Glint before the passes' position was kept wrote fewer: render it again)"
               : ""));
    slices.push_back({channelName(i), Imf::UINT, sizeof(uint32_t) * size_t(i)});
  }
  ResumeState state;
  PassPosition& position = state.position;
  for (const auto& [key, value] : {std::pair{kResumeFinishedEndKey, &position.finishedEnd},
                                   std::pair{kResumeCutEndKey, &position.cutEnd}}) {
    const auto* a = header.findTypedAttribute<Imf::IntAttribute>(key);
    if (!a)
      throw UsageError(path + " has no " + key +
                       ": a Glint before the passes' position was kept wrote it (render it "
                       "again)");
    *value = a->value();
  }
  // Plausible ends only; whether this render's passes can continue from them is the render's
  // to say (a pixel past --spp is refused below, naming the counts).
  if (position.finishedEnd < 0 || position.finishedEnd > kMaxSampleSet || position.cutEnd < 0 ||
      position.cutEnd > kMaxSampleSet ||
      (position.cutEnd > 0 && position.cutEnd <= position.finishedEnd))
    throw UsageError(path + ": its passes' position (finished to " +
                     std::to_string(position.finishedEnd) + " spp, cut at " +
                     std::to_string(position.cutEnd) + ") is not one a render leaves");
  const size_t pixelBytes = sizeof(uint32_t) * kChannels;
  checkImageFits(path, "data window", w.width, w.height, double(pixelBytes));
  std::vector<uint32_t> words;
  readPixelsInBands(path, *file, 0, slices, pixelBytes, words);
  PixelEstimates& out = state.estimates;
  out.resize(size_t(window.area()));  // every pixel is written below, or the read throws
  if (position.cutEnd > 0) position.cutChosen.resize(out.size());
  for (size_t p = 0; p < out.size(); ++p) {
    const uint32_t* in = words.data() + p * kChannels;
    for (int h = 0; h < 2; ++h) {
      HalfEstimate& half = out[p].half[h];
      const uint32_t* hw = in + h * kChannelsPerHalf;
      for (int k = 0; k < kDoublesPerHalf; ++k)
        *doublesOf(half, k) = std::bit_cast<double>(joinWords(hw + 2 * k));
      const uint32_t count = hw[kCountChannel];
      half.rays = joinWords(hw + kRaysChannel);
      // Every sample traces its camera ray.
      bool valid = count <= uint64_t(maxSamples) && half.alpha >= 0 && half.alpha <= count &&
                   half.rays >= count && half.rays <= kMaxRaysOfHalf &&
                   (count > 0 || half.rays == 0);
      for (int k = 0; k < kDoublesPerHalf; ++k) valid = valid && std::isfinite(*doublesOf(half, k));
      if (!valid)
        throw UsageError(
            path + ": the resume state of pixel (" +
            std::to_string(window.x0 + int(p % size_t(window.width()))) + ", " +
            std::to_string(window.y0 + int(p / size_t(window.width()))) +
            ") is not one a render leaves (a non-finite value, a negative coverage, fewer " +
            "rays than samples or more than 2^62, or more samples than the --spp asked)");
      half.count = static_cast<int32_t>(count);
    }
    if (out[p].samples() > maxSamples)
      throw UsageError(path + ": a pixel's resume state holds " + std::to_string(out[p].samples()) +
                       " samples, more than the " + std::to_string(maxSamples) + " asked");
    if (halfSampleCount(out[p].samples(), 0) != out[p].half[0].count)
      throw UsageError(path +
                       ": the halves of a pixel's resume state do not split its samples "
                       "as a render does");
    // A pass brings a pixel up to its end at most, and a pixel past the last finished pass is
    // one the cut pass had chosen (a continuation's earlier frame may have left it between the
    // two: --spp 24, continued to 64 and cut in the pass to 32).
    const uint32_t chosen = in[kCutChosenChannel];
    const int64_t n = out[p].samples();
    if (chosen > 1 || (chosen == 1 && position.cutEnd == 0) ||
        (n > position.finishedEnd && !(chosen == 1 && n <= position.cutEnd)))
      throw UsageError(path + ": pixel (" +
                       std::to_string(window.x0 + int(p % size_t(window.width()))) + ", " +
                       std::to_string(window.y0 + int(p / size_t(window.width()))) + ") holds " +
                       std::to_string(n) + " samples, past the passes its frame finished (" +
                       std::to_string(position.finishedEnd) + " spp)");
    if (position.cutEnd > 0) position.cutChosen[p] = static_cast<uint8_t>(chosen);
  }
  if (resumeHash) {
    const auto* stored = header.findTypedAttribute<Imf::StringAttribute>(kResumeChecksumKey);
    if (!stored || stored->value() != checksumOf(state.estimates, position, *resumeHash))
      throw UsageError(path + (stored ? "'s resume state is not the one its render wrote: it was "
                                        "altered (a tool that converts its words to float, an "
                                        "edit) or taken from another frame"
                                      : " has no glint:resume_checksum: it was not written by "
                                        "this Glint"));
  }
  return state;
}

}  // namespace glint
