#pragma once
// The files this run has read (its scene, meshes, images): no output may replace one, so
// `glint render scene.json -o scene.json` is refused instead of destroying the scene.
#include <cstddef>
#include <string>

namespace glint {

// Remembers `path`'s file (by device and inode, so other names of it count too). Paths that
// cannot be stat'ed are ignored: reading them fails with its own error.
void noteInputFile(const std::string& path);

// Whether `path` names a file noted above.
bool isInputFile(const std::string& path);

// Reads a whole input file, notes it (above), and refuses more than `maxBytes`: a device such
// as /dev/zero, or a file that is not what it claims, would otherwise be read until memory runs
// out. Too large, or not to be opened (no permission): a UsageError naming the file (and the
// limit and `what` it was meant to be); a failure part-way through reading: a GlintError.
// Pipes and FIFOs are read like files (a scene from `<(generator)`).
std::string readInputFile(const std::string& path, size_t maxBytes, const std::string& what);

}  // namespace glint
