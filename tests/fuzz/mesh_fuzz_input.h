#pragma once
// The input form and the oracle of glint_fuzz_mesh, shared with its regression test
// (tests/io/input_fuzz_regression_test.cpp). An input is a format byte, a mesh file and
// optionally kPartSeparator and a second file the mesh may name: byte % 11 picks m.ply, m.obj
// (+ m.mtl), m.gltf (+ m.bin), m.glb (+ m.bin), or a file of Assimp's other formats Glint reads
// (io/scene_formats.h): m.dae, m.fbx, m.3ds, m.stl, m.ac, m.ms3d or m.x3d (+ m.bin, which none of
// them names, but a mutated one may).
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <string_view>

#include "core/error.h"
#include "io/mesh_io.h"

namespace glint::fuzz {

// In mesh.dict, so mutations keep it.
inline constexpr std::string_view kPartSeparator = "\n@@glint-part@@\n";

// Writes `input` into `dir` (removing an earlier input's second file) and returns the mesh's
// path; an empty input has none.
inline std::filesystem::path writeMeshInput(const std::filesystem::path& dir,
                                            std::string_view input) {
  namespace fs = std::filesystem;
  struct Format {
    const char *mesh, *part;
  };
  static constexpr Format kFormats[] = {
      {"m.ply", "m.bin"}, {"m.obj", "m.mtl"},  {"m.gltf", "m.bin"}, {"m.glb", "m.bin"},
      {"m.dae", "m.bin"}, {"m.fbx", "m.bin"},  {"m.3ds", "m.bin"},  {"m.stl", "m.bin"},
      {"m.ac", "m.bin"},  {"m.ms3d", "m.bin"}, {"m.x3d", "m.bin"}};
  if (input.empty()) return {};
  const Format& format = kFormats[static_cast<unsigned char>(input[0]) % std::size(kFormats)];
  const std::string_view rest = input.substr(1);
  const size_t split = rest.find(kPartSeparator);
  const auto write = [](const fs::path& path, std::string_view bytes) {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  };
  for (const Format& f : kFormats) fs::remove(dir / f.part);
  write(dir / format.mesh, rest.substr(0, split));
  if (split != std::string_view::npos)
    write(dir / format.part, rest.substr(split + kPartSeparator.size()));
  return dir / format.mesh;
}

// Loads the mesh at `path`: "" when the outcome is acceptable (one material per part, and
// parts whose indices name their vertices, in whole triangles, with finite positions and a
// normal per vertex or none; or a GlintError naming the file), else what is wrong. Any other
// exception propagates: that is a bug too.
inline std::string meshLoadProblem(const std::string& path) {
  try {
    // Without textures: OpenImageIO's decoders are not under test here, and LeakSanitizer's
    // exit-time scan crashed once its module (and its threads) were loaded.
    const MeshFile file = loadMeshFile(path, /*readTextures=*/false);
    if (file.parts.empty() || file.parts.size() != file.materials.size())
      return std::to_string(file.parts.size()) + " parts and " +
             std::to_string(file.materials.size()) + " materials";
    for (const TriangleMesh& m : file.parts) {
      if (m.indices.empty() || m.indices.size() % 3 != 0)
        return "a loaded mesh has " + std::to_string(m.indices.size()) + " indices";
      for (const uint32_t i : m.indices)
        if (i >= m.positions.size())
          return "index " + std::to_string(i) + " of " + std::to_string(m.positions.size());
      for (const auto& p : m.positions)
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
          return "a loaded mesh has a non-finite vertex";
      if (!m.normals.empty() && m.normals.size() != m.positions.size())
        return std::to_string(m.normals.size()) + " normals for " +
               std::to_string(m.positions.size()) + " vertices";
    }
  } catch (const GlintError& e) {
    if (std::string(e.what()).find(path) == std::string::npos)
      return std::string("an error that does not name the file: ") + e.what();
  }
  return "";
}

}  // namespace glint::fuzz
