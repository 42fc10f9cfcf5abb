#pragma once
// The files this run has read (its scene, meshes, images): no output may replace one, so
// `glint render scene.json -o scene.json` is refused instead of destroying the scene.
#include <string>

namespace glint {

// Remembers `path`'s file (by device and inode, so other names of it count too). Paths that
// cannot be stat'ed are ignored: reading them fails with its own error.
void noteInputFile(const std::string& path);

// Whether `path` names a file noted above.
bool isInputFile(const std::string& path);

}  // namespace glint
