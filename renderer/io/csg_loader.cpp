// "type": "csg" (seed 000 §13.3): a tree of union, intersection and difference nodes over
// spheres, boxes and closed meshes, read into one CsgSolid placed in render (or group) space.
#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <optional>
#include <stdexcept>

#include "core/error.h"
#include "io/local_mesh.h"
#include "io/scene_builder.h"

namespace glint {

namespace {

// Deeper trees than this are refused: every level is a recursion on every ray.
constexpr size_t kMaxCsgDepth = 64;
// Intervals thinner than this share of the solid's size and distance from the origin are taken
// for rounding (CsgSolid::thinness): about 60 float ulps of the coordinates.
constexpr float kThinShare = 0x1p-18f;

std::string pointText(const Vec3d& p) {
  return "(" + formatNumber(p.x) + ", " + formatNumber(p.y) + ", " + formatNumber(p.z) + ")";
}

class CsgReader {
 public:
  explicit CsgReader(SceneBuilder& b) : b_(b) {}

  // Node `obj` placed by `toSpace` (its own "transform" not yet applied unless `placed`), under
  // the material `imposed` by a node above (if any), subtracted an odd number of times when
  // `flipped`. Returns its node index.
  uint32_t node(const JsonNode& obj, const Affine& toSpace, bool placed,
                std::optional<uint32_t> imposed, bool flipped, size_t depth) {
    if (depth > kMaxCsgDepth)
      obj.fail("CSG nodes nest deeper than " + std::to_string(kMaxCsgDepth) + " levels");
    const std::string type =
        depth == 0 ? "csg" : obj.at("type").choice({"sphere", "box", "mesh", "csg"});
    Affine local = toSpace;
    if (!placed && obj.has("transform")) local = toSpace * parseTransform(obj.at("transform"));
    Placement place;
    try {
      place = Placement(local);
    } catch (const std::invalid_argument& e) {
      (obj.has("transform") ? obj.at("transform") : obj).fail(e.what());
    }
    if (type != "csg") return leaf(obj, type, place, imposed, flipped);

    if (depth > 0) obj.checkKeys({"type", "op", "operands", "material", "transform"});
    const std::string op = obj.at("op").choice({"union", "intersection", "difference"});
    // Checked even where a node above imposes its own: a misspelt name must not load silently.
    if (obj.has("material")) {
      const uint32_t named = solidMaterial(obj);
      if (!imposed) imposed = named;
    }
    const JsonNode operands = obj.at("operands");
    if (!operands.isArray() || operands.size() < 2)
      operands.fail("must list at least two operands (spheres, boxes, closed meshes or csg nodes)");
    const auto index = static_cast<uint32_t>(solid_.nodes.size());
    solid_.nodes.emplace_back();
    CsgNode n;
    n.op = op == "union"          ? CsgOp::Union
           : op == "intersection" ? CsgOp::Intersection
                                  : CsgOp::Difference;
    const std::vector<JsonNode> list = operands.elements();
    for (size_t k = 0; k < list.size(); ++k) {
      // The operands after a difference's first are subtracted: their surfaces face the other way.
      const bool subtracted = n.op == CsgOp::Difference && k > 0;
      n.operands.push_back(node(list[k], local, false, imposed, flipped != subtracted, depth + 1));
    }
    n.box = solid_.nodes[n.operands[0]].box;
    for (size_t k = 1; k < n.operands.size(); ++k) {
      const Bounds3f& o = solid_.nodes[n.operands[k]].box;
      if (n.op == CsgOp::Union) n.box.extend(o);
      if (n.op == CsgOp::Intersection) n.box = {max(n.box.lo, o.lo), min(n.box.hi, o.hi)};
    }
    if (n.box.empty())
      obj.fail("the intersection is empty: its operands' bounding boxes do not overlap");
    solid_.nodes[index] = std::move(n);
    return index;
  }

  CsgSolid finish() {
    const Bounds3f& box = solid_.box();
    const Vec3f reach = max(abs(box.lo), abs(box.hi));
    solid_.thinness = kThinShare * (length(box.diagonal()) + maxComponent(reach));
    solid_.buildMeshHierarchies();
    return std::move(solid_);
  }

