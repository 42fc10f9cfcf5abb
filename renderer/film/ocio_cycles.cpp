#include "film/ocio_cycles.h"

#include <map>
#include <utility>
#include <vector>

#include "core/error.h"

namespace OCIO = OCIO_NAMESPACE;

namespace glint {

namespace {

// A node of the reference graph: a kind ("colour space", "look", ...) and the config's name.
using Node = std::pair<std::string, std::string>;

class ReferenceGraph {
 public:
  explicit ReferenceGraph(const OCIO::ConstConfigRcPtr& config) : config_(config) {}

  void addColorSpaces() {
    const auto search = OCIO::SEARCH_REFERENCE_SPACE_ALL;
    for (int i = 0; i < config_->getNumColorSpaces(search, OCIO::COLORSPACE_ALL); ++i) {
      const char* name = config_->getColorSpaceNameByIndex(search, OCIO::COLORSPACE_ALL, i);
      const auto space = config_->getColorSpace(name);
      if (!space) continue;
      const Node from{"colour space", space->getName()};
      edges_[from];
      for (const auto dir :
           {OCIO::COLORSPACE_DIR_TO_REFERENCE, OCIO::COLORSPACE_DIR_FROM_REFERENCE})
        addTransform(from, space->getTransform(dir));
    }
  }

  void addLooks() {
    for (int i = 0; i < config_->getNumLooks(); ++i) {
      const auto look = config_->getLook(config_->getLookNameByIndex(i));
      if (!look) continue;
      const Node from{"look", look->getName()};
      edges_[from];
      addSpace(from, look->getProcessSpace());
      addTransform(from, look->getTransform());
      addTransform(from, look->getInverseTransform());
    }
  }

  void addViewAndNamedTransforms() {
    for (int i = 0; i < config_->getNumViewTransforms(); ++i) {
      const auto view = config_->getViewTransform(config_->getViewTransformNameByIndex(i));
      if (!view) continue;
      const Node from{"view transform", view->getName()};
      edges_[from];
      for (const auto dir :
           {OCIO::VIEWTRANSFORM_DIR_TO_REFERENCE, OCIO::VIEWTRANSFORM_DIR_FROM_REFERENCE})
        addTransform(from, view->getTransform(dir));
    }
    for (int i = 0; i < config_->getNumNamedTransforms(OCIO::NAMEDTRANSFORM_ALL); ++i) {
      const auto named = config_->getNamedTransform(
          config_->getNamedTransformNameByIndex(OCIO::NAMEDTRANSFORM_ALL, i));
      if (!named) continue;
      const Node from{"named transform", named->getName()};
      edges_[from];
      for (const auto dir : {OCIO::TRANSFORM_DIR_FORWARD, OCIO::TRANSFORM_DIR_INVERSE})
        addTransform(from, named->getTransform(dir));
    }
  }

  // The first loop found, as the nodes round it (the first repeated at the end); empty if none.
  std::vector<Node> loop() const {
    enum class Mark { Unseen, OnPath, Done };
    std::map<Node, Mark> mark;
    for (const auto& [start, unused] : edges_) {
      if (mark[start] != Mark::Unseen) continue;
      // Depth first without recursion (a long chain must not overflow the stack either): the
      // path and, for each node on it, the next of its edges to follow.
      std::vector<std::pair<Node, size_t>> path{{start, 0}};
      mark[start] = Mark::OnPath;
      while (!path.empty()) {
        const Node node = path.back().first;  // a copy: the path may grow below
        const std::vector<Node>& out = edges_.at(node);
        const size_t next = path.back().second++;
        if (next == out.size()) {
          mark[node] = Mark::Done;
          path.pop_back();
          continue;
        }
        const Node& to = out[next];
        const Mark m = mark[to];
        if (m == Mark::OnPath) {
          std::vector<Node> loop;
          size_t k = 0;
          while (path[k].first != to) ++k;
          for (; k < path.size(); ++k) loop.push_back(path[k].first);
          loop.push_back(to);
          return loop;
        }
        if (m == Mark::Unseen && edges_.count(to)) {
          mark[to] = Mark::OnPath;
          path.emplace_back(to, 0);
        }
      }
    }
    return {};
  }

 private:
  void addEdge(const Node& from, const Node& to) { edges_[from].push_back(to); }

  // A name a transform's end gives: a colour space (a role or an alias resolved to its name)
  // or a named transform; names the config does not know are OCIO's to report.
  void addSpace(const Node& from, const char* name) {
    if (!name || !*name) return;
    if (const auto space = config_->getColorSpace(name))
      addEdge(from, {"colour space", space->getName()});
    else if (const auto named = config_->getNamedTransform(name))
      addEdge(from, {"named transform", named->getName()});
  }

  // Looks as OCIO writes them: names separated by ',' or ':', each perhaps led by '+' or '-'.
  void addLooks(const Node& from, const char* looks) {
    if (!looks) return;
    std::string name;
    const auto flush = [&] {
      const size_t begin = name.find_first_not_of(" \t+-");
      const size_t end = name.find_last_not_of(" \t");
      if (begin != std::string::npos) {
        const auto look = config_->getLook(name.substr(begin, end - begin + 1).c_str());
        if (look) addEdge(from, {"look", look->getName()});
      }
      name.clear();
    };
    for (const char* c = looks; *c; ++c) {
      if (*c == ',' || *c == ':' || *c == '|')
        flush();
      else
        name += *c;
    }
    flush();
  }

  void addTransform(const Node& from, const OCIO::ConstTransformRcPtr& t) {
    if (!t) return;
    if (const auto group = OCIO::DynamicPtrCast<const OCIO::GroupTransform>(t)) {
      for (int i = 0; i < group->getNumTransforms(); ++i)
        addTransform(from, group->getTransform(i));
    } else if (const auto cs = OCIO::DynamicPtrCast<const OCIO::ColorSpaceTransform>(t)) {
      addSpace(from, cs->getSrc());
      addSpace(from, cs->getDst());
    } else if (const auto lt = OCIO::DynamicPtrCast<const OCIO::LookTransform>(t)) {
      addSpace(from, lt->getSrc());
      addSpace(from, lt->getDst());
      addLooks(from, lt->getLooks());
    } else if (const auto dv = OCIO::DynamicPtrCast<const OCIO::DisplayViewTransform>(t)) {
      addSpace(from, dv->getSrc());
      const char *display = dv->getDisplay(), *view = dv->getView();
      if (!display || !view) return;
      addSpace(from, config_->getDisplayViewColorSpaceName(display, view));
      addLooks(from, config_->getDisplayViewLooks(display, view));
      const char* viewTransform = config_->getDisplayViewTransformName(display, view);
      if (viewTransform && *viewTransform && config_->getViewTransform(viewTransform))
        addEdge(from, {"view transform", viewTransform});
    }
  }

  const OCIO::ConstConfigRcPtr& config_;
  std::map<Node, std::vector<Node>> edges_;
};

}  // namespace

void checkOcioReferenceCycles(const OCIO::ConstConfigRcPtr& config, const std::string& source) {
  ReferenceGraph graph(config);
  graph.addColorSpaces();
  graph.addLooks();
  graph.addViewAndNamedTransforms();
  const std::vector<Node> loop = graph.loop();
  if (loop.empty()) return;
  std::string path;
  for (const Node& n : loop)
    path += (path.empty() ? "" : " → ") + n.first + " " + inQuotes(n.second);
  throw UsageError("OCIO (" + source + "): " + path +
                   ": these refer to each other in a loop, which OCIO would follow until its "
                   "stack overflows");
}

}  // namespace glint
