#include "io/mesh_limits.h"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <set>
#include <string>
#include <vector>

#include "core/error.h"
#include "io/ply_header.h"
#include "io/scene_formats.h"

namespace glint {

namespace {

std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

std::string headOf(const std::string& path, size_t bytes) {
  std::ifstream in(path, std::ios::binary);
  std::string head(bytes, '\0');
  in.read(head.data(), static_cast<std::streamsize>(bytes));
  head.resize(static_cast<size_t>(std::max<std::streamsize>(in.gcount(), 0)));
  return head;
}

// Adds the names that follow `keyword` at the start of a line of `file` to `names`, and the
// material libraries its `mtllib` lines name to `libraries` (when given); throws past
// kMaxObjMaterials, naming `file`.
void collectObjNames(const std::string& mesh, const std::filesystem::path& file,
                     const char* keyword, std::set<std::string>& names,
                     std::vector<std::string>* libraries) {
  std::ifstream in(file, std::ios::binary);
  const std::string key = std::string(keyword) + " ";
  for (std::string line; std::getline(in, line);) {
    size_t at = line.find_first_not_of(" \t");
    if (at == std::string::npos) continue;
    const auto rest = [&](size_t length) {
      std::string value = line.substr(std::min(line.size(), at + length));
      while (!value.empty() && std::isspace(static_cast<unsigned char>(value.back())))
        value.pop_back();
      return value.substr(std::min(value.size(), value.find_first_not_of(" \t")));
    };
    if (line.compare(at, key.size(), key) == 0) {
      names.insert(rest(key.size()));
      if (names.size() > kMaxObjMaterials)
        throw GlintError("mesh " + mesh +
                         (file == mesh ? "" : ": its material library " + file.string()) +
                         " names more than " + std::to_string(kMaxObjMaterials) + " materials (\"" +
                         keyword + "\" lines with distinct names); Glint reads at most " +
                         std::to_string(kMaxObjMaterials) + " from one OBJ file");
    } else if (libraries && line.compare(at, 7, "mtllib ") == 0) {
      libraries->push_back(rest(7));
    }
  }
}

}  // namespace

void checkObjMaterialCount(const std::string& path) {
  std::set<std::string> used, defined;
  std::vector<std::string> libraries;
  collectObjNames(path, path, "usemtl", used, &libraries);
  const std::filesystem::path dir = std::filesystem::path(path).parent_path();
  for (const std::string& library : libraries) {
    std::error_code ec;
    const std::filesystem::path file = dir / library;
    // Assimp opens only regular files a mesh names (io/mesh_io.cpp); so does this count.
    if (std::filesystem::is_regular_file(file, ec))
      collectObjNames(path, file, "newmtl", defined, nullptr);
  }
}

bool isMeshExtension(const std::string& extension) {
  const SceneFormat* f = findSceneFormat("x" + extension);
  return f && f->kind != SceneFileKind::GlintScene;
}

std::string meshFormatList() { return sceneFormatList(true); }

void checkPlyCounts(const std::string& path, const std::string& head, uint64_t fileSize) {
  if (head.size() < 3 || lower(head.substr(0, 3)) != "ply") return;  // the reader refuses it
  checkPlyElementsFitInTheFile(path, parsePlyHeader(path, head, fileSize), fileSize);
}

void checkMeshFileBeforeImport(const std::string& path) {
  const std::filesystem::path p(path);
  if (!isMeshExtension(p.extension().string()))
    throw GlintError("mesh " + path + ": Glint reads " + meshFormatList() + "; \"" +
                     excerpt(p.extension().string()) + "\" is not one of them");
  std::error_code ec;
  const uint64_t size = std::filesystem::file_size(p, ec);
  if (ec) throw GlintError("cannot read mesh " + path + ": " + ec.message());
  if (size > kMaxMeshFileBytes)
    throw GlintError("mesh " + path + " is " + std::to_string(size) +
                     " bytes; mesh files may have at most " + std::to_string(kMaxMeshFileBytes) +
                     " (1 GiB)");
  if (lower(p.extension().string()) == ".obj") checkObjMaterialCount(path);
  if (lower(p.extension().string()) == ".ply")
    checkPlyCounts(path, headOf(path, kMaxPlyHeaderBytes), size);
}

}  // namespace glint
