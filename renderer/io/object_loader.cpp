// Turns entries of `objects` and `groups` into scene geometry. Triangle-based shapes (box,
// triangle, polygon, mesh) are baked into world (or group) space; analytic shapes keep their
// exact form; a sphere under a non-similarity transform becomes an implicit instance.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <optional>
#include <set>

#include "core/error.h"
#include "core/hash.h"
#include "core/input_files.h"
#include "core/unit_vector.h"
#include "geometry/tangents.h"
#include "geometry/triangulate.h"
#include "io/expansion_limits.h"
#include "io/local_mesh.h"
#include "io/mesh_io.h"
#include "io/mesh_limits.h"
#include "io/scene_builder.h"

namespace glint {

uint32_t materialOf(SceneBuilder& b, const JsonNode& obj) {
  const JsonNode n = obj.at("material");
  const std::string name = n.string();
  const auto it = b.materialIds.find(name);
  if (it != b.materialIds.end()) return it->second;
  std::vector<std::string> names;
  for (const auto& [k, v] : b.materialIds) names.push_back(k);
  const std::string hint = nearestName(name, names);
  n.fail("no material named " + inQuotes(name) +
         (hint.empty() ? "" : " (did you mean \"" + hint + "\"?)"));
}

uint32_t push(Scene& s, uint32_t groupId, GeomKind kind, uint32_t index, uint32_t material,
              uint32_t objectId) {
  auto& geoms = s.groups[groupId].geometries;
  geoms.push_back({kind, index, material, objectId});
  return static_cast<uint32_t>(geoms.size() - 1);
}

namespace {

void addMesh(SceneBuilder& b, const LocalMesh& local, const Placement& place, const JsonNode& where,
             uint32_t groupId, uint32_t material, uint32_t objectId) {
  const auto placed = [&](const std::vector<Vec3d>& points) {
    std::vector<Vec3f> out;
    out.reserve(points.size());
    for (const Vec3d& p : points) {
      if (!isFinite(toFloat(p))) where.fail("a vertex is not finite");
      out.push_back(place.point(p));
      if (!isFinite(out.back())) where.fail("a transformed vertex is not finite");
    }
    return out;
  };
  TriangleMesh mesh;
  mesh.indices = local.indices;
  mesh.uvs = local.uvs;
  mesh.uvs1 = local.uvs1;
  mesh.colors = local.colors;
  mesh.objectIds = local.objectIds;
  mesh.positions = placed(local.positions);
  for (const auto& key : local.positionKeys) mesh.positionKeys.push_back(placed(key));
  // Normals go through the inverse transpose, which keeps them outward under a mirroring
  // transform too. A deforming mesh is shaded flat: its normals would have to move with it.
  if (local.positionKeys.empty())
    for (const Vec3d& n : local.normals) {
      const Vec3f placedNormal = place.transform().normal(toFloat(n));
      const float len = length(placedNormal);
      // A zero normal cannot be interpolated; Scene::smoothNormal falls back to the triangle's
      // where the interpolated normal vanishes, so a zero stays zero.
      mesh.normals.push_back(len > 0 && std::isfinite(len) ? placedNormal / len : Vec3f{});
    }
  // The file's tangents go as directions; a mirroring transform turns the bitangent they
  // carry against normal × tangent (Scene::tangentFrame), so it flips their sign.
  const bool mirrors = place.transform().determinant() < 0;
  if (local.tangents.size() == local.indices.size())
    for (const TriangleMesh::Tangent& t : local.tangents) {
      const Vec3f placedTangent = place.transform().vector(t.direction);
      const float len = length(placedTangent);
      mesh.tangents.push_back({len > 0 && std::isfinite(len) ? placedTangent / len : Vec3f{},
                               mirrors ? -t.sign : t.sign});
    }
  // A mirroring transform (negative determinant) reverses the winding, which would turn the
  // geometric normals inward; swap two corners to keep them outward.
  if (mirrors)
    for (size_t i = 0; i < mesh.indices.size(); i += 3) {
      std::swap(mesh.indices[i + 1], mesh.indices[i + 2]);
      if (!mesh.tangents.empty()) std::swap(mesh.tangents[i + 1], mesh.tangents[i + 2]);
    }
  for (uint32_t idx : mesh.indices)
    if (idx >= mesh.positions.size())
      where.fail("index " + std::to_string(idx) + " is out of range (" +
                 std::to_string(mesh.positions.size()) + " vertices)");
  // Under a normal map, a mesh without tangents of its own gets glTF's (geometry/tangents.h).
  const std::shared_ptr<const ShadingMaps>& maps = b.scene.materials[material].surface.normalMaps;
  if (mesh.tangents.empty() && maps && maps->normal.image) mesh.tangents = generateTangents(mesh);
  if (!(maps && maps->normal.image)) mesh.tangents.clear();  // nothing reads them
  mesh.padForEmbree();
  b.scene.meshes.push_back(std::move(mesh));
  push(b.scene, groupId, GeomKind::Mesh, static_cast<uint32_t>(b.scene.meshes.size() - 1), material,
       objectId);
}

}  // namespace

std::vector<Vec3d> parsePoints(const JsonNode& n, size_t minCount) {
  if (!n.isArray() || n.size() < minCount)
    n.fail("must be an array of at least " + std::to_string(minCount) + " points");
  std::vector<Vec3d> out;
  for (const JsonNode& p : n.elements()) out.push_back(p.vec3d());
  return out;
}

LocalMesh boxMesh(const Vec3d& lo, const Vec3d& hi) {
  LocalMesh m;
  for (int c = 0; c < 8; ++c)
    m.positions.push_back({(c & 1) ? hi.x : lo.x, (c & 2) ? hi.y : lo.y, (c & 4) ? hi.z : lo.z});
  // Counter-clockwise seen from outside, so normals point out (dielectric boxes need that).
  m.indices = {0, 2, 1, 1, 2, 3, 4, 5, 6, 5, 7, 6, 0, 1, 4, 1, 5, 4,
               2, 6, 3, 3, 6, 7, 0, 4, 2, 2, 4, 6, 1, 3, 5, 3, 7, 5};
  return m;
}

LocalMesh inlineMesh(const JsonNode& obj) {
  LocalMesh m;
  m.positions = parsePoints(obj.at("positions"), 3);
  if (obj.has("normals")) {
    const JsonNode normals = obj.at("normals");
    m.normals = parsePoints(normals, 1);
    if (m.normals.size() != m.positions.size())
      normals.fail("has " + std::to_string(m.normals.size()) + " normals; the mesh has " +
                   std::to_string(m.positions.size()) + " positions (one normal per position)");
  }
  if (obj.has("uvs")) {
    const JsonNode uvs = obj.at("uvs");
    if (!uvs.isArray() || uvs.size() != m.positions.size())
      uvs.fail("must hold one [u, v] pair per position (" + std::to_string(m.positions.size()) +
               ")");
    for (const JsonNode& uv : uvs.elements()) {
      if (!uv.isArray() || uv.size() != 2) uv.fail("must be a pair [u, v]");
      m.uvs.push_back({uv[0].number(), uv[1].number()});
    }
  }
  const JsonNode idx = obj.at("indices");
  for (const JsonNode& tri : idx.elements()) {
    if (tri.size() != 3) tri.fail("must be a triple of vertex indices");
    for (const JsonNode& i : tri.elements()) {
      const int v = i.integer(0, std::numeric_limits<int>::max());
      if (static_cast<size_t>(v) >= m.positions.size())
        i.fail("index " + std::to_string(v) + " is out of range (" +
               std::to_string(m.positions.size()) + " positions)");
      m.indices.push_back(static_cast<uint32_t>(v));
    }
  }
  if (m.indices.empty()) idx.fail("must list at least one triangle");
  return m;
}

namespace {

// The bytes of the image files a mesh file's materials read join the scene hash, as the mesh
// file's own do (an image embedded in it is part of those already), so crops rendered after a
// texture changed are not merged with ones rendered before.
void hashTextureFiles(SceneBuilder& b, const std::vector<Material>& materials) {
  std::set<std::string> paths;
  for (const Material& m : materials) {
    const Surface& s = m.surface;
    for (const ColorTexture* t : {&s.ka, &s.kd, &s.ks, &s.km, &s.ke})
      if (t->image) paths.insert(t->image->path());
    if (m.cutout.image) paths.insert(m.cutout.image->path());
    if (s.normalMaps && s.normalMaps->normal.image)
      paths.insert(s.normalMaps->normal.image->path());
    if (s.normalMaps && s.normalMaps->bump.image) paths.insert(s.normalMaps->bump.image->path());
    if (s.maps)
      for (const auto* image : {s.maps->metallicRoughness.get(), s.maps->occlusion.get()})
        if (image) paths.insert(image->path());
  }
  for (const std::string& path : paths) {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec)) continue;  // embedded: "FILE#*0.png"
    std::ifstream in(path, std::ios::binary);
    b.scene.sourceHash = hashCombine(
        b.scene.sourceHash, hashBytes(std::string(std::istreambuf_iterator<char>(in), {})));
  }
}

}  // namespace

