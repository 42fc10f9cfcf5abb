#pragma once
// Assimp 5.2.5's glTF 2 reader drops, without a word, every triangle whose index names a vertex
// the primitive does not have (assimp-testmodels' glTF2/IndexOutOfRange renders one triangle
// short, exit 0). Glint reads each primitive's indices itself before Assimp does and refuses
// the file, naming the primitive and the index.
#include <string>

namespace glint {

// Checks the indices of every primitive of `gltfJson` (a .gltf file's text, or a .glb file's JSON
// chunk) against its POSITION accessor's count. `path` locates buffers given by a file URI (each
// read through checkInputFile); `glbBinary` is a .glb file's binary chunk (buffer 0 without a
// URI). Indices that cannot be located (a malformed accessor, a missing buffer) are left to
// Assimp's own checks. Throws GlintError naming `path`, the mesh, the primitive, the index and
// the vertex count.
void checkGltfIndices(const std::string& path, const std::string& gltfJson,
                      const std::string& glbBinary = "");

// A GLB file's binary chunk (empty when it has none). `bytes` is the whole file, whose JSON
// chunk has been read (io/gltf_subset.h glbJsonChunk).
std::string glbBinaryChunk(const std::string& bytes);

}  // namespace glint
