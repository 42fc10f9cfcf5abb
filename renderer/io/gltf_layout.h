#pragma once
// Where a glTF file's accessors lie in its buffers, checked before Assimp reads them. Assimp
// 5.2.5 adds offsets and lengths in 64 bits without checking them: a bufferView byteOffset near
// 2^64 wrapped its bounds test and it read memory before the buffer (the geometry rendered from
// whatever lay there); and it allocates an accessor that has no bufferView (zeros, then its
// sparse values) at whatever count it declares: 840 bytes of glTF took 2.65 GB.
#include <nlohmann/json_fwd.hpp>

#include <cstdint>
#include <string>

namespace glint {

// The bytes, in all, of the accessors without a bufferView that a file's triangles may read:
// such an accessor is zeros but for its sparse values, which real files use for morph targets
// (which Glint leaves out), not for a mesh's vertices; 64 MiB is 5.6 million float positions.
inline constexpr uint64_t kMaxUnbackedAccessorBytes = uint64_t{1} << 26;

// Element `index` of `doc`'s array `list` ("accessors", "bufferViews", ...), null where the
// index is not a whole number within it or the element is not an object.
const nlohmann::json* gltfElementAt(const nlohmann::json& doc, const char* list,
                                    const nlohmann::json& index);

// The bytes of one element of `accessor` (componentType × type), 0 where either is missing or
// not one glTF 2.0 defines. Byte and short matrices' column padding is left out.
uint64_t gltfElementBytes(const nlohmann::json& accessor);

// Throws UsageError naming `path` and the element when, in `doc` (glTF 2.0 JSON, trimmed to what
// Glint reads), an attribute is stored in a type Assimp does not read it in (POSITION and NORMAL
// VEC3 of floats, TANGENT VEC4, TEXCOORD_n VEC2 or VEC3, COLOR_n VEC3 or VEC4 of floats or of
// unsigned bytes or shorts), an accessor a primitive reads (an attribute, its indices,
// their sparse indices and values) has no type or componentType glTF defines (Assimp reads a
// missing one as the smallest), or does not lie within its buffer view; when such a view, or an
// image's, does not lie within its buffer's byteLength or has a byteStride glTF does not allow (a
// multiple of 4 from 4 to 252); or when the accessors without a buffer view hold more than
// kMaxUnbackedAccessorBytes. Accessors no primitive reads (a morph target's) are left alone:
// Assimp does not read them either.
void checkGltfBufferLayout(const std::string& path, const nlohmann::json& doc);

}  // namespace glint
