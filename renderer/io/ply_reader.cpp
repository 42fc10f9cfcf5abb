#include "io/ply_reader.h"

#include <algorithm>
#include <bit>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <initializer_list>
#include <memory>
#include <string>
#include <vector>

#include "core/error.h"
#include "io/load_progress.h"
#include "io/mesh_materials.h"
#include "io/ply_body.h"
#include "io/ply_header.h"

namespace glint {

namespace {

// Logged as it loads (io/load_progress.h): seconds, at today's speed.
constexpr uint64_t kBigFaceCount = 1'000'000;
constexpr uint64_t kBigFileBytes = 50'000'000;

using ply::AsciiValues;
using ply::Bad;
using ply::BinaryValues;
using ply::Body;
using ply::isWhole;
using ply::typeName;

// What a property of an element is read for.
enum class Use : uint8_t { Skip, X, Y, Z, NX, NY, NZ, U, V, R, G, B, Corners };
constexpr int kSlots = 12;  // X … B

// A colour channel of a whole-number type counts up to the type's largest value (uchar 255 is
// 1), as Assimp's PLY reader read them; a float channel is its value.
float colourScale(PlyType t) {
  switch (t) {
    case PlyType::Int8:
      return 1.0f / 127;
    case PlyType::UInt8:
      return 1.0f / 255;
    case PlyType::Int16:
      return 1.0f / 32767;
    case PlyType::UInt16:
      return 1.0f / 65535;
    case PlyType::Int32:
      return float(1.0 / 2147483647);
    case PlyType::UInt32:
      return float(1.0 / 4294967295);
    default:
      return 1;
  }
}

int propertyIndex(const PlyElement& e, std::initializer_list<const char*> names) {
  for (size_t i = 0; i < e.properties.size(); ++i)
    for (const char* n : names)
      if (e.properties[i].name == n) return int(i);
  return -1;
}

// Reads one PLY file into one triangle mesh.
class PlyReader {
 public:
  PlyReader(const std::string& path, PlyHeader header, uint64_t fileSize, uint64_t bodyLine)
      : path_(path), header_(std::move(header)), fileSize_(fileSize), bodyLine_(bodyLine) {}

  TriangleMesh read() {
    planUses();
    const uint64_t faces = faceElement_ >= 0 ? header_.elements[size_t(faceElement_)].count : 0;
    const char* format = header_.format == PlyFormat::Ascii                ? "ASCII"
                         : header_.format == PlyFormat::BinaryLittleEndian ? "binary little endian"
                                                                           : "binary big endian";
    char size[32];
    std::snprintf(size, sizeof size, "%.1f MB", double(fileSize_) * 1e-6);
    LoadProgress progress("mesh " + path_,
                          std::string(size) + " of " + format + " PLY, " +
                              std::to_string(vertexCount_) + " vertices, " + std::to_string(faces) +
                              " faces",
                          fileSize_, faces >= kBigFaceCount || fileSize_ >= kBigFileBytes);
    // Sized by the counts, which fit in the file (checkPlyElementsFitInTheFile); reserved, not
    // filled, so memory is touched only as values arrive.
    mesh_.positions.reserve(size_t(vertexCount_) + 1);  // + 1: TriangleMesh::padForEmbree
    if (normals_) mesh_.normals.reserve(size_t(vertexCount_));
    if (uvs_) mesh_.uvs.reserve(size_t(vertexCount_));
    if (colours_) mesh_.colors.reserve(size_t(vertexCount_));
    mesh_.indices.reserve(3 * size_t(faces));
    Body body(path_, header_.bodyStart, fileSize_, bodyLine_);
    if (header_.format == PlyFormat::Ascii) {
      AsciiValues values(body);
      readElements(values, body, progress);
    } else {
      // PLY's binary formats name their byte order; this machine's is little endian.
      static_assert(std::endian::native == std::endian::little);
      BinaryValues values(body, header_.format == PlyFormat::BinaryBigEndian);
      readElements(values, body, progress);
    }
    if (mesh_.indices.empty()) throw GlintError("mesh " + path_ + " has no triangles");
    dropUnusedVertices();
    colour_.warnIfReplaced(path_);
    progress.finish(std::to_string(mesh_.triangleCount()) + " triangles, " +
                    std::to_string(mesh_.positions.size()) + " vertices");
    return std::move(mesh_);
  }