FileMesh fileMesh(SceneBuilder& b, const JsonNode& fileNode) {
  const std::filesystem::path rel(fileNode.string());
  const std::filesystem::path full =
      rel.is_absolute() ? rel : std::filesystem::path(b.baseDir) / rel;
  try {
    // Before anything reads it (the hash below): a device or FIFO would never end.
    checkInputFile(full.string(), kMaxMeshFileBytes, "mesh file");
    // The file's bytes join the scene hash, so crops rendered after the mesh changed are not
    // merged with ones rendered before.
    std::ifstream in(full, std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(in)), {});
    b.scene.sourceHash = hashCombine(b.scene.sourceHash, hashBytes(bytes));
    MeshFile loaded = loadMeshFile(full.lexically_normal().string());
    FileMesh out;
    for (const TriangleMesh& part : loaded.parts) {
      LocalMesh m;
      for (const Vec3f& p : part.positions) m.positions.push_back(toDouble(p));
      for (const Vec3f& n : part.normals) m.normals.push_back(toDouble(n));
      m.uvs = part.uvs;
      m.uvs1 = part.uvs1;
      m.colors = part.colors;
      m.tangents = part.tangents;
      m.indices = part.indices;
      m.objectIds = part.objectIds;
      out.parts.push_back(std::move(m));
    }
    out.objectNames = std::move(loaded.objectNames);
    hashTextureFiles(b, loaded.materials);
    out.materials = std::move(loaded.materials);
    return out;
  } catch (const OutOfMemoryError&) {
    throw;  // the machine's failure, not the file's
  } catch (const GlintError& e) {
    fileNode.fail(e.what());
  }
}

