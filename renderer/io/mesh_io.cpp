#include "io/mesh_io.h"

#include <assimp/BaseImporter.h>
#include <assimp/DefaultIOSystem.h>
#include <assimp/MemoryIOWrapper.h>
#include <assimp/config.h>
#include <assimp/importerdesc.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <algorithm>
#include <array>
#include <assimp/Importer.hpp>
#include <cmath>
#include <cstdio>
#include <deque>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <optional>
#include <sstream>
#include <string_view>

#include "core/error.h"
#include "core/file_names.h"
#include "core/input_files.h"
#include "core/log.h"
#include "core/out_of_memory.h"
#include "io/ac3d_shading.h"
#include "io/assimp_scene_info.h"
#include "io/expansion_limits.h"
#include "io/face_normals.h"
#include "io/fbx_axes.h"
#include "io/gltf_indices.h"
#include "io/gltf_subset.h"
#include "io/json_source.h"
#include "io/mesh_limits.h"
#include "io/mesh_materials.h"
#include "io/obj_smoothing.h"
#include "io/object_names.h"
#include "io/ply_reader.h"
#include "io/texture_file.h"

namespace glint {

namespace {

// Assimp's file access for one mesh: the files a mesh names (a glTF's buffers, an OBJ's
// materials) pass checkInputFile (core/input_files.h: regular files only, since a device or FIFO
// such as /dev/zero would never end) and together hold at most kMaxMeshFileBytes. Opens of the
// mesh file itself (Assimp opens it several times) are not counted; it was checked before the
// import. A glTF mesh file is served as Glint's subset of it (io/gltf_subset.h), an OBJ file
// with its smoothing groups' normals (io/obj_smoothing.h).
class BoundedFiles : public Assimp::DefaultIOSystem {
 public:
  explicit BoundedFiles(std::string meshPath) : meshPath_(std::move(meshPath)) {}

  // Serves `bytes` whenever Assimp opens the mesh file itself (a glTF reduced to Glint's subset,
  // an OBJ given its smoothing groups' normals).
  void replaceMeshBytes(std::string bytes) { meshBytes_ = std::move(bytes); }

  // Why the last file refused was refused, for the message of the failed import.
  const std::string& refusal() const { return refusal_; }

  bool Exists(const char* file) const override {
    std::error_code ec;
    return std::filesystem::is_regular_file(file, ec);
  }

  Assimp::IOStream* Open(const char* file, const char* mode) override {
    const bool isMesh = ComparePaths(file, meshPath_.c_str());
    if (isMesh && meshBytes_) return inMemory(*meshBytes_);
    std::error_code ec;
    if (!isMesh && !std::filesystem::exists(file, ec))
      return severalLibraries(file);  // or a file that may not be there (an OBJ's default .mtl)
    if (!isMesh && !checked(file)) return nullptr;
    return DefaultIOSystem::Open(file, mode);
  }

 private:
  static Assimp::IOStream* inMemory(const std::string& bytes) {
    return new Assimp::MemoryIOStream(reinterpret_cast<const uint8_t*>(bytes.data()), bytes.size());
  }

  // Whether a file the mesh names may be read: within what the mesh's files may hold together.
  bool checked(const std::string& file) {
    try {
      referencedBytes_ +=
          checkInputFile(file, kMaxMeshFileBytes - std::min(referencedBytes_, kMaxMeshFileBytes),
                         "mesh " + meshPath_ + "'s file");
      return true;
    } catch (const GlintError& e) {
      // Assimp fails the import for a buffer it cannot open but goes on without a material
      // library: said either way.
      if (refusal_ != e.what()) log::warning(e.what());  // Assimp may ask more than once
      refusal_ = e.what();
      return false;
    }
  }

  // An OBJ's `mtllib a.mtl b.mtl`, which Assimp opens as the one name "dir/a.mtl b.mtl" (and
  // `mtllib /abs/a.mtl` as "dir//abs/a.mtl", `mtllib a.mtl ` with its trailing space): the
  // libraries it names (objMaterialLibraries) read one after the other, as one. Null where it
  // names no file that is there, and for any other format's files.
  Assimp::IOStream* severalLibraries(const std::string& file) {
    if (lowerExtension(meshPath_) != ".obj") return nullptr;
    const std::filesystem::path dir = std::filesystem::path(meshPath_).parent_path();
    const std::string prefix = dir.empty() ? "" : dir.string() + "/";
    if (file.rfind(prefix, 0) != 0) return nullptr;
    const std::vector<std::string> libraries =
        objMaterialLibraries(dir, file.substr(prefix.size()));
    std::string& bytes = joinedLibraries_.emplace_back();
    for (const std::string& library : libraries) {
      const std::string path = (dir / library).string();
      std::error_code ec;
      if (!std::filesystem::is_regular_file(path, ec) || !checked(path)) continue;
      std::ifstream in(path, std::ios::binary);
      bytes.append(std::istreambuf_iterator<char>(in), {});
      bytes += '\n';
    }
    return bytes.empty() ? nullptr : inMemory(bytes);
  }