 private:
  // The material of a node that names one: solid, without a cut-out.
  uint32_t solidMaterial(const JsonNode& obj) {
    const uint32_t m = materialOf(b_, obj);
    if (b_.scene.materials[m].cutout.active())
      obj.at("material")
          .fail(
              "has an opacity cut-out, which would open the solid; CSG operands need materials "
              "without one");
    return m;
  }

  uint32_t leaf(const JsonNode& obj, const std::string& type, const Placement& place,
                std::optional<uint32_t> imposed, bool flipped) {
    CsgLeaf l;
    l.flipped = flipped;
    Bounds3f box;
    if (type == "sphere") {
      obj.checkKeys({"type", "center", "radius", "material", "transform"});
      const float radius = obj.at("radius").number(0, 3.4e38f, true);
      float scale = 1;
      if (!place.transform().isSimilarity(&scale))
        (obj.has("transform") ? obj.at("transform") : obj)
            .fail(
                "places a CSG sphere by a non-uniform scale; CSG spheres take rotation, "
                "translation and uniform scale (an ellipsoid can be a closed mesh)");
      l.sphere = {place.point(obj.at("center")), radius * scale};
      if (!isFinite(l.sphere.center) || !std::isfinite(l.sphere.radius))
        obj.fail("the placed sphere is not finite (beyond the float range)");
      box = bounds(l.sphere);
    } else {
      l.isSphere = false;
      LocalMesh mesh;
      if (type == "box") {
        obj.checkKeys({"type", "min", "max", "material", "transform"});
        const Vec3d lo = obj.at("min").vec3d(), hi = obj.at("max").vec3d();
        if (!(lo.x < hi.x && lo.y < hi.y && lo.z < hi.z))
          obj.at("max").fail("must exceed min in x, y and z");
        mesh = boxMesh(lo, hi);
      } else {
        obj.checkKeys({"type", "file", "positions", "indices", "material", "transform"});
        if (obj.has("file") == obj.has("positions"))
          obj.fail("a mesh needs either \"file\" or \"positions\" with \"indices\"");
        mesh = obj.has("file") ? joinedParts(fileMesh(b_, obj.at("file"))) : inlineMesh(obj);
      }
      l.firstTriangle = static_cast<uint32_t>(solid_.triangles.size());
      closedTriangles(obj, mesh, place, box);
      l.triangleCount = static_cast<uint32_t>(solid_.triangles.size()) - l.firstTriangle;
    }
    const std::optional<uint32_t> named =
        obj.has("material") ? std::optional(solidMaterial(obj)) : std::nullopt;
    if (imposed) {
      l.materialId = *imposed;
    } else if (named) {
      l.materialId = *named;
    } else {
      obj.fail(
          "needs a \"material\" (or the csg node above it one): a mesh file's own materials "
          "are not used in CSG");
    }
    solid_.leaves.push_back(l);
    CsgNode n;
    n.leaf = static_cast<uint32_t>(solid_.leaves.size() - 1);
    n.box = box;
    solid_.nodes.push_back(std::move(n));
    return static_cast<uint32_t>(solid_.nodes.size() - 1);
  }

  static LocalMesh joinedParts(const FileMesh& file) {
    LocalMesh all;
    for (const LocalMesh& part : file.parts) {
      const auto offset = static_cast<uint32_t>(all.positions.size());
      all.positions.insert(all.positions.end(), part.positions.begin(), part.positions.end());
      for (uint32_t i : part.indices) all.indices.push_back(offset + i);
    }
    return all;
  }