Affine parseTransform(const JsonNode& n) {
  n.checkKeys({"translate", "rotate", "scale", "matrix"});
  Affine t;
  if (auto m = n.get("matrix")) {
    if (n.has("translate") || n.has("rotate") || n.has("scale"))
      n.fail("\"matrix\" replaces translate/rotate/scale; give one or the other");
    if (m->size() != 16) m->fail("must hold 16 numbers (row-major 4×4)");
    std::array<double, 12> rows;
    for (size_t i = 0; i < 12; ++i) rows[i] = (*m)[i].real();
    for (size_t i = 12; i < 16; ++i)
      if ((*m)[i].real() != (i == 15 ? 1 : 0))
        m->fail("the last row must be [0, 0, 0, 1] (affine transforms only)");
    t = Affine::fromRows(rows);
  } else {
    if (auto s = n.get("scale")) {
      const Vec3d v = s->vec3d();
      if (v.x == 0 || v.y == 0 || v.z == 0) s->fail("scale factors must be non-zero");
      t = Affine::scale(v);
    }
    if (auto r = n.get("rotate")) {
      if (r->size() != 4) r->fail("must be [axis x, axis y, axis z, angle in degrees]");
      const Vec3d axis{(*r)[0].real(), (*r)[1].real(), (*r)[2].real()};
      if (!(axis.x != 0 || axis.y != 0 || axis.z != 0))
        r->fail("the rotation axis has zero length");
      t = Affine::rotate(axis, (*r)[3].real()) * t;
    }
    if (auto tr = n.get("translate")) t = Affine::translate(tr->vec3d()) * t;
  }
  try {
    t.toTransform();  // singular, or singular once rounded to float
  } catch (const std::invalid_argument& e) {
    (n.has("matrix") ? n.at("matrix") : n).fail(e.what());
  }
  return t;
}

