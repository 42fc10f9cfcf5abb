#pragma once
// The names of a scene's objects and lights (docs/scene-format.md, Names): what a "name" key
// may hold, and the names a mesh file's reader made up rather than read.
#include <string>
#include <string_view>

#include "io/json_source.h"

namespace glint {

// What is wrong with `name` as the name of an object or a light, "" when nothing: a name is a
// non-empty string without control characters, not beginning with "objects[" or "lights["
// (the names of unnamed ones).
std::string objectNameProblem(std::string_view name);
// The "name" at `n`, checked by objectNameProblem. Throws SceneError at `n`.
std::string parseObjectName(const JsonNode& n);

// `name` as a file gave it, or "" where it is one Assimp's readers make up for what the file
// left unnamed: the root of every file ("<OFFRoot>", "<3DSDummyRoot>"), FBX's helper nodes
// ("root_$AssimpFbx$_GeometricScaling"), Collada's nodes without a name or id
// ("$ColladaAutoName$_3"), glTF 2's element ids ("nodes[3]", "meshes[0]",
// "meshes[0]-1") and OBJ's "defaultobject".
std::string fileGivenName(std::string_view name);

}  // namespace glint
