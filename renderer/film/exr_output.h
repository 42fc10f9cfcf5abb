#pragma once
// Writes the film as an OpenEXR file through OpenImageIO: RGBA (float or half; alpha =
// coverage) and AOV planes, layered in one part or one part each, the chosen compression, the
// data window = the crop inside the full display window, and Glint's metadata (docs/output.md)
// with the film's own attributes (those its planes need, such as Cryptomatte's manifests).
#include <OpenEXR/ImfIO.h>

#include <array>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/transform.h"
#include "film/film.h"

namespace glint {

struct ExrMetadata {
  std::vector<std::pair<std::string, std::string>> strings;  // e.g. {"glint:sampler", "..."}
  std::vector<std::pair<std::string, int>> ints;
  std::vector<std::pair<std::string, float>> floats;
  // Written as OpenEXR M44f (Imath's row-vector convention, so transposed from Glint's).
  std::vector<std::pair<std::string, Mat4>> matrices;
  float pixelAspectRatio = 1;  // OpenEXR's standard attribute: a pixel's width over its height
};

struct ExrOptions {
  bool half = false;                // half-float beauty instead of float
  std::string compression = "zip";  // none, rle, zips, zip, piz, pxr24, b44, b44a, dwaa, dwab
  bool multipart = false;  // one part per AOV instead of layered channels in one part (UINT
                           // planes, Glint's own state, stay in part 0 with the beauty)
};

// The threads OpenEXR compresses and decompresses line blocks on, for the whole process (its
// own pool; 0: the calling thread alone). Blocks are written in order, so the bytes are the
// same for any count.
void setExrThreads(int threads);

// The compression names OpenEXR (through OpenImageIO) accepts.
const std::vector<std::string>& exrCompressions();

// Cryptomatte IDs are a hash's bits stored as floats: pxr24 (24-bit floats) and dwaa and dwab
// (lossy for channels named R, G, B) change them, and no matte matches its name any more.
// Throws UsageError, before any work, where a frame with Cryptomatte layers (`hasIds`) would be
// written in one part with such a compression; a multipart frame writes the Cryptomatte parts
// with zip instead (writeExr).
void checkIdsSurviveCompression(bool hasIds, const ExrOptions& options);

// Writes the film; a part holding Cryptomatte layers (the planes the film's cryptomatte/KEY/name
// attributes name) is compressed with zip where options.compression would change its IDs
// (checkIdsSurviveCompression), and a single-part frame with them is refused.
// Returns how many values lay beyond their channel type's finite range (±65504 for half,
// ±FLT_MAX for float) and were clamped to it; the file records the count as
// glint:clamped_values (saturating at 2^31 − 1). Nothing written is Inf or NaN.
uint64_t writeExr(const std::string& path, const Film& film, ExrMetadata meta,
                  const ExrOptions& options = {});

// Writes an EXR to `tmpPath` through `write`, which makes an OpenEXR output file on the stream
// it is given. The stream is Glint's own, closed and checked after OpenEXR is done with it:
// OpenEXR writes the line-offset table in its destructor and swallows a failure there (a full
// disk), which would publish a truncated frame. Throws GlintError naming `path`.
void writeExrStream(const std::string& path, const std::string& tmpPath,
                    const std::function<void(Imf::OStream&)>& write);

// Reads an EXR's channels (full data window) as float, RGBA first; used by tests, `glint
// compare`, `convert` and `converge`, and with every part by the Python module's read_frame
// (a --multipart frame's AOVs are parts of their own; a part over other pixels than the first
// is left out, and named in partsLeftOut). Throws UsageError naming the file when it cannot be
// read, its data window would not fit in memory (film/image_limits.h), or (every part) a part
// repeats a channel name once qualified by its part's.
struct Image {
  int width = 0, height = 0, channels = 0;
  std::vector<std::string> channelNames;  // as in the file; empty for images made in memory
  int x = 0, y = 0, fullWidth = 0, fullHeight = 0;
  std::vector<float> pixels;
  std::string colorspace;  // its glint:colorspace, empty when it has none (a foreign EXR)
  // OpenEXR's standard chromaticities, when the file has them: red, green, blue, white (x, y).
  std::optional<std::array<float, 8>> chromaticities;
  std::vector<std::string> partsLeftOut;  // ExrParts::All: each part not read, and why
};
enum class ExrParts { First, All };
Image readImage(const std::string& path, ExrParts parts = ExrParts::First);
// The film's window as an RGBA image (float), as it would read back from its EXR.
Image imageFromFilm(const Film& film);

}  // namespace glint