 private:
  // Which element holds the vertices and the faces, and what each of their properties gives.
  void planUses() {
    uses_.resize(header_.elements.size());
    for (size_t ei = 0; ei < header_.elements.size(); ++ei) {
      const PlyElement& e = header_.elements[ei];
      std::vector<Use>& uses = uses_[ei];
      uses.assign(e.properties.size(), Use::Skip);
      const bool vertex = e.name == "vertex" && vertexElement_ < 0;
      const bool face = e.name == "face" && faceElement_ < 0;
      if (vertex) {
        vertexElement_ = int(ei);
        vertexCount_ = e.count;
        const auto use = [&](std::initializer_list<const char*> names, Use u) {
          const int i = propertyIndex(e, names);
          if (i >= 0) uses[size_t(i)] = u;
          return i >= 0;
        };
        if (!use({"x"}, Use::X) || !use({"y"}, Use::Y) || !use({"z"}, Use::Z))
          throw GlintError("mesh " + path_ + ": its PLY vertex element has no x, y and z");
        normals_ = propertyIndex(e, {"nx"}) >= 0 && propertyIndex(e, {"ny"}) >= 0 &&
                   propertyIndex(e, {"nz"}) >= 0;
        if (normals_) {
          use({"nx"}, Use::NX);
          use({"ny"}, Use::NY);
          use({"nz"}, Use::NZ);
        }
        // The first pair of texture coordinate names the file has both of.
        static const std::pair<const char*, const char*> kUvNames[] = {
            {"u", "v"}, {"s", "t"}, {"texture_u", "texture_v"}, {"texture_s", "texture_t"}};
        for (const auto& [u, v] : kUvNames)
          if (!uvs_ && propertyIndex(e, {u}) >= 0 && propertyIndex(e, {v}) >= 0) {
            use({u}, Use::U);
            use({v}, Use::V);
            uvs_ = true;
          }
        // Vertex colours: red green blue (or diffuse_red ...), alpha ignored.
        for (const char* prefix : {"", "diffuse_"})
          if (!colours_ && propertyIndex(e, {(std::string(prefix) + "red").c_str()}) >= 0 &&
              propertyIndex(e, {(std::string(prefix) + "green").c_str()}) >= 0 &&
              propertyIndex(e, {(std::string(prefix) + "blue").c_str()}) >= 0) {
            use({(std::string(prefix) + "red").c_str()}, Use::R);
            use({(std::string(prefix) + "green").c_str()}, Use::G);
            use({(std::string(prefix) + "blue").c_str()}, Use::B);
            colours_ = true;
          }
      }
      if (face) {
        faceElement_ = int(ei);
        const int i = propertyIndex(e, {"vertex_indices", "vertex_index"});
        if (i < 0 || !e.properties[size_t(i)].list)
          throw GlintError("mesh " + path_ +
                           ": its PLY face element has no vertex_indices (or vertex_index) list");
        uses[size_t(i)] = Use::Corners;
      }
      for (size_t pi = 0; pi < e.properties.size(); ++pi) {
        const PlyProperty& p = e.properties[pi];
        if (p.list && uses[pi] != Use::Corners && uses[pi] != Use::Skip)
          throw GlintError("mesh " + path_ + ": PLY vertex property " + excerpt(p.name) +
                           " is a list, not a number");
        if (p.list && !isWhole(p.countType))
          throw GlintError("mesh " + path_ + ": PLY " + excerpt(e.name) + " property " +
                           excerpt(p.name) + " counts its list in " + typeName(p.countType) +
                           ", not a whole-number type");
        if (uses[pi] == Use::Corners && !isWhole(p.type))
          throw GlintError("mesh " + path_ + ": PLY face property " + excerpt(p.name) + " holds " +
                           typeName(p.type) + " vertex numbers, not a whole-number type");
      }
    }
    if (vertexElement_ < 0)
      throw GlintError("mesh " + path_ + ": its PLY header declares no \"vertex\" element");
  }