  std::string meshPath_;
  std::optional<std::string> meshBytes_;
  std::deque<std::string> joinedLibraries_;  // what severalLibraries' streams read
  uint64_t referencedBytes_ = 0;
  std::string refusal_;
};

// Where several of Assimp's importers claim an extension (.gltf and .glb: glTF 1 and glTF 2),
// it asks each whether the file is its own, and when none says so it offers the file to every
// importer it has, by content: a .gltf holding an OFF file reached the OFF reader. Glint asks
// the claimants first and refuses the file when none of them recognises it.
void checkAnImporterOfTheExtensionReadsIt(Assimp::Importer& importer, const std::string& path) {
  std::string ext = lowerExtension(path);
  if (ext.empty()) return;
  ext = ext.substr(1);
  std::vector<Assimp::BaseImporter*> claimants;
  for (size_t i = 0; i < importer.GetImporterCount(); ++i) {
    std::istringstream extensions(importer.GetImporterInfo(i)->mFileExtensions);
    for (std::string e; extensions >> e;)
      if (e == ext) claimants.push_back(importer.GetImporter(i));
  }
  if (claimants.size() == 1) return;  // Assimp takes it without looking at the content
  for (Assimp::BaseImporter* claimant : claimants)
    if (claimant->CanRead(path, importer.GetIOHandler(), true)) return;
  throw GlintError("cannot read mesh " + path + ": its content is not ." + ext +
                   " (Assimp's readers of ." + ext + " do not recognise it)");
}

// Opens the textures a mesh file's materials name. An image the file carries is read from the
// file: by index ("*0", a .glb's buffer view or a data URI) or by the name of the file it was
// (an FBX's embedded Content, matched as Assimp matches it, by the name after the last
// separator), as Blender takes an FBX's packed images before any file of that name. Others are
// read relative to the mesh file, with Windows separators turned around (OBJ files from Windows
// tools write .\\wood.jpg) and, where the name's case does not match, the one file in the
// folder whose name matches regardless of case. A texture that cannot be read is warned about and
// left out (the slot keeps its colour): real assets often name textures they were not shipped
// with.
TextureOpener textureOpener(const std::string& meshPath, const aiScene& scene) {
  const std::filesystem::path dir = std::filesystem::path(meshPath).parent_path();
  auto opened = std::make_shared<std::map<std::string, std::shared_ptr<const ImageTexture>>>();
  return [dir, meshPath, opened,
          &scene](const std::string& named) -> std::shared_ptr<const ImageTexture> {
    if (const auto it = opened->find(named); it != opened->end()) return it->second;
    std::shared_ptr<const ImageTexture>& slot = (*opened)[named];
    if (named.empty()) {
      // Assimp's name for a glTF image whose data URI holds no bytes: no file to look for.
      log::warning("mesh " + meshPath +
                   ": texture left out: a material names an image without a name or bytes");
      return slot;
    }
    const aiTexture* t = scene.GetEmbeddedTexture(named.c_str());
    if (t || named[0] == '*') {
      try {
        // Assimp hands a compressed image over as the PNG or JPEG (or other) file it was.
        if (!t || t->mHeight != 0 || !t->pcData)
          throw GlintError("Glint reads embedded image files only, not raw texels");
        // Readers are chosen by the name's extension: the format Assimp names, where the name
        // does not end in it. Assimp names none for an extension of four letters (.tiff): the
        // name's own then, and PNG for a name without one.
        const std::string ext = lowerExtension(named);
        const std::string hint = t->achFormatHint[0] ? lowerCase(t->achFormatHint)
                                 : ext.size() > 1    ? ext.substr(1)
                                                     : "png";
        const bool ends = ext == "." + hint;
        slot = openImageTextureInMemory(
            meshPath + "#" + named + (ends ? "" : "." + hint),
            std::string(reinterpret_cast<const char*>(t->pcData), t->mWidth));
      } catch (const OutOfMemoryError&) {
        throw;  // not a texture to leave out: the rest would not fit either
      } catch (const GlintError& e) {
        log::warning("mesh " + meshPath + ": embedded texture " + inQuotes(excerpt(named)) +
                     " left out: " + e.what());
      }
      return slot;
    }
    std::string name = named;
    std::replace(name.begin(), name.end(), '\\', '/');
    std::filesystem::path file(name);
    if (file.is_relative()) file = dir / file;
    std::error_code ec;
    if (!std::filesystem::exists(file, ec)) {
      const std::string lower = lowerCase(file.filename().string());
      for (const auto& entry : std::filesystem::directory_iterator(file.parent_path(), ec))
        if (lowerCase(entry.path().filename().string()) == lower) file = entry.path();
    }
    // A path of the machine that wrote the file (an FBX's "D:\projects\wood.jpg"): the image
    // of that name beside the mesh, where there is one.
    if (!std::filesystem::exists(file, ec) && std::filesystem::exists(dir / file.filename(), ec))
      file = dir / file.filename();
    try {
      slot = openImageTexture(file.lexically_normal().string());
    } catch (const OutOfMemoryError&) {
      throw;
    } catch (const GlintError& e) {
      log::warning("mesh " + meshPath + ": texture left out: " + e.what());
    }
    return slot;
  };
}

// The triangles Assimp's pre-transformation makes of the node tree under `node` (each node's
// meshes copied for it), and the nodes on the way to where most of them are.
uint64_t flattenedTriangles(const aiScene& s, const aiNode& node, int depth,
                            std::vector<std::string>* path) {
  uint64_t count = 0;
  for (unsigned i = 0; i < node.mNumMeshes; ++i)
    if (node.mMeshes[i] < s.mNumMeshes)
      for (unsigned f = 0; f < s.mMeshes[node.mMeshes[i]]->mNumFaces; ++f)
        count += s.mMeshes[node.mMeshes[i]]->mFaces[f].mNumIndices == 3;
  uint64_t most = 0;
  const aiNode* mostBelow = nullptr;
  for (unsigned c = 0; c < node.mNumChildren && depth < 1024; ++c) {
    const uint64_t below = flattenedTriangles(s, *node.mChildren[c], depth + 1, nullptr);
    count = saturatingAdd(count, below);
    if (below > most) most = below, mostBelow = node.mChildren[c];
  }
  if (path) {
    path->push_back(inQuotes(excerpt(node.mName.C_Str())));
    if (mostBelow) flattenedTriangles(s, *mostBelow, depth + 1, path);
  }
  return count;
}

// Refuses a file whose meshes, placed by every node that names them, would take more than
// kMaxFlattenedTriangles: Assimp's pre-transformation copies a mesh for each node.
void checkFlattenedTriangles(const std::string& path, const aiScene& s) {
  const uint64_t triangles = flattenedTriangles(s, *s.mRootNode, 0, nullptr);
  if (triangles <= kMaxFlattenedTriangles) return;
  std::vector<std::string> nodes;
  flattenedTriangles(s, *s.mRootNode, 0, &nodes);
  throw UsageError("mesh " + path + ": its nodes place " + countText(triangles) +
                   " triangles (a mesh is copied for each node that places it), more than the " +
                   std::to_string(kMaxFlattenedTriangles) + " Glint reads from one file; most " +
                   "come through the nodes " + pathText(nodes));
}

// Refuses a node whose transform, composed with its parents' (in double, as a 1e38 scale
// under another overflows float), places its meshes past ±kMaxRayOrigin or outside the float
// range, naming the node: Assimp's pre-transformation would make such vertices infinite, and
// the error would surface only as a camera that cannot frame them.
void checkNodePlacements(const std::string& path, const aiScene& s) {
  std::vector<std::pair<aiVector3D, aiVector3D>> boxes(s.mNumMeshes);
  for (unsigned mi = 0; mi < s.mNumMeshes; ++mi) {
    const aiMesh& m = *s.mMeshes[mi];
    aiVector3D lo(kInfinity), hi(-kInfinity);
    for (unsigned v = 0; v < m.mNumVertices; ++v)
      for (int a = 0; a < 3; ++a) {
        lo[a] = std::min(lo[a], m.mVertices[v][a]);
        hi[a] = std::max(hi[a], m.mVertices[v][a]);
      }
    boxes[mi] = {lo, hi};
  }
  using Matrix = std::array<double, 12>;  // rows of a 3 × 4 affine transform
  const auto visit = [&](const auto& self, const aiNode& node, const Matrix& parent,
                         int depth) -> void {
    const aiMatrix4x4& l = node.mTransformation;
    const double local[12] = {l.a1, l.a2, l.a3, l.a4, l.b1, l.b2,
                              l.b3, l.b4, l.c1, l.c2, l.c3, l.c4};
    Matrix world{};
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 4; ++c)
        world[size_t(4 * r + c)] =
            parent[size_t(4 * r)] * local[c] + parent[size_t(4 * r + 1)] * local[4 + c] +
            parent[size_t(4 * r + 2)] * local[8 + c] + (c == 3 ? parent[size_t(4 * r + 3)] : 0.0);
    for (unsigned i = 0; i < node.mNumMeshes; ++i) {
      if (node.mMeshes[i] >= s.mNumMeshes || s.mMeshes[node.mMeshes[i]]->mNumVertices == 0)
        continue;
      const auto& [lo, hi] = boxes[node.mMeshes[i]];
      for (int corner = 0; corner < 8; ++corner) {
        const double p[3] = {corner & 1 ? hi.x : lo.x, corner & 2 ? hi.y : lo.y,
                             corner & 4 ? hi.z : lo.z};
        for (int r = 0; r < 3; ++r) {
          const double x = world[size_t(4 * r)] * p[0] + world[size_t(4 * r + 1)] * p[1] +
                           world[size_t(4 * r + 2)] * p[2] + world[size_t(4 * r + 3)];
          if (std::fabs(x) <= double(kMaxRayOrigin)) continue;
          double scale = 0;
          for (int k = 0; k < 3; ++k) scale = std::max(scale, std::fabs(world[size_t(4 * r + k)]));
          char text[200];
          std::snprintf(text, sizeof text,
                        "places a vertex at %g along an axis (its transform composed with its "
                        "parents' scales by up to %g and moves by %g)",
                        x, scale, world[size_t(4 * r + 3)]);
          throw UsageError("mesh " + path + ": node " + inQuotes(excerpt(node.mName.C_Str())) +
                           " " + text +
                           "; Glint's geometry must lie within ±1e18, the range of "
                           "rays it traces");
        }
      }
    }
    for (unsigned c = 0; c < node.mNumChildren && depth < 1024; ++c)
      self(self, *node.mChildren[c], world, depth + 1);
  };
  visit(visit, *s.mRootNode, Matrix{1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0}, 0);
}

// Assimp's vertex format of a mesh (GetMeshVFormatUnique of its ProcessHelper): the vertex
// components it has. PreTransformVertices merges the meshes of one material and one format.
unsigned vertexFormat(const aiMesh& m) {
  unsigned format = 1;
  if (m.HasNormals()) format |= 0x2;
  if (m.HasTangentsAndBitangents()) format |= 0x4;
  for (unsigned p = 0; p < AI_MAX_NUMBER_OF_TEXTURECOORDS && m.HasTextureCoords(p); ++p) {
    format |= 0x100u << p;
    if (m.mNumUVComponents[p] == 3) format |= 0x10000u << p;
  }
  for (unsigned p = 0; p < AI_MAX_NUMBER_OF_COLOR_SETS && m.HasVertexColors(p); ++p)
    format |= 0x1000000u << p;
  return format;
}

// The names of the faces of the meshes Assimp's PreTransformVertices makes, read from the node
// tree before it flattens it. It merges, per material and vertex format, the faces of every
// mesh each node places, node by node in depth-first order (its CollectData); the same walk
// gives each run of faces its node's name (else its mesh's: object_names.h).
class FaceNames {
 public:
  explicit FaceNames(const aiScene& s) {
    std::vector<const aiNode*> stack{s.mRootNode};
    while (!stack.empty()) {
      const aiNode* node = stack.back();
      stack.pop_back();
      const std::string nodeName = usableName(node->mName);
      for (unsigned i = 0; i < node->mNumMeshes; ++i) {
        const aiMesh& m = *s.mMeshes[node->mMeshes[i]];
        const std::string name = nodeName.empty() ? meshName(s, m) : nodeName;
        runs_[{m.mMaterialIndex, vertexFormat(m)}].push_back({indexOf(name), m.mNumFaces});
      }
      for (unsigned c = node->mNumChildren; c-- > 0;) stack.push_back(node->mChildren[c]);
    }
  }

