#pragma once
// Writes a file so that readers see either the complete new file or the previous one: the data
// goes to a temporary file in the same directory, is fsync'ed, then renamed into place.
#include <functional>
#include <string>

namespace glint {

// Throws a UsageError unless finalPath may be written: its directory exists, and nothing is
// there or a regular file that this run did not read (core/input_files.h). Commands call it
// before rendering, so that a long render does not end in a refusal.
void checkOutputPath(const std::string& finalPath);

// Calls write(tmpPath) to produce the data, then publishes it at finalPath. On any failure the
// temporary file is removed, finalPath is left untouched, and a GlintError names the cause.
// Temporary files are named ".glint-tmp-HOST-PID-N-NAME.EXT" within NAME_MAX; those of this
// host's processes that died before cleaning up are removed by the next write in the directory.
void writeFileAtomically(const std::string& finalPath,
                         const std::function<void(const std::string& tmpPath)>& write);

// The same for a text file (JSON figures, CSV); "-" writes to standard output.
void writeTextFileAtomically(const std::string& finalPath, const std::string& text);

}  // namespace glint
