#pragma once
// Writes a file so that readers see either the complete new file or the previous one: the data
// goes to a temporary file in the same directory, is fsync'ed, then renamed into place.
#include <functional>
#include <string>

namespace glint {

// Calls write(tmpPath) to produce the data, then publishes it at finalPath. On any failure the
// temporary file is removed, finalPath is left untouched, and a GlintError names the cause.
void writeFileAtomically(const std::string& finalPath,
                         const std::function<void(const std::string& tmpPath)>& write);

// The same for a text file (JSON figures, CSV).
void writeTextFileAtomically(const std::string& finalPath, const std::string& text);

}  // namespace glint
