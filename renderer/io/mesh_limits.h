#pragma once
// What a mesh file must pass before Assimp reads it. Assimp trusts what a file declares: a PLY
// or OFF header promising 10^12 elements made it reserve or loop until memory ran out (Assimp's
// own test file invalid/OutOfMemory.off hangs it), and a file of any other format, or with a
// documented extension but foreign content, reached one of its 40 importers. So Glint reads only
// the formats it documents, files of bounded size, and PLY files whose element counts fit in
// the file (docs/scene-format.md, docs/hardening.md). PLY files are read by Glint's own reader
// (io/ply_reader.h), which keeps these checks; Collada files pass io/collada_limits.h's.
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace glint {

// Assimp holds a whole mesh file in memory and builds several times its size of structures
// from it; it also counts file sizes in 32 bits (Importer::ReadFile). 1 GiB is about 40 million
// triangles of binary PLY, far more than a scene here needs, and keeps a file's import within
// a few GB.
inline constexpr uint64_t kMaxMeshFileBytes = uint64_t{1} << 30;

// Distinct material names an OBJ file may use (`usemtl`) or its material libraries define
// (`newmtl`): Assimp builds a material of about 30 properties for each, every property key a
// 1 kB string, and looks each name up linearly: time grows with the square of the names and
// memory with their number (docs/hardening.md). Real files use a few dozen.
inline constexpr size_t kMaxObjMaterials = 4096;

// The mesh extensions of io/scene_formats.h's table (any case, with the dot).
bool isMeshExtension(const std::string& extension);
// "OBJ (.obj), PLY (.ply), glTF 2.0 (.gltf, .glb), ...", for messages.
std::string meshFormatList();

// Throws GlintError naming `path` when its extension is not one of the above, it is larger
// than kMaxMeshFileBytes, an OBJ file names too many materials, a PLY header does not end or
// declares more elements than the bytes after it can hold, a Collada file fails
// checkColladaCounts, an ASCII STL file fails checkStlEnds, or an ASCII FBX file fails
// checkFbxEmbeddedContent (io/fbx_limits.h).
void checkMeshFileBeforeImport(const std::string& path);

// The OBJ check alone: throws GlintError naming `path` (or the material library) when the file
// and the libraries its `mtllib` lines name use or define more than kMaxObjMaterials distinct
// material names, or its `mtllib` lines name libraries more than kMaxObjMaterials times, and naming
// the line where a vertex, texture coordinate or normal holds a number that is not a finite float
// (Assimp read a texture coordinate's nan and 1e39 as 0).
void checkObjFile(const std::string& path);

// The material libraries an OBJ `mtllib` line's `value` names, relative to the OBJ file's
// folder `dir`: the value itself where it names a file there (a name may hold spaces), else each
// of its distinct words, as the OBJ format lists several libraries on one line (at most
// kMaxObjMaterials + 1 of them).
std::vector<std::string> objMaterialLibraries(const std::filesystem::path& dir,
                                              const std::string& value);

// Throws GlintError naming `path` (`size` bytes) when it is an ASCII STL file (it starts with
// "solid" and its size is not that of the binary file its header describes) whose last line is
// not `endsolid`: Assimp's reader takes a file cut short for the facets before the cut.
void checkStlEnds(const std::string& path, uint64_t size);

// The PLY check alone, on a file's bytes (`fileSize` is the whole file's size, `head` its first
// bytes, at least the header): throws GlintError naming `path` when the header is not PLY
// 1.0's or has no end_header line (Assimp's reader never returned), or an element's count times
// the least bytes one element can take exceeds what follows the header (io/ply_header.h).
void checkPlyCounts(const std::string& path, const std::string& head, uint64_t fileSize);

}  // namespace glint