  // Whether any face has a name.
  bool any() const { return names_.size() > 1 || (names_.size() == 1 && !names_[0].empty()); }
  const std::vector<std::string>& names() const { return names_; }

  // The name index of each face of `merged`, one of PreTransformVertices' meshes; empty when
  // its faces are not the ones the walk counted (then they go unnamed).
  std::vector<uint32_t> of(const aiMesh& merged) const {
    std::vector<uint32_t> out;
    const auto it = runs_.find({merged.mMaterialIndex, vertexFormat(merged)});
    if (it == runs_.end()) return out;
    for (const auto& [name, faces] : it->second) out.insert(out.end(), faces, name);
    if (out.size() != merged.mNumFaces) out.clear();
    return out;
  }

 private:
  uint32_t indexOf(const std::string& name) {
    const auto [it, added] = index_.emplace(name, static_cast<uint32_t>(names_.size()));
    if (added) names_.push_back(name);
    return it->second;
  }
  // A mesh's name, or "" where Assimp gave it its material's: the OBJ reader names a mesh by
  // its `g` group, else by the `usemtl` that started it, which names no object.
  static std::string meshName(const aiScene& s, const aiMesh& m) {
    if (m.mMaterialIndex < s.mNumMaterials && s.mMaterials[m.mMaterialIndex]->GetName() == m.mName)
      return "";
    return usableName(m.mName);
  }
  // The file's name, or "" for one Assimp made up or one no scene may give (a control
  // character, "objects[2]": io/object_names.h).
  static std::string usableName(const aiString& name) {
    std::string given = fileGivenName(name.C_Str());
    return objectNameProblem(given).empty() ? given : std::string();
  }
  std::map<std::pair<unsigned, unsigned>, std::vector<std::pair<uint32_t, unsigned>>> runs_;
  std::map<std::string, uint32_t> index_;
  std::vector<std::string> names_;
};

// Assimp catches every exception of its readers and processing steps and keeps only its text:
// a failed allocation is the machine's failure (exit 1, named by loadMeshFile), not the file's.
void rethrowOutOfMemory(const Assimp::Importer& importer) {
  if (std::string_view(importer.GetErrorString()) == std::bad_alloc().what())
    throw std::bad_alloc();
}

// Assimp's reading of `path` with no processing but its own validation, or a GlintError.
const aiScene* importOrThrow(Assimp::Importer& importer, const BoundedFiles& files,
                             const std::string& path) {
  // A file without meshes (a Collada file of cameras alone) would get Assimp's stand-in pyramids
  // at its nodes, which Glint would render as if they were the file's.
  importer.SetPropertyBool(AI_CONFIG_IMPORT_NO_SKELETON_MESHES, true);
  const aiScene* s = importer.ReadFile(path, aiProcess_ValidateDataStructure);
  if (!s) rethrowOutOfMemory(importer);
  if (!s || !s->mRootNode)
    throw GlintError("cannot read mesh " + path + ": " + excerpt(importer.GetErrorString()) +
                     (files.refusal().empty() ? "" : " (" + files.refusal() + ")"));
  return s;
}

// Assimp's `steps` applied to the scene `importer` holds, or a GlintError.
const aiScene* processOrThrow(Assimp::Importer& importer, unsigned steps, const std::string& path) {
  const aiScene* s = importer.ApplyPostProcessing(steps);
  if (!s) {
    rethrowOutOfMemory(importer);
    throw GlintError("cannot process mesh " + path + ": " + importer.GetErrorString());
  }
  return s;
}

// An AC3D file whose surfaces are shaded smooth, given vertex normals (creaseNormals): Assimp's
// reader leaves none, and such a model rendered faceted. An edge sharper than the file's crease
// stays sharp.
void smoothAc3dSurfaces(const aiScene& scene, const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  const Ac3dShading shading = readAc3dShading(in);
  if (shading.smoothSurfaces == 0) return;
  if (shading.flatSurfaces > 0)
    log::warning("mesh " + path + ": " + std::to_string(shading.flatSurfaces) + " of its " +
                 std::to_string(shading.flatSurfaces + shading.smoothSurfaces) +
                 " surfaces are flat-shaded; Glint shades every surface of the file smooth "
                 "(edges sharper than its crease angle stay sharp)");
  if (shading.creasesDiffer)
    log::warning("mesh " + path + ": its objects give different crease angles; Glint smooths " +
                 "them all at the largest, " + formatNumber(shading.creaseDegrees) + " degrees");
  size_t crowded = 0;
  for (unsigned mi = 0; mi < scene.mNumMeshes; ++mi) {
    aiMesh& m = *scene.mMeshes[mi];
    if (!(m.mPrimitiveTypes & aiPrimitiveType_TRIANGLE) || m.mNormals) continue;
    std::vector<Vec3f> positions(m.mNumVertices);
    for (unsigned v = 0; v < m.mNumVertices; ++v)
      positions[v] = {m.mVertices[v].x, m.mVertices[v].y, m.mVertices[v].z};
    std::vector<uint32_t> triangles;
    for (unsigned f = 0; f < m.mNumFaces; ++f)
      if (m.mFaces[f].mNumIndices == 3)
        triangles.insert(triangles.end(), m.mFaces[f].mIndices, m.mFaces[f].mIndices + 3);
    size_t crowdedHere = 0;
    const std::vector<Vec3f> normals =
        creaseNormals(positions, triangles, shading.creaseDegrees, crowdedHere);
    crowded += crowdedHere;
    m.mNormals = new aiVector3D[m.mNumVertices];
    for (unsigned v = 0; v < m.mNumVertices; ++v)
      m.mNormals[v] = aiVector3D(normals[v].x, normals[v].y, normals[v].z);
  }
  if (crowded > 0)
    log::warning("mesh " + path + ": at " + std::to_string(crowded) + " vertices more than " +
                 std::to_string(kMaxCornersCompared) +
                 " faces meet; they keep their faces' own normals there");
}

MeshFile readMeshFile(const std::string& path, bool readTextures) {
  checkInputFile(path, kMaxMeshFileBytes, "mesh");
  checkMeshFileBeforeImport(path);
  if (lowerExtension(path) == ".ply") return readPlyFile(path);  // Glint's own (io/ply_reader.h)
  Assimp::Importer importer;
  auto* files = new BoundedFiles(path);
  importer.SetIOHandler(files);  // the importer owns it
  const std::string ext = lowerExtension(path);
  std::vector<GltfMaterialInfo> gltfMaterials;  // what Glint reads of them itself
  if (ext == ".gltf" || ext == ".glb") {
    std::ifstream in(path, std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(in)), {});
    files->replaceMeshBytes(ext == ".gltf" ? gltfSubset(path, bytes, &gltfMaterials)
                                           : glbSubset(path, bytes, &gltfMaterials));
    if (ext == ".gltf")
      checkGltfIndices(path, bytes);
    else
      checkGltfIndices(path, glbJsonChunk(path, bytes), glbBinaryChunk(bytes));
  }
  if (ext == ".obj") {
    std::ifstream in(path, std::ios::binary);
    const std::string text((std::istreambuf_iterator<char>(in)), {});
    if (std::optional<std::string> smoothed = objWithSmoothingGroupNormals(text, path))
      files->replaceMeshBytes(std::move(*smoothed));
  }
  checkAnImporterOfTheExtensionReadsIt(importer, path);
  // Positions, the file's vertex normals (smooth shading), its first two texture coordinates and
  // vertex colours, and its materials are kept.
  importer.SetPropertyInteger(AI_CONFIG_PP_RVC_FLAGS, 0);
  // Read with no processing but Assimp's own validation: its post-processing steps index
  // vertices through the faces before any check of ours, and a face naming a vertex that does
  // not exist made them read and write out of bounds.
  const aiScene* s = importOrThrow(importer, *files, path);
  if (ext == ".fbx") turnFbxAxesToGlints(const_cast<aiScene&>(*s));
  for (unsigned mi = 0; mi < s->mNumMeshes; ++mi) {
    // The importer's own scene, not const: the primitive types its readers declare are replaced
    // by those of the faces. Assimp's triangulation asserts (an abort, in Debian's build) when a
    // mesh declares polygons but has none; a PLY face of zero vertices did that (and is refused).
    aiMesh* m = const_cast<aiScene*>(s)->mMeshes[mi];
    unsigned types = 0;
    for (unsigned f = 0; f < m->mNumFaces; ++f) {
      const unsigned n = m->mFaces[f].mNumIndices;
      if (n == 0)
        throw GlintError("mesh " + path + ": face " + std::to_string(f) + " of mesh " +
                         std::to_string(mi) + " has no vertices");
      types |= n == 1   ? aiPrimitiveType_POINT
               : n == 2 ? aiPrimitiveType_LINE
               : n == 3 ? aiPrimitiveType_TRIANGLE
                        : aiPrimitiveType_POLYGON;
    }
    m->mPrimitiveTypes = types;
    for (unsigned f = 0; f < m->mNumFaces; ++f)
      for (unsigned c = 0; c < m->mFaces[f].mNumIndices; ++c)
        if (m->mFaces[f].mIndices[c] >= m->mNumVertices)
          throw GlintError("mesh " + path + ": face " + std::to_string(f) + " of mesh " +
                           std::to_string(mi) + " names vertex " +
                           std::to_string(m->mFaces[f].mIndices[c]) + ", but there are only " +
                           std::to_string(m->mNumVertices));
  }
  // An STL facet's normal only restates its vertices' winding, and exporters write 0 0 0, or
  // NaN for a facet of no area, as often as the normal: STL is flat by definition, so its
  // triangles are shaded from their vertices and the file's normals are not read (a NaN one
  // refused the whole file; a zero one shaded its facet black).
  if (ext == ".stl")
    for (unsigned mi = 0; mi < s->mNumMeshes; ++mi) {
      aiMesh* m = s->mMeshes[mi];
      delete[] m->mNormals;
      m->mNormals = nullptr;
    }
  // Check for NaN and Inf before Assimp joins vertices: its vertex welding compares positions
  // (and normals) and would silently merge or drop non-finite ones.
  for (unsigned mi = 0; mi < s->mNumMeshes; ++mi)
    for (unsigned v = 0; v < s->mMeshes[mi]->mNumVertices; ++v) {
      const aiMesh* m = s->mMeshes[mi];
      for (const aiVector3D* values : {m->mVertices, m->mNormals}) {
        if (!values) continue;
        const aiVector3D& p = values[v];
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
          throw GlintError("mesh " + path + ": " + (values == m->mNormals ? "the normal of " : "") +
                           "vertex " + std::to_string(v) + " of mesh " + std::to_string(mi) +
                           " is not finite (" + std::to_string(p.x) + ", " + std::to_string(p.y) +
                           ", " + std::to_string(p.z) + ")");
      }
      // Texture coordinates too, as the PLY reader refuses them: read as (0, 0), a texture
      // showed its corner texel there without a word.
      for (int set = 0; set < 2; ++set)
        if (const aiVector3D* uv = m->mTextureCoords[set];
            uv && (!std::isfinite(uv[v].x) || !std::isfinite(uv[v].y)))
          throw GlintError("mesh " + path + ": the texture coordinates of vertex " +
                           std::to_string(v) + " of mesh " + std::to_string(mi) +
                           " are not finite (" + std::to_string(uv[v].x) + ", " +
                           std::to_string(uv[v].y) + ")");
    }
  s = processOrThrow(
      importer, aiProcess_Triangulate | aiProcess_RemoveComponent | aiProcess_SortByPType, path);
  if (ext == ".ac") smoothAc3dSurfaces(*s, path);
  checkFlattenedTriangles(path, *s);
  checkNodePlacements(path, *s);
  // The importer's own scene again (io/face_normals.h).
  auto& faces = const_cast<aiScene&>(*s);
  if (someMeshesLackNormals(faces)) giveFlatNormalsWhereMissing(faces, path);
  windMirroredTrianglesOutward(faces);
  const FaceNames faceNames(*s);
  s = processOrThrow(importer, aiProcess_JoinIdenticalVertices | aiProcess_PreTransformVertices,
                     path);
  // Shaded smooth when the file gives vertex normals (where some of its meshes do, the others
  // were given their faces' above), else flat from the triangles.
  bool smooth = true;
  for (unsigned mi = 0; mi < s->mNumMeshes; ++mi)
    if (s->mMeshes[mi]->mPrimitiveTypes & aiPrimitiveType_TRIANGLE)
      smooth = smooth && s->mMeshes[mi]->mNormals != nullptr;
  const MeshFileFormat format = ext == ".ply"                     ? MeshFileFormat::Ply
                                : ext == ".obj"                   ? MeshFileFormat::Obj
                                : ext == ".gltf" || ext == ".glb" ? MeshFileFormat::Gltf
                                                                  : MeshFileFormat::Other;
  const std::string fileName = std::filesystem::path(path).filename().string();
  MeshFile file;
  const TextureOpener openTexture =
      readTextures ? textureOpener(path, *s)
                   : [](const std::string&) { return std::shared_ptr<const ImageTexture>(); };
  std::vector<int> partOfMaterial(s->mNumMaterials, -1);
  if (faceNames.any()) file.objectNames = faceNames.names();
  std::vector<bool> partWithoutTangents(s->mNumMaterials, false);
  VertexColourChannels colour;
  for (unsigned mi = 0; mi < s->mNumMeshes; ++mi) {
    const aiMesh* m = s->mMeshes[mi];
    if (!(m->mPrimitiveTypes & aiPrimitiveType_TRIANGLE)) continue;  // points and lines
    if (m->mMaterialIndex >= s->mNumMaterials)
      throw GlintError("mesh " + path + ": mesh " + std::to_string(mi) + " names material " +
                       std::to_string(m->mMaterialIndex) + ", but there are only " +
                       std::to_string(s->mNumMaterials));
    int& part = partOfMaterial[m->mMaterialIndex];
    if (part < 0) {
      part = int(file.parts.size());
      file.parts.emplace_back();
      file.materials.push_back(materialFromMeshFile(*s->mMaterials[m->mMaterialIndex], format,
                                                    fileName, openTexture, gltfMaterials));
    }
    TriangleMesh& mesh = file.parts[size_t(part)];
    const auto base = static_cast<uint32_t>(mesh.positions.size());
    for (unsigned v = 0; v < m->mNumVertices; ++v) {
      const aiVector3D& p = m->mVertices[v];
      mesh.positions.push_back({p.x, p.y, p.z});
      if (smooth) mesh.normals.push_back({m->mNormals[v].x, m->mNormals[v].y, m->mNormals[v].z});
    }
    // Vertex colours (RGB of the first set, as VertexColourChannels reads them), and
    // texture coordinates: where one mesh of a part has them and another not, the other's
    // vertices take white and (0, 0).
    if (const aiColor4D* c = m->mColors[0]) {
      mesh.colors.resize(base, Rgb{1, 1, 1});
      for (unsigned v = 0; v < m->mNumVertices; ++v)
        mesh.colors.push_back({colour(c[v].r), colour(c[v].g), colour(c[v].b)});
    }
    // The second set (glTF's TEXCOORD_1) likewise, where a mesh of the part has one.
    for (int set = 0; set < 2; ++set)
      if (const aiVector3D* uv = m->mTextureCoords[set]) {
        std::vector<Vec2f>& uvs = set == 0 ? mesh.uvs : mesh.uvs1;
        uvs.resize(base, Vec2f{0, 0});
        for (unsigned v = 0; v < m->mNumVertices; ++v) uvs.push_back({uv[v].x, uv[v].y});
      }
    const std::vector<uint32_t> names =
        file.objectNames.empty() ? std::vector<uint32_t>() : faceNames.of(*m);
    uint32_t unnamed = 0;
    if (!file.objectNames.empty() && names.empty()) {
      // Not expected of the Assimp Glint is built with; said rather than named wrongly.
      log::warning("mesh " + path + ": the faces of mesh " + std::to_string(mi) +
                   " could not be matched to the nodes that place them; they take the object's "
                   "name");
      const auto it = std::find(file.objectNames.begin(), file.objectNames.end(), "");
      unnamed = static_cast<uint32_t>(it - file.objectNames.begin());
      if (it == file.objectNames.end()) file.objectNames.push_back("");
    }
    // The file's tangents (glTF's TANGENT: Assimp gives xyz, and the bitangent normal × xyz
    // times w, whose side recovers w), per corner; a part where one mesh has none has none
    // (they are generated for it where a normal map needs them).
    const bool tangents = m->mTangents && m->mBitangents && m->mNormals &&
                          mesh.tangents.size() == mesh.indices.size();
    if (!tangents) mesh.tangents.clear();
    const auto tangentOf = [&](unsigned v) -> TriangleMesh::Tangent {
      const aiVector3D& t = m->mTangents[v];
      const Vec3f direction{t.x, t.y, t.z};
      const float len = length(direction);
      if (!(len > 0 && std::isfinite(len))) return {};  // generated tangents replace it
      const aiVector3D side = m->mNormals[v] ^ t;
      return {direction / len, side * m->mBitangents[v] < 0 ? -1.0f : 1.0f};
    };
    bool tangentsUsable = tangents;
    for (unsigned f = 0; f < m->mNumFaces; ++f) {
      const aiFace& face = m->mFaces[f];
      if (face.mNumIndices != 3) continue;
      for (int c = 0; c < 3; ++c) {
        mesh.indices.push_back(base + face.mIndices[c]);
        if (!tangents) continue;
        mesh.tangents.push_back(tangentOf(face.mIndices[c]));
        tangentsUsable = tangentsUsable && length(mesh.tangents.back().direction) > 0;
      }
      if (!file.objectNames.empty()) mesh.objectIds.push_back(names.empty() ? unnamed : names[f]);
    }
    if (!tangentsUsable) mesh.tangents.clear();
    if (!tangents || !tangentsUsable) partWithoutTangents[size_t(part)] = true;
  }
  colour.warnIfReplaced(path);
  for (size_t i = 0; i < file.parts.size(); ++i)
    if (partWithoutTangents[i]) file.parts[i].tangents.clear();
  // A material whose meshes held only points and lines leaves an empty part.
  for (size_t i = file.parts.size(); i-- > 0;)
    if (file.parts[i].indices.empty()) {
      file.parts.erase(file.parts.begin() + ptrdiff_t(i));
      file.materials.erase(file.materials.begin() + ptrdiff_t(i));
    }
  if (file.parts.empty()) throw GlintError("mesh " + path + " has no triangles");
  for (size_t i = 0; i < file.parts.size(); ++i) {
    TriangleMesh& part = file.parts[i];
    // A second set without a first (no texture would read it as a first set) is dropped.
    if (!part.hasUvs()) part.uvs1.clear();
    if (part.hasUvs()) part.uvs.resize(part.positions.size(), Vec2f{0, 0});
    if (!part.uvs1.empty()) part.uvs1.resize(part.positions.size(), Vec2f{0, 0});
    // Vertex colours multiply the diffuse colour (glTF's COLOR_0 its base colour); a mesh of
    // the part without them is white.
    if (part.colors.empty()) continue;
    part.colors.resize(part.positions.size(), Rgb{1, 1, 1});
    multiplyDiffuseByVertexColors(file.materials[i].surface);
  }
  return file;
}

}  // namespace

MeshFile loadMeshFile(const std::string& path, bool readTextures) {
  return out_of_memory::whileDoing("reading mesh " + path,
                                   [&] { return readMeshFile(path, readTextures); });
}

FileSceneInfo readMeshFileSceneInfo(const std::string& path) {
  return out_of_memory::whileDoing("reading mesh " + path, [&] {
    try {
      checkInputFile(path, kMaxMeshFileBytes, "mesh");
      checkMeshFileBeforeImport(path);
      Assimp::Importer importer;
      auto* files = new BoundedFiles(path);
      importer.SetIOHandler(files);  // the importer owns it
      checkAnImporterOfTheExtensionReadsIt(importer, path);
      const aiScene& scene = *importOrThrow(importer, *files, path);
      // The cameras and lights stand where the meshes do (readMeshFile).
      if (lowerExtension(path) == ".fbx") turnFbxAxesToGlints(const_cast<aiScene&>(scene));
      return sceneInfoFromAssimp(scene, path);
    } catch (const OutOfMemoryError&) {
      throw;
    } catch (const UsageError&) {
      throw;
    } catch (const GlintError& e) {
      // The file's fault, as the same error is where a scene names the file (exit 2).
      throw UsageError(e.what());
    }
  });
}

}  // namespace glint
