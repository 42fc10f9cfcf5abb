#pragma once
// Scene files (../shared/SCENE_FORMAT.md, docs/scene-format.md) → an immutable Scene. Every
// user mistake throws SceneError naming file:line, the JSON path and the problem.
#include <optional>
#include <string>

#include "scene/scene.h"

namespace glint {

// A JSON scene's size limit: parsed, each byte costs about 10 in memory, and a scene's own
// geometry at this size is millions of inline triangles, which belong in mesh files.
inline constexpr size_t kMaxSceneFileBytes = size_t{128} << 20;
// What parsing a JSON scene takes per byte of its text (the JSON tree, its line map, the
// builder's copies; docs/hardening.md): checked against the memory budget before parsing, since
// nlohmann-json cannot unwind from a failed allocation (its destructor allocates).
inline constexpr double kSceneBytesPerTextByte = 11;

// `frame`: which frame of an animated scene (default: its first); asking a still scene for one
// is a UsageError (io/animation.h).
Scene loadSceneFile(const std::string& path, std::optional<int> frame = std::nullopt);
// `fileName` is used in messages; relative mesh paths resolve against `baseDir`.
Scene loadSceneText(const std::string& text, const std::string& fileName,
                    const std::string& baseDir, std::optional<int> frame = std::nullopt);

}  // namespace glint
