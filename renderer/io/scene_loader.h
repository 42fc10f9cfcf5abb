#pragma once
// Scene files (../shared/SCENE_FORMAT.md, docs/scene-format.md) → an immutable Scene. Every
// user mistake throws SceneError naming file:line, the JSON path and the problem.
#include <optional>
#include <string>

#include "scene/scene.h"

namespace glint {

// A JSON scene's size limit: parsed, a byte of an inline mesh costs about 19 in memory, and a
// scene's own geometry at this size is millions of inline triangles, which belong in mesh files.
inline constexpr size_t kMaxSceneFileBytes = size_t{128} << 20;
// What a JSON scene keeps for each value beside nlohmann-json's tree (core/json_memory.h): its
// line map entry (an unordered_map node with malloc's header and a bucket, 40 bytes) and the
// builder's copies of what it reads (a mesh's numbers as floats, in the scene and in Embree).
// Checked with the tree against the memory budget before parsing (docs/hardening.md).
inline constexpr double kSceneBytesPerValue = 48;
// And for each line: where it starts, for the line of an error (a size_t, in a vector that may
// have grown to twice its size).
inline constexpr double kSceneBytesPerLine = 16;

// `frame`: which frame of an animated scene (default: its first); asking a still scene for one
// is a UsageError (io/animation.h).
Scene loadSceneFile(const std::string& path, std::optional<int> frame = std::nullopt);
// `fileName` is used in messages; relative mesh paths resolve against `baseDir`.
Scene loadSceneText(const std::string& text, const std::string& fileName,
                    const std::string& baseDir, std::optional<int> frame = std::nullopt);

}  // namespace glint
