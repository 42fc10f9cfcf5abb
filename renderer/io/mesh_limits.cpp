#include "io/mesh_limits.h"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <string>

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

}  // namespace

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
  if (lower(p.extension().string()) == ".ply")
    checkPlyCounts(path, headOf(path, kMaxPlyHeaderBytes), size);
}

}  // namespace glint