namespace {

// A motion key: translate / rotate / scale only, since rotations are interpolated by slerp and a
// general matrix has no unique rotation to interpolate.
// `origin` shifts the translation into render space (io/placement.h).
TrsKey parseTrsKey(const JsonNode& n, const Vec3d& origin) {
  if (n.has("matrix"))
    n.at("matrix").fail(
        "motion keys take translate/rotate/scale (rotation is interpolated by "
        "slerp), not a matrix");
  n.checkKeys({"translate", "rotate", "scale"});
  TrsKey k;
  if (auto sc = n.get("scale")) {
    k.scale = sc->vec3();
    if (k.scale.x == 0 || k.scale.y == 0 || k.scale.z == 0)
      sc->fail("scale factors must be non-zero");
  }
  if (auto r = n.get("rotate")) {
    if (r->size() != 4) r->fail("must be [axis x, axis y, axis z, angle in degrees]");
    const Vec3f axis{(*r)[0].number(), (*r)[1].number(), (*r)[2].number()};
    if (!(length(axis) > 0)) r->fail("the rotation axis has zero length");
    k.rotation = Quat::fromAxisAngle(axis, (*r)[3].number());
  }
  k.translation = toFloat((n.has("translate") ? n.at("translate").vec3d() : Vec3d{}) - origin);
  try {
    (void)k.toTransform();  // singular once rounded to float (a scale of 1e-45)
  } catch (const std::invalid_argument& e) {
    (n.has("scale") ? n.at("scale") : n).fail(e.what());
  }
  return k;
}

// Keys that are all equal describe no motion: they come back as the one key, so the object is
// built static (no time steps, no time dimension) and renders exactly as if it had no keys —
// interpolating between equal keys in float would not always return the key itself.
// `animated`: the scene's animation resamples the keys to each frame's few (io/animation.h), so
// only a still scene's keys reach Embree as they are, at most kMaxMotionKeys of them.
template <typename T, typename Parse>
std::vector<T> parseKeys(const JsonNode& n, bool animated, Parse parse) {
  if (!n.isArray() || n.size() < 2)
    n.fail("must list at least 2 keys (spread evenly over normalised time [0, 1])");
  if (!animated && n.size() > kMaxMotionKeys)
    n.fail("lists " + std::to_string(n.size()) + " keys; an object may move through at most " +
           std::to_string(kMaxMotionKeys) + " in a frame (Embree's limit, " +
           "RTC_MAX_TIME_STEP_COUNT; an animation's keys are resampled for each frame)");
  std::vector<T> keys;
  for (const JsonNode& k : n.elements()) keys.push_back(parse(k));
  if (std::all_of(keys.begin(), keys.end(), [&](const T& k) { return k == keys[0]; }))
    keys.resize(1);
  return keys;
}

uint32_t addSphere(Scene& s, const Sphere& sphere, std::vector<Vec3f> centerKeys) {
  s.spheres.push_back(sphere);
  if (centerKeys.size() == 1) centerKeys.clear();  // equal keys: a sphere that does not move
  s.sphereCenterKeys.push_back(std::move(centerKeys));
  return static_cast<uint32_t>(s.spheres.size() - 1);
}

uint32_t newImplicitGroup(Scene& s, const std::string& what, uint32_t objectId) {
  s.groups.push_back({"<" + what + " " + s.objectName(objectId) + ">", {}});
  return static_cast<uint32_t>(s.groups.size() - 1);
}

// `placement` is the JSON node that places the instance, named by the error when its group's
// box, placed at any key, leaves the float range: Embree bounds an instance by that box, and
// with an infinite one it misses the instance silently while the reference BVH hits it.
void addInstance(SceneBuilder& b, uint32_t groupId, const Transform& xf, std::vector<TrsKey> motion,
                 uint32_t objectId, const JsonNode& placement) {
  Scene& s = b.scene;
  // One key (parseKeys collapsed equal keys): placed, not moving.
  Instance inst{groupId, motion.empty() ? xf : motion[0].toTransform(), std::move(motion)};
  if (inst.motion.size() == 1) inst.motion.clear();
  auto cached = b.groupBounds.find(groupId);
  if (cached == b.groupBounds.end())
    cached = b.groupBounds.emplace(groupId, s.groupBounds(groupId)).first;
  const Bounds3f& box = cached->second;
  const size_t keys = std::max<size_t>(1, inst.motion.size());
  for (size_t k = 0; k < keys && !box.empty(); ++k) {
    const Transform placed =
        inst.motion.empty() ? inst.worldFromObject : inst.motion[k].toTransform();
    // Corner by corner, not transformBox: a NaN corner (inf − inf) would vanish from a box.
    for (int c = 0; c < 8; ++c)
      if (!withinRayRange(placed.point(box.corner(c))))
        placement.fail(
            "the placed instance reaches past ±1e18 from the camera, beyond the range of rays "
            "Glint traces (or the float range)");
  }
  s.instances.push_back(std::move(inst));
  push(s, 0, GeomKind::Instance, static_cast<uint32_t>(s.instances.size() - 1), 0, objectId);
}

// Nested groups deeper than this are refused (a glTF node tree is a dozen levels).
constexpr size_t kMaxGroupNesting = 64;

// Places group `groupId` by `toRender` (its space → render space), moving by `motion` when
// given: a world-level instance of its own geometry, then, recursively, one for each instance
// it holds (SceneBuilder::nested), composed with its transform. `path`: the groups being placed
// around this one, which it must not hold (a cycle would place itself forever).
void placeGroup(SceneBuilder& b, uint32_t groupId, const Affine& toRender,
                std::vector<TrsKey> motion, uint32_t objectId, const JsonNode& where,
                std::vector<uint32_t>& path) {
  const std::string& name = b.scene.groups[groupId].name;
  if (std::find(path.begin(), path.end(), groupId) != path.end())
    where.fail("group " + inQuotes(name) + " holds an instance of itself");
  if (path.size() >= kMaxGroupNesting)
    where.fail("groups nest deeper than " + std::to_string(kMaxGroupNesting) + " levels");
  const auto nested = b.nested.find(groupId);
  if (nested != b.nested.end() && !motion.empty())
    where.fail("group " + inQuotes(name) +
               " holds instances, which a moving instance cannot place (nested groups are "
               "flattened with static transforms): move the instances inside it instead");
  Transform xf;
  try {
    xf = Placement(toRender).transform();
  } catch (const std::invalid_argument& e) {
    where.fail(e.what());
  }
  if (nested == b.nested.end() || !b.scene.groups[groupId].geometries.empty())
    addInstance(b, groupId, xf, std::move(motion), objectId, where);
  if (nested == b.nested.end()) return;
  path.push_back(groupId);
  for (const SceneBuilder::NestedInstance& n : nested->second)
    placeGroup(b, n.groupId, toRender * n.local, {}, objectId, n.where, path);
  path.pop_back();
}

// The world-level instances placeGroup creates for group `groupId`, counted from the nesting
// without placing any, each group's count kept (SceneBuilder::flattenedInstances): linear in
// the groups and their instances however many paths they have. A cycle or a nesting deeper
// than kMaxGroupNesting counts what lies before it; placeGroup then refuses the scene for it.
uint64_t flattenedInstances(SceneBuilder& b, uint32_t groupId, size_t depth) {
  if (const auto it = b.flattenedInstances.find(groupId); it != b.flattenedInstances.end())
    return it->second;
  const auto nested = b.nested.find(groupId);
  if (nested == b.nested.end()) return 1;
  if (depth >= kMaxGroupNesting) return 0;
  b.flattenedInstances[groupId] = 0;  // a cycle back to this group adds nothing
  uint64_t count = b.scene.groups[groupId].geometries.empty() ? 0 : 1;
  for (const SceneBuilder::NestedInstance& n : nested->second)
    count = saturatingAdd(count, flattenedInstances(b, n.groupId, depth + 1));
  return b.flattenedInstances[groupId] = count;
}

// Refuses, at `where`, an instance of `groupId` that would take the scene's world-level
// instances past kMaxFlattenedInstances, naming the groups through which most of them come.
void checkFlattenedInstances(SceneBuilder& b, uint32_t groupId, const JsonNode& where) {
  const uint64_t count = flattenedInstances(b, groupId, 0);
  const uint64_t placed = b.scene.instances.size();
  if (saturatingAdd(placed, count) <= kMaxFlattenedInstances) return;
  std::vector<std::string> names;
  std::vector<uint32_t> seen;
  for (uint32_t g = groupId;;) {
    names.push_back(inQuotes(b.scene.groups[g].name));
    seen.push_back(g);
    const auto nested = b.nested.find(g);
    if (nested == b.nested.end()) break;
    const auto most = std::max_element(
        nested->second.begin(), nested->second.end(), [&](const auto& x, const auto& y) {
          return flattenedInstances(b, x.groupId, 0) < flattenedInstances(b, y.groupId, 0);
        });
    if (std::find(seen.begin(), seen.end(), most->groupId) != seen.end()) break;
    g = most->groupId;
  }
  where.fail("this instance of group " + inQuotes(b.scene.groups[groupId].name) + " places " +
             countText(count) +
             " instances (each instance of a group places every instance it "
             "holds, so groups that place another twice double at each level)" +
             (placed ? " after the " + std::to_string(placed) + " already placed" : "") +
             ", more than the " + std::to_string(kMaxFlattenedInstances) +
             " a scene may have; most come through " + pathText(names));
}

// Turns the file's part names (LocalMesh::objectIds: indices into file.objectNames) into the
// object ids of a world-level object `objectId`: "PREFIX/PART" or "PART" (SceneBuilder::
// partPrefix), the object's own id for triangles without a name. A group's member keeps none.
void nameParts(SceneBuilder& b, FileMesh& file, uint32_t objectId) {
  if (!b.partPrefix || file.objectNames.empty()) {
    for (LocalMesh& part : file.parts) part.objectIds.clear();
    return;
  }
  std::vector<uint32_t> ids;
  for (const std::string& name : file.objectNames)
    ids.push_back(name.empty()            ? objectId
                  : b.partPrefix->empty() ? b.objectIdOf(name)
                                          : b.objectIdOf(*b.partPrefix + "/" + name));
  for (LocalMesh& part : file.parts)
    for (uint32_t& id : part.objectIds) id = ids[id];
}

// Adds a shape (not an instance) under `xf`; `motion` may hold "center" (spheres) or
// "positions" (meshes); "transform" motion has been taken care of by the caller.
void addShape(SceneBuilder& b, const JsonNode& obj, const std::string& type, uint32_t groupId,
              uint32_t objectId, const Placement& place, const std::optional<JsonNode>& motion) {
  const Transform& xf = place.transform();
  Scene& s = b.scene;
  if (motion && motion->has("center") && type != "sphere")
    motion->at("center").fail("only spheres have centre keys; use \"transform\" keys");
  if (motion && motion->has("positions") && type != "mesh")
    motion->at("positions").fail("only meshes have position keys; use \"transform\" keys");
  if (type == "csg") return addCsg(b, obj, groupId, objectId, place);
  // A mesh file without a "material" keeps the file's own materials.
  const bool fileMaterials = type == "mesh" && obj.has("file") && !obj.has("material");
  const uint32_t material = fileMaterials ? 0 : materialOf(b, obj);
  if (type == "sphere") {
    obj.checkKeys({"type", "name", "center", "radius", "material", "transform", "motion"});
    const float radius = obj.at("radius").number(0, 3.4e38f, true);
    const auto centersPlacedBy = [&](const Placement& p) {
      std::vector<Vec3f> keys;
      if (motion && motion->has("center"))
        keys = parseKeys<Vec3f>(motion->at("center"), b.scene.animation.has_value(),
                                [&](const JsonNode& k) { return p.point(k); });
      return keys;
    };
    float scale = 1;
    if (xf.isSimilarity(&scale)) {
      std::vector<Vec3f> centers = centersPlacedBy(place);
      const Sphere sp{centers.empty() ? place.point(obj.at("center")) : centers[0], radius * scale};
      bool finite = isFinite(sp.center) && std::isfinite(sp.radius);
      for (const Vec3f& c : centers) finite = finite && isFinite(c);
      if (!finite) obj.fail("the placed sphere is not finite (beyond the float range)");
      push(s, groupId, GeomKind::Sphere, addSphere(s, sp, std::move(centers)), material, objectId);
      return;
    }
    // An ellipsoid: keep the exact sphere in a group of its own, placed by an instance.
    if (groupId != 0)
      obj.at("transform").fail("a non-uniformly scaled sphere cannot sit inside a group");
    std::vector<Vec3f> centers = centersPlacedBy(Placement{});
    const Sphere sp{centers.empty() ? obj.at("center").vec3() : centers[0], radius};
    const uint32_t g = newImplicitGroup(s, "sphere", objectId);
    push(s, g, GeomKind::Sphere, addSphere(s, sp, std::move(centers)), material, objectId);
    addInstance(b, g, xf, {}, objectId, obj.at("transform"));
  } else if (type == "plane") {
    obj.checkKeys({"type", "name", "point", "normal", "material", "transform"});
    if (groupId != 0) obj.fail("planes are unbounded and cannot be placed in groups");
    const Vec3f n = obj.at("normal").direction();
    const Plane plane{place.point(obj.at("point")), unitVector(xf.normal(n))};
    if (!isFinite(plane.point) || !isFinite(plane.normal))
      obj.fail("the placed plane is not finite (beyond the float range)");
    s.planes.push_back(plane);
    s.planeGeometries.push_back(push(s, groupId, GeomKind::Plane,
                                     static_cast<uint32_t>(s.planes.size() - 1), material,
                                     objectId));
  } else if (type == "quad") {
    obj.checkKeys({"type", "name", "corner", "edge1", "edge2", "material", "transform", "motion"});
    Quad q{place.point(obj.at("corner")), xf.vector(obj.at("edge1").vec3()),
           xf.vector(obj.at("edge2").vec3())};
    // Under a mirroring transform edge1 × edge2 would point the other way: swap the edges (the
    // same parallelogram) so the normal is the transformed normal.
    if (xf.determinant() < 0) std::swap(q.edge1, q.edge2);
    if (!isFinite(q.corner) || !isFinite(q.edge1) || !isFinite(q.edge2))
      obj.fail("the placed quad is not finite (beyond the float range)");
    if (!(length(cross(q.edge1, q.edge2)) > 0))
      obj.fail("edge1 and edge2 must span a parallelogram (they are parallel or zero)");
    s.quads.push_back(q);
    push(s, groupId, GeomKind::Quad, static_cast<uint32_t>(s.quads.size() - 1), material, objectId);
  } else if (type == "box") {
    obj.checkKeys({"type", "name", "min", "max", "material", "transform", "motion"});
    const Vec3d lo = obj.at("min").vec3d(), hi = obj.at("max").vec3d();
    if (!(lo.x < hi.x && lo.y < hi.y && lo.z < hi.z))
      obj.at("max").fail("must exceed min in x, y and z");
    addMesh(b, boxMesh(lo, hi), place, obj, groupId, material, objectId);
  } else if (type == "triangle") {
    obj.checkKeys({"type", "name", "vertices", "material", "transform", "motion"});
    const JsonNode v = obj.at("vertices");
    if (v.size() != 3) v.fail("must hold exactly 3 points");
    LocalMesh m;
    m.positions = parsePoints(v, 3);
    m.indices = {0, 1, 2};
    addMesh(b, m, place, obj, groupId, material, objectId);
  } else if (type == "polygon") {
    obj.checkKeys({"type", "name", "vertices", "material", "transform", "motion"});
    const JsonNode v = obj.at("vertices");
    LocalMesh m;
    m.positions = parsePoints(v, 3);
    std::vector<Vec3f> outline;
    for (const Vec3d& p : m.positions) outline.push_back(toFloat(p));
    if (!triangulatePolygon(outline, m.indices))
      v.fail("cannot triangulate: the polygon is degenerate or self-intersecting");
    addMesh(b, m, place, obj, groupId, material, objectId);
  } else {  // mesh
    obj.checkKeys({"type", "name", "file", "positions", "normals", "uvs", "indices", "material",
                   "transform", "motion"});
    for (const char* key : {"normals", "uvs"})
      if (obj.has("file") && obj.has(key))
        obj.at(key).fail(std::string("a mesh from a file takes its ") + key +
                         " from the file; remove \"" + key + "\"");
    if (obj.has("file") == obj.has("positions"))
      obj.fail("a mesh needs either \"file\" or \"positions\" with \"indices\"");
    if (obj.has("file") && obj.has("indices"))
      obj.at("indices").fail(
          "a mesh from a file takes its triangles from the file; remove \"indices\"");
    FileMesh file;
    if (obj.has("file"))
      file = fileMesh(b, obj.at("file"));
    else
      file.parts.push_back(inlineMesh(obj));
    if (motion && motion->has("positions")) {
      // A deforming mesh (seed 000 §13.4.5): the same vertices at each key.
      const JsonNode keys = motion->at("positions");
      if (file.parts.size() > 1)
        keys.fail("the file's triangles use " + std::to_string(file.parts.size()) +
                  " materials; position keys need a mesh of one");
      LocalMesh& m = file.parts[0];
      m.positionKeys = parseKeys<std::vector<Vec3d>>(
          keys, b.scene.animation.has_value(), [&](const JsonNode& k) {
            std::vector<Vec3d> key = parsePoints(k, 3);
            if (key.size() != m.positions.size())
              k.fail("has " + std::to_string(key.size()) + " positions; the mesh has " +
                     std::to_string(m.positions.size()));
            return key;
          });
      m.positions = m.positionKeys[0];
      if (m.positionKeys.size() == 1) m.positionKeys.clear();  // equal keys: no deformation
    }
    nameParts(b, file, objectId);
    for (size_t i = 0; i < file.parts.size(); ++i) {
      uint32_t partMaterial = material;
      if (fileMaterials) {
        s.materials.push_back(file.materials[i]);
        partMaterial = static_cast<uint32_t>(s.materials.size() - 1);
      }
      const uint32_t partObject =
          file.parts[i].objectIds.empty() ? objectId : file.parts[i].objectIds[0];
      // A part of one object needs no table, except inside the implicit instance of a moving
      // object, whose hits count for the instance's object unless their triangles say.
      if (groupId == 0 &&
          std::all_of(file.parts[i].objectIds.begin(), file.parts[i].objectIds.end(),
                      [&](uint32_t id) { return id == partObject; }))
        file.parts[i].objectIds.clear();
      addMesh(b, file.parts[i], place, obj, groupId, partMaterial, partObject);
    }
  }
}

}  // namespace

