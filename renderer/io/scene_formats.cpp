#include "io/scene_formats.h"

#include <vector>

#include "core/error.h"
#include "core/file_names.h"
#include "core/word_list.h"

namespace glint {

const SceneFormat* findSceneFormat(const std::string& path) {
  const std::string ext = lowerExtension(path);
  for (const SceneFormat& f : kSceneFormats)
    if (ext == f.extension) return &f;
  return nullptr;
}

SceneFileKind sceneFileKind(const std::string& path) {
  if (const SceneFormat* f = findSceneFormat(path)) return f->kind;
  const std::string ext = lowerExtension(path);
  if (ext.empty()) return SceneFileKind::GlintScene;
  throw UsageError(path + ": Glint does not read " + excerpt(ext) + " files; it reads " +
                   sceneFormatList());
}

std::string sceneFormatList(bool meshesOnly) {
  std::vector<std::string> entries;
  std::string lastName;
  for (const SceneFormat& f : kSceneFormats) {
    if (meshesOnly && f.kind == SceneFileKind::GlintScene) continue;
    if (f.name == lastName) {
      entries.back().insert(entries.back().size() - 1, std::string(", ") + f.extension);
      continue;
    }
    lastName = f.name;
    entries.push_back(std::string(f.name) + " (" + f.extension + ")");
  }
  return wordList(entries);
}

}  // namespace glint
