#pragma once
// What a glTF file's node graph flattens to. Nodes may share children (a node listed as the
// child of two parents, or twice by one), and every reader that places them, Assimp's and
// Glint's (io/gltf_scene.h), visits a shared node once per path to it: 40 levels of a node
// listing the next one twice name 2^40 node copies in 1 kB. Counted here from the graph before
// either reader runs (io/expansion_limits.h).
#include <nlohmann/json_fwd.hpp>

#include <string>

namespace glint {

// Throws UsageError naming `path`, the counted total, the budget and the path of nodes through
// which most copies come, when one of the file's scenes (each scene's nodes, and the nodes
// without a parent, which a file without scenes shows) flattens to more than
// kMaxFlattenedInstances node copies or kMaxFlattenedTriangles triangles (each primitive's
// index count, else its POSITION count, read as triangles of its mode), or when the graph has
// a cycle, an index out of range or a path deeper than kMaxGltfNodeDepth.
void checkGltfExpansion(const std::string& path, const nlohmann::json& doc);

// Deeper node trees than this are refused: real files nest a dozen levels.
inline constexpr int kMaxGltfNodeDepth = 256;

}  // namespace glint
