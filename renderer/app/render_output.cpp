#include "app/render_output.h"

#include <filesystem>

#include "core/error.h"
#include "core/word_list.h"

namespace glint {

ImageFormat renderOutputFormat(const std::string& path, const std::vector<std::string>& exrOnly) {
  const ImageFormat format = imageOutputFormat("-o", path, ImageOutput::ExrOrDisplay);
  if (!isDisplayFormat(format) || exrOnly.empty()) return format;
  const std::string flags = wordList(exrOnly);
  const std::string exr = std::filesystem::path(path).replace_extension(".exr").string();
  throw UsageError("-o " + excerpt(path) + " writes a display-referred " + formatName(format) +
                   ", which cannot carry what " + flags + (exrOnly.size() == 1 ? " asks" : " ask") +
                   " for (only the EXR frame does): write -o " + excerpt(exr) + " --display " +
                   excerpt(path) + " to have both");
}

}  // namespace glint
