#pragma once
// What Glint's own texture readers (io/own_texture_readers.h) share: the module interface's
// error text, the file opened for reading, and the header they fill.
#include <cstddef>
#include <cstdio>
#include <string>

#include "film/oiio_module_abi.h"

namespace glint::texture_reader {

// `message` into the caller's `error` buffer of `errorSize` bytes, cut to fit.
inline void copyMessage(const char* message, char* error, size_t errorSize) {
  if (errorSize > 0) std::snprintf(error, errorSize, "%s", message);
}

// `path` opened for binary reading, not inherited by a child (e); null, with the message in
// `error`, when it cannot be opened.
inline std::FILE* openFile(const std::string& path, char* error, size_t errorSize) {
  std::FILE* file = std::fopen(path.c_str(), "rbe");
  if (!file) copyMessage("cannot open the file", error, errorSize);
  return file;
}

// Whether reading rows [y0, y1) of the first `channels` channels keeps the module's contract
// (film/oiio_module_abi.h) for an image of `height` rows and `fileChannels` channels, read in
// order from row `nextRow` (negative: in any order); if not, false with the message in `error`.
inline bool rowsInContract(int y0, int y1, int channels, int height, int fileChannels, int nextRow,
                           char* error, size_t errorSize) {
  if (channels >= 1 && channels <= fileChannels && y0 >= 0 && y1 <= height && y0 <= y1 &&
      (nextRow < 0 || y0 == nextRow))
    return true;
  copyMessage("rows or channels out of order or range", error, errorSize);
  return false;
}

// The header a reader gives, as OpenImageIO's reader would: a scanline image (no tiles).
inline void fillInfo(GlintOiioTextureInfo* info, int width, int height, int channels, bool isFloat,
                     int bytesPerChannel, const std::string& colorspace) {
  info->width = width;
  info->height = height;
  info->channels = channels;
  info->isFloat = isFloat ? 1 : 0;
  info->bytesPerChannel = bytesPerChannel;
  std::snprintf(info->colorspace, sizeof info->colorspace, "%s", colorspace.c_str());
  info->tileHeight = 0;
}

}  // namespace glint::texture_reader