  template <class Values>
  void readElements(Values& values, Body& body, LoadProgress& progress) {
    for (size_t ei = 0; ei < header_.elements.size(); ++ei) {
      const PlyElement& e = header_.elements[ei];
      const std::vector<Use>& uses = uses_[ei];
      const bool vertex = int(ei) == vertexElement_;
      uint64_t i = 0;
      size_t pi = 0;
      try {
        float slot[kSlots] = {};
        for (; i < e.count; ++i) {
          values.beginElement();
          for (pi = 0; pi < uses.size(); ++pi) {
            const PlyProperty& p = e.properties[pi];
            const Use use = uses[pi];
            if (!p.list) {
              if (use == Use::Skip)
                values.skipScalar(p.type);
              else if (use >= Use::R)
                slot[int(use) - 1] = float(values.scalar(p.type)) * colourScale(p.type);
              else
                slot[int(use) - 1] = float(values.scalar(p.type));
              continue;
            }
            const int64_t n = values.whole(p.countType);
            if (n < 0) throw Bad{"its list count is " + std::to_string(n)};
            // Checked before anything is read or allocated for it: a misaligned ASCII line
            // once made a coordinate a list count of 7 GB (in Assimp's reader).
            values.checkListFits(n, p.type);
            if (use == Use::Corners)
              readCorners(values, p.type, n, i);
            else
              values.skipList(n, p.type);
          }
          pi = uses.size();  // past its properties
          values.endElement();
          if (vertex) addVertex(slot, i);
          if ((i & 0xffff) == 0) progress.update(body.offset());
        }
      } catch (const Bad& bad) {
        throw GlintError("mesh " + path_ + ": PLY " + excerpt(e.name) + " " + std::to_string(i) +
                         " of " + std::to_string(e.count) + values.place() +
                         (pi < e.properties.size() ? ", property " + excerpt(e.properties[pi].name)
                                                   : std::string()) +
                         ": " + bad.what);
      }
    }
  }

  void addVertex(const float* slot, uint64_t v) {
    const auto finite = [](float a, float b, float c) {
      return std::isfinite(a) && std::isfinite(b) && std::isfinite(c);
    };
    const auto triple = [](float a, float b, float c) {
      return " (" + std::to_string(a) + ", " + std::to_string(b) + ", " + std::to_string(c) + ")";
    };
    const float* p = slot;  // X, Y, Z, NX, NY, NZ, U, V
    if (!finite(p[0], p[1], p[2]))
      throw GlintError("mesh " + path_ + ": vertex " + std::to_string(v) +
                       " of mesh 0 is not finite" + triple(p[0], p[1], p[2]));
    mesh_.positions.push_back({p[0], p[1], p[2]});
    if (normals_) {
      if (!finite(p[3], p[4], p[5]))
        throw GlintError("mesh " + path_ + ": the normal of vertex " + std::to_string(v) +
                         " of mesh 0 is not finite" + triple(p[3], p[4], p[5]));
      mesh_.normals.push_back({p[3], p[4], p[5]});
    }
    if (uvs_) {
      if (!std::isfinite(p[6]) || !std::isfinite(p[7]))
        throw GlintError("mesh " + path_ + ": the texture coordinates of vertex " +
                         std::to_string(v) + " of mesh 0 are not finite (" + std::to_string(p[6]) +
                         ", " + std::to_string(p[7]) + ")");
      mesh_.uvs.push_back({p[6], p[7]});
    }
    if (colours_) mesh_.colors.push_back({colour_(p[8]), colour_(p[9]), colour_(p[10])});
  }

