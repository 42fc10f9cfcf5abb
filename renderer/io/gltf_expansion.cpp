#include "io/gltf_expansion.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <vector>

#include "core/error.h"
#include "io/expansion_limits.h"

namespace glint {

namespace {

using nlohmann::json;

// A count below one node, copies and all: the node copies and the triangles they place.
struct Copies {
  uint64_t nodes = 0, triangles = 0;
  void add(const Copies& o) {
    nodes = saturatingAdd(nodes, o.nodes);
    triangles = saturatingAdd(triangles, o.triangles);
  }
};

class Counter {
 public:
  Counter(const std::string& path, const json& doc) : path_(path), doc_(doc) {
    const auto n = doc.find("nodes");
    if (n != doc.end() && n->is_array()) nodes_ = &*n;
    const size_t count = nodes_ ? nodes_->size() : 0;
    state_.assign(count, State::Unvisited);
    below_.resize(count);
    height_.assign(count, 0);
  }

  size_t nodeCount() const { return state_.size(); }

  // The copies below `roots` (a scene's nodes, in order, repeats counted); throws as the header
  // says.
  void checkScene(const std::vector<size_t>& roots, const std::string& sceneName) {
    Copies total;
    for (size_t r : roots) total.add(visit(r, 0, sceneName + ".nodes"));
    const bool tooManyNodes = total.nodes > kMaxFlattenedInstances;
    if (!tooManyNodes && total.triangles <= kMaxFlattenedTriangles) return;
    // The path through which most copies come: at each node the child below which most lie.
    const auto weight = [&](size_t i) {
      return tooManyNodes ? below_[i].nodes : below_[i].triangles;
    };
    std::vector<std::string> names;
    size_t at = *std::max_element(roots.begin(), roots.end(),
                                  [&](size_t a, size_t b) { return weight(a) < weight(b); });
    for (;;) {
      names.push_back("nodes[" + std::to_string(at) + "]");
      const std::vector<size_t> children = childrenOf(at, "");
      if (children.empty()) break;
      at = *std::max_element(children.begin(), children.end(),
                             [&](size_t a, size_t b) { return weight(a) < weight(b); });
    }
    throw UsageError("glTF " + path_ + ": " + sceneName + " flattens to " +
                     (tooManyNodes ? countText(total.nodes) + " node copies, more than the " +
                                         std::to_string(kMaxFlattenedInstances)
                                   : countText(total.triangles) + " triangles, more than the " +
                                         std::to_string(kMaxFlattenedTriangles)) +
                     " Glint places (a node that is the child of several parents, or listed "
                     "twice, is placed once per path to it); most come through " +
                     pathText(names));
  }

 private:
  enum class State { Unvisited, OnPath, Done };

  [[noreturn]] void fail(const std::string& what) const {
    throw UsageError("glTF " + path_ + ": " + what);
  }

  std::vector<size_t> childrenOf(size_t i, const std::string& where) const {
    std::vector<size_t> out;
    const json& node = (*nodes_)[i];
    if (!node.is_object()) return out;
    const auto c = node.find("children");
    if (c == node.end()) return out;
    if (!c->is_array()) fail(where + ".children is not an array");
    for (const json& child : *c) {
      if (!child.is_number_unsigned()) fail(where + ".children holds a value that is not an index");
      out.push_back(child.get<size_t>());
    }
    return out;
  }