void addObject(SceneBuilder& b, const JsonNode& obj, uint32_t groupId, uint32_t objectId) {
  Scene& s = b.scene;
  const std::string type = obj.at("type").choice(
      {"sphere", "plane", "quad", "box", "triangle", "polygon", "mesh", "csg", "instance"});
  const std::optional<JsonNode> motion = obj.get("motion");
  if (motion) motion->checkKeys({"center", "transform", "positions"});
  std::vector<TrsKey> transformKeys;
  if (motion && motion->has("transform")) {
    if (obj.has("transform"))
      obj.at("transform").fail("give either \"transform\" or \"motion.transform\", not both");
    if (type == "plane") motion->fail("planes are unbounded and cannot move");
    if (groupId != 0)
      motion->at("transform")
          .fail(
              "objects inside groups cannot carry transform keys: move the "
              "instance that places the group");
    transformKeys =
        parseKeys<TrsKey>(motion->at("transform"), s.animation.has_value(),
                          [&](const JsonNode& k) { return parseTrsKey(k, s.worldOrigin); });
  }
  const Placement place = [&] {
    const Affine local = obj.has("transform") ? parseTransform(obj.at("transform")) : Affine{};
    try {
      return Placement(b.placementOf(groupId, local));
    } catch (const std::invalid_argument& e) {
      obj.at("transform").fail(e.what());
    }
  }();

  if (type == "instance") {
    obj.checkKeys({"type", "name", "group", "transform", "motion"});
    if (motion && (motion->has("center") || motion->has("positions")))
      motion->fail("instances move by \"transform\" keys only");
    const JsonNode g = obj.at("group");
    const auto it = b.groupIds.find(g.string());
    if (it == b.groupIds.end()) {
      std::vector<std::string> names;
      for (const auto& [k, v] : b.groupIds) names.push_back(k);
      const std::string hint = nearestName(g.string(), names);
      g.fail("no group named " + inQuotes(g.string()) +
             (hint.empty() ? "" : " (did you mean \"" + hint + "\"?)"));
    }
    if (groupId != 0) {  // placed with the group that holds it
      b.nested[groupId].push_back({it->second, place.affine(), obj});
      return;
    }
    checkFlattenedInstances(b, it->second, obj);
    std::vector<uint32_t> path;
    placeGroup(b, it->second, place.affine(), std::move(transformKeys), objectId,
               motion && motion->has("transform") ? motion->at("transform")
               : obj.has("transform")             ? obj.at("transform")
                                                  : obj,
               path);
    return;
  }
  if (!transformKeys.empty()) {
    // Any shape with transform keys becomes an implicit instance that moves.
    const uint32_t g = newImplicitGroup(s, type, objectId);
    addShape(b, obj, type, g, objectId, Placement{}, motion);
    addInstance(b, g, Transform{}, std::move(transformKeys), objectId, motion->at("transform"));
    return;
  }
  const size_t before = s.groups[0].geometries.size();
  addShape(b, obj, type, groupId, objectId, place, motion);
  // What lies in the world (a group's contents are checked where an instance places them).
  for (size_t i = before; groupId == 0 && i < s.groups[0].geometries.size(); ++i) {
    const Bounds3f box = s.geometryBounds(s.groups[0].geometries[i]);
    if (!box.empty() && !(withinRayRange(box.lo) && withinRayRange(box.hi)))
      obj.fail("reaches past ±1e18 from the camera, beyond the range of rays Glint traces");
  }
}

}  // namespace glint