  // A face's `n` corners, fanned into triangles from the first.
  template <class Values>
  void readCorners(Values& values, PlyType type, int64_t n, uint64_t face) {
    if (n == 0)
      throw GlintError("mesh " + path_ + ": face " + std::to_string(face) +
                       " of mesh 0 has no vertices");
    uint32_t first = 0, previous = 0;
    for (int64_t k = 0; k < n; ++k) {
      const int64_t index = values.whole(type);
      if (index < 0 || uint64_t(index) >= vertexCount_)
        throw GlintError("mesh " + path_ + ": face " + std::to_string(face) +
                         " of mesh 0 names vertex " + std::to_string(index) +
                         ", but there are only " + std::to_string(vertexCount_));
      const auto corner = static_cast<uint32_t>(index);
      if (k == 0) first = corner;
      if (k >= 2) mesh_.indices.insert(mesh_.indices.end(), {first, previous, corner});
      previous = corner;
    }
  }

  // Vertices no triangle names would still widen the mesh's bounds, which the default camera
  // frames (Assimp's reader dropped them too). Kept in order, renumbered in place.
  void dropUnusedVertices() {
    std::vector<uint32_t> renumber(mesh_.positions.size(), 0);
    for (const uint32_t i : mesh_.indices) renumber[i] = 1;
    uint32_t kept = 0;
    for (uint32_t& r : renumber) r = r ? kept++ : UINT32_MAX;
    if (kept == mesh_.positions.size()) return;
    for (size_t v = 0; v < renumber.size(); ++v) {
      if (renumber[v] == UINT32_MAX) continue;
      mesh_.positions[renumber[v]] = mesh_.positions[v];
      if (normals_) mesh_.normals[renumber[v]] = mesh_.normals[v];
      if (uvs_) mesh_.uvs[renumber[v]] = mesh_.uvs[v];
      if (colours_) mesh_.colors[renumber[v]] = mesh_.colors[v];
    }
    mesh_.positions.resize(kept);
    if (normals_) mesh_.normals.resize(kept);
    if (uvs_) mesh_.uvs.resize(kept);
    if (colours_) mesh_.colors.resize(kept);
    for (uint32_t& i : mesh_.indices) i = renumber[i];
  }

  std::string path_;
  PlyHeader header_;
  uint64_t fileSize_;
  uint64_t bodyLine_;
  std::vector<std::vector<Use>> uses_;  // per element, per property
  int vertexElement_ = -1, faceElement_ = -1;
  uint64_t vertexCount_ = 0;
  bool normals_ = false, uvs_ = false, colours_ = false;
  VertexColourChannels colour_;
  TriangleMesh mesh_;
};

}  // namespace

MeshFile readPlyFile(const std::string& path) {
  std::error_code ec;
  const uint64_t fileSize = std::filesystem::file_size(path, ec);
  if (ec) throw GlintError("cannot read mesh " + path + ": " + ec.message());
  std::string head(size_t(std::min<uint64_t>(fileSize, kMaxPlyHeaderBytes)), '\0');
  {
    std::unique_ptr<std::FILE, int (*)(std::FILE*)> f(std::fopen(path.c_str(), "rb"), std::fclose);
    if (!f) throw GlintError("cannot read mesh " + path + ": " + std::strerror(errno));
    head.resize(std::fread(head.data(), 1, head.size(), f.get()));
  }
  // The header's first line must then be "ply" alone (parsePlyHeader).
  if (head.size() < 3 || (head.compare(0, 3, "ply") != 0 && head.compare(0, 3, "PLY") != 0))
    throw GlintError("mesh " + path + " is not a PLY file: it does not begin with \"ply\"");
  PlyHeader header = parsePlyHeader(path, head, fileSize);
  checkPlyElementsFitInTheFile(path, header, fileSize);
  MeshFile file;
  const uint64_t bodyLine = header.bodyLine;
  file.parts.push_back(PlyReader(path, std::move(header), fileSize, bodyLine).read());
  // A PLY has no materials Glint reads: the default surface, named as before ("FILE:"), its
  // diffuse colour the vertex colours where the file has them (as io/mesh_io.cpp does).
  Material m = defaultMaterial(MaterialKind::Phong);
  m.name = std::filesystem::path(path).filename().string() + ":";
  if (!file.parts[0].colors.empty()) multiplyDiffuseByVertexColors(m.surface);
  file.materials.push_back(std::move(m));
  return file;
}

}  // namespace glint
