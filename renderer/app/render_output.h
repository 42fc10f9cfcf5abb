#pragma once
// What `glint render -o` writes, chosen by its extension (film/image_format.h): the scene-linear
// EXR frame, or a display-referred image through the OCIO view, as --display makes. What only
// the EXR can carry (half floats, parts, AOVs, compression, a resume state, previews and
// partial frames, which are marked partial and resumable) is refused with a display -o before
// anything is loaded or rendered.
#include <string>
#include <vector>

#include "film/image_format.h"

namespace glint {

// The format of -o `path`. Throws UsageError when its extension is not one -o writes, or when
// it names a display image and `exrOnly` (the EXR-only flags given, e.g. "--half") is not
// empty, naming them and the way to get both.
ImageFormat renderOutputFormat(const std::string& path, const std::vector<std::string>& exrOnly);

}  // namespace glint