  // Appends the mesh's triangles, placed, to the solid, wound so their normals point out of the
  // volume. Refuses a mesh that is not closed or not consistently wound: inside and outside
  // would not be defined. Vertices are matched by their placed position, so a file that splits
  // vertices along texture seams still closes.
  void closedTriangles(const JsonNode& obj, const LocalMesh& mesh, const Placement& place,
                       Bounds3f& box) {
    std::vector<Vec3f> points;
    for (const Vec3d& p : mesh.positions) {
      points.push_back(place.point(p));
      if (!isFinite(points.back())) obj.fail("a placed vertex is not finite");
    }
    std::map<std::array<float, 3>, uint32_t> welded;
    std::vector<uint32_t> firstIndex;  // per welded vertex, a vertex of the mesh at its place
    const auto weld = [&](uint32_t i) {
      const Vec3f& p = points[i];
      const auto [it, added] =
          welded.emplace(std::array<float, 3>{p.x, p.y, p.z}, uint32_t(welded.size()));
      if (added) firstIndex.push_back(i);
      return it->second;
    };
    std::map<std::pair<uint32_t, uint32_t>, int> edges;  // directed, with their counts
    std::vector<std::array<Vec3f, 3>> tris;
    double volume = 0;
    for (size_t i = 0; i + 2 < mesh.indices.size(); i += 3) {
      const std::array<uint32_t, 3> v{weld(mesh.indices[i]), weld(mesh.indices[i + 1]),
                                      weld(mesh.indices[i + 2])};
      const std::array<Vec3f, 3> p{points[mesh.indices[i]], points[mesh.indices[i + 1]],
                                   points[mesh.indices[i + 2]]};
      // A triangle without area bounds nothing and no ray crosses it.
      if (v[0] == v[1] || v[1] == v[2] || v[0] == v[2] ||
          length(cross(p[1] - p[0], p[2] - p[0])) == 0)
        continue;
      for (int e = 0; e < 3; ++e) ++edges[{v[e], v[(e + 1) % 3]}];
      // The signed volume of the tetrahedron to the origin, in double: the sum over a closed
      // surface is its enclosed volume, positive when the triangles wind outward.
      const Vec3d a = toDouble(p[0]), b = toDouble(p[1]), c = toDouble(p[2]);
      volume += (a.x * (b.y * c.z - b.z * c.y) + a.y * (b.z * c.x - b.x * c.z) +
                 a.z * (b.x * c.y - b.y * c.x)) /
                6;
      tris.push_back(p);
      for (const Vec3f& q : p) box.extend(q);
    }
    // Errors name points as the file gives them, before any transform.
    const auto point = [&](uint32_t id) { return pointText(mesh.positions[firstIndex[id]]); };
    for (const auto& [edge, count] : edges) {
      const auto back = edges.find({edge.second, edge.first});
      const int opposite = back == edges.end() ? 0 : back->second;
      if (opposite == count) continue;
      const std::string where = "the edge from " + point(edge.first) + " to " + point(edge.second);
      if (opposite == 0 && count == 1)
        obj.fail("is not a closed surface: " + where +
                 " borders one triangle; CSG needs closed meshes");
      obj.fail("is not consistently wound: the triangles along " + where + " cross it " +
               std::to_string(count) + " times that way and " + std::to_string(opposite) +
               " times the other; CSG needs a closed mesh whose triangles all wind alike");
    }
    if (tris.empty() || !(std::fabs(volume) > 0)) obj.fail("encloses no volume");
    for (auto& p : tris) {
      if (volume < 0) std::swap(p[1], p[2]);  // wound inward: turn every normal out
      solid_.triangles.push_back(p);
    }
  }

  SceneBuilder& b_;
  CsgSolid solid_;
};

}  // namespace

void addCsg(SceneBuilder& b, const JsonNode& obj, uint32_t groupId, uint32_t objectId,
            const Placement& place) {
  obj.checkKeys({"type", "name", "op", "operands", "material", "transform", "motion"});
  CsgReader reader(b);
  reader.node(obj, place.affine(), true, std::nullopt, false, 0);
  CsgSolid solid = reader.finish();
  const uint32_t material = solid.leaves[0].materialId;  // the solid's own surfaces carry theirs
  b.scene.csgs.push_back(std::move(solid));
  push(b.scene, groupId, GeomKind::Csg, static_cast<uint32_t>(b.scene.csgs.size() - 1), material,
       objectId);
}

}  // namespace glint
