#include "io/object_names.h"

#include <cctype>

#include "core/error.h"

namespace glint {

std::string objectNameProblem(std::string_view name) {
  if (name.empty()) return "must not be empty (leave \"name\" out for the default name)";
  for (const unsigned char c : name)
    if (c < 0x20 || c == 0x7f)
      return "holds a control character; a name is typed into compositors' matte lists";
  for (const std::string_view reserved : {"objects[", "lights["})
    if (name.substr(0, reserved.size()) == reserved)
      return "begins with " + inQuotes(std::string(reserved)) +
             ", which names the objects and lights that have no \"name\"";
  return "";
}

std::string parseObjectName(const JsonNode& n) {
  const std::string name = n.string();
  if (const std::string problem = objectNameProblem(name); !problem.empty()) n.fail(problem);
  return name;
}

namespace {

// "nodes[3]", "meshes[0]", "meshes[0]-1": glTF 2 ids of Assimp's, an element's array and index,
// which it gives to nodes and meshes without a name (a mesh's primitives after the first get
// "-P").
bool isGltfId(std::string_view name) {
  for (const std::string_view array : {"nodes[", "meshes["}) {
    if (name.substr(0, array.size()) != array) continue;
    size_t i = array.size();
    const size_t digits = i;
    while (i < name.size() && std::isdigit(static_cast<unsigned char>(name[i]))) ++i;
    if (i == digits || i >= name.size() || name[i] != ']') return false;
    ++i;
    if (i == name.size()) return true;
    if (name[i] != '-' || i + 1 == name.size()) return false;
    for (++i; i < name.size(); ++i)
      if (!std::isdigit(static_cast<unsigned char>(name[i]))) return false;
    return true;
  }
  return false;
}

}  // namespace

std::string fileGivenName(std::string_view name) {
  const bool madeUp = name.empty() || (name.front() == '<' && name.back() == '>') ||
                      name.find("$AssimpFbx$") != std::string_view::npos ||
                      name.substr(0, 17) == "$ColladaAutoName$" || isGltfId(name) ||
                      name == "defaultobject";
  return madeUp ? std::string() : std::string(name);
}

}  // namespace glint