  // The triangles one copy of the node's mesh places.
  uint64_t trianglesOfMesh(const json& node) const {
    const auto m = node.find("mesh");
    const auto meshes = doc_.find("meshes");
    if (m == node.end() || !m->is_number_unsigned() || meshes == doc_.end() ||
        !meshes->is_array() || m->get<size_t>() >= meshes->size())
      return 0;  // Assimp refuses a mesh index out of range
    const json& mesh = (*meshes)[m->get<size_t>()];
    const auto primitives = mesh.is_object() ? mesh.find("primitives") : mesh.end();
    if (!mesh.is_object() || primitives == mesh.end() || !primitives->is_array()) return 0;
    const auto accessors = doc_.find("accessors");
    const auto countOf = [&](const json& index) -> uint64_t {
      if (!index.is_number_unsigned() || accessors == doc_.end() || !accessors->is_array() ||
          index.get<size_t>() >= accessors->size())
        return 0;
      const json& a = (*accessors)[index.get<size_t>()];
      const auto count = a.is_object() ? a.find("count") : a.end();
      return a.is_object() && count != a.end() && count->is_number_unsigned()
                 ? count->get<uint64_t>()
                 : 0;
    };
    uint64_t triangles = 0;
    for (const json& p : *primitives) {
      if (!p.is_object()) continue;
      uint64_t vertices = 0;
      if (const auto indices = p.find("indices"); indices != p.end())
        vertices = countOf(*indices);
      else if (const auto a = p.find("attributes"); a != p.end() && a->is_object())
        if (const auto position = a->find("POSITION"); position != a->end())
          vertices = countOf(*position);
      const auto mode = p.find("mode");
      const bool list = mode == p.end() || !mode->is_number_integer() || *mode == 4;
      triangles = saturatingAdd(triangles, list ? vertices / 3 : vertices > 2 ? vertices - 2 : 0);
    }
    return triangles;
  }

  // The copies below node `i` (itself included), each node's counted once and reused: the graph
  // is walked in time linear in its nodes and edges however many paths it has.
  const Copies& visit(size_t i, int depth, const std::string& parent) {
    const std::string where = "nodes[" + std::to_string(i) + "]";
    if (!nodes_ || i >= nodes_->size())
      fail(parent + " names " + where + ", which does not exist (" + std::to_string(nodeCount()) +
           " nodes)");
    if (state_[i] == State::OnPath)
      fail(where + " is its own ancestor (the node tree has a cycle)");
    if (depth + height_[i] > kMaxGltfNodeDepth || depth > kMaxGltfNodeDepth)
      fail("the node tree is deeper than " + std::to_string(kMaxGltfNodeDepth) + " levels");
    if (state_[i] == State::Done) return below_[i];
    state_[i] = State::OnPath;
    Copies c{1, trianglesOfMesh((*nodes_)[i])};
    int height = 0;
    for (size_t child : childrenOf(i, where)) {
      c.add(visit(child, depth + 1, where + ".children"));
      height = std::max(height, 1 + height_[child]);
    }
    state_[i] = State::Done;
    height_[i] = height;
    below_[i] = c;
    return below_[i];
  }

  const std::string& path_;
  const json& doc_;
  const json* nodes_ = nullptr;
  std::vector<State> state_;
  std::vector<Copies> below_;
  std::vector<int> height_;  // the longest path of children below each node
};

}  // namespace

void checkGltfExpansion(const std::string& path, const json& doc) {
  Counter counter(path, doc);
  if (counter.nodeCount() == 0) return;
  const json& nodes = doc["nodes"];
  // Each scene, as a reader shows one of them.
  if (const auto scenes = doc.find("scenes"); scenes != doc.end() && scenes->is_array())
    for (size_t s = 0; s < scenes->size(); ++s) {
      const json& scene = (*scenes)[s];
      const auto n = scene.is_object() ? scene.find("nodes") : scene.end();
      if (!scene.is_object() || n == scene.end() || !n->is_array()) continue;
      std::vector<size_t> roots;
      for (const json& r : *n)
        if (r.is_number_unsigned()) roots.push_back(r.get<size_t>());
      if (!roots.empty()) counter.checkScene(roots, "scenes[" + std::to_string(s) + "]");
    }
  // The nodes without a parent, which a file without scenes shows (io/gltf_scene.cpp).
  std::vector<bool> isChild(nodes.size());
  for (const json& node : nodes)
    if (const auto c = node.is_object() ? node.find("children") : node.end();
        node.is_object() && c != node.end() && c->is_array())
      for (const json& i : *c)
        if (i.is_number_unsigned() && i.get<size_t>() < isChild.size())
          isChild[i.get<size_t>()] = true;
  std::vector<size_t> roots;
  for (size_t i = 0; i < nodes.size(); ++i)
    if (!isChild[i]) roots.push_back(i);
  if (!roots.empty()) counter.checkScene(roots, "the nodes without a parent");
}

}  // namespace glint
