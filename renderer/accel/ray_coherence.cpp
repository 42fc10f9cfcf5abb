#include "accel/ray_coherence.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <optional>
#include <variant>

#include "core/seconds_since.h"

namespace glint {

namespace {

// Whether a ray that hits material `id` may send rays on from it (seed 002: the reflective and
// refractive objects are origins).
bool sendsRaysOn(const Scene& scene, uint32_t id) {
  const Material& m = scene.materials[id];
  return m.refracts() || m.surface.reflectsCoherently();
}

// Whether a world or group entry holds a surface that sends rays on (a CSG solid's operands, an
// instance's group and the groups inside it).
bool entrySendsRaysOn(const Scene& scene, const Geometry& g, int depth = 0) {
  switch (g.kind) {
    case GeomKind::Csg:
      for (const CsgLeaf& leaf : scene.csgs[g.index].leaves)
        if (sendsRaysOn(scene, leaf.materialId)) return true;
      return false;
    case GeomKind::Instance:
      // Nesting deeper than the loader allows cannot happen; the bound keeps a cycle finite.
      if (depth > 64) return true;
      for (const Geometry& inner : scene.groups[scene.instances[g.index].groupId].geometries)
        if (entrySendsRaysOn(scene, inner, depth + 1)) return true;
      return false;
    case GeomKind::Plane:
      return false;
    default:
      return sendsRaysOn(scene, g.materialId);
  }
}

double largestCoordinate(const Vec3f& p) {
  return std::max({std::fabs(double(p.x)), std::fabs(double(p.y)), std::fabs(double(p.z))});
}

}  // namespace

RayCoherence::RayCoherence(const Scene& scene, int resolution, size_t pairBudget, size_t wordBudget)
    : TwoLevelAccelerator(scene), classes_(resolution > 0 ? resolution : kMinResolution) {
  const auto start = std::chrono::steady_clock::now();
  // Instanced groups first (they follow their parents): an instance's box is its group's box.
  groupTrees_.resize(scene.groups.size());
  for (size_t g = scene.groups.size(); g-- > 0;)
    groupTrees_[g] = BoxTree(groupPrimitives(
        scene, uint32_t(g), [&](uint32_t child) { return groupTrees_[child].box(); }));

  // The world's entries, each bounded over the shutter by its primitives' boxes.
  const std::vector<Geometry>& world = scene.groups[0].geometries;
  std::vector<Bounds3f> entryBox(world.size());
  std::vector<std::vector<PrimitiveBox>> triangles(world.size());
  for (const PrimitiveBox& p : groupTrees_[0].primitives()) {
    entryBox[p.geom].extend(p.box);
    if (world[p.geom].kind == GeomKind::Mesh) triangles[p.geom].push_back(p);
  }
  std::vector<Shell> targets;
  std::vector<Shell> origins;
  struct Origin {
    enum { Eye, Light, Entry } kind;
    size_t index;
  };
  std::vector<Origin> originOf;
  double extent = largestCoordinate(scene.cameraDesc.eye);
  for (uint32_t gi = 0; gi < world.size(); ++gi) {
    const Geometry& g = world[gi];
    if (entryBox[gi].empty()) continue;
    extent =
        std::max({extent, largestCoordinate(entryBox[gi].lo), largestCoordinate(entryBox[gi].hi)});
    Object o;
    o.geom = gi;
    if (g.kind == GeomKind::Mesh) {
      o.tree = static_cast<int>(meshTrees_.size());
      meshTrees_.emplace_back(std::move(triangles[gi]));
    }
    objects_.push_back(o);
    const bool staticSphere = g.kind == GeomKind::Sphere && scene.sphereCenterKeys[g.index].empty();
    if (staticSphere) {
      targets.push_back(
          Shell::ofSphere(scene.spheres[g.index].center, scene.spheres[g.index].radius));
    } else if (g.kind == GeomKind::Quad) {
      const Quad& q = scene.quads[g.index];
      targets.push_back(Shell::ofPolygon(
          {q.corner, q.corner + q.edge1, q.corner + q.edge1 + q.edge2, q.corner + q.edge2}));
    } else {
      targets.push_back(Shell::ofBox(entryBox[gi]));
    }
  }

  // The origins in the order their rows are built: the eye, the lights, the objects.
  const CameraDesc& cam = scene.cameraDesc;
  if (cam.projection == Projection::Perspective) {
    // A square lens reaches √2 apertures from the eye.
    origins.push_back(Shell::ofSphere(cam.eye, cam.apertureRadius * std::sqrt(2.0f) * (1 + 1e-6f)));
    originOf.push_back({Origin::Eye, 0});
  }
  for (size_t k = 0; k < scene.lights.size(); ++k) {
    std::optional<Shell> shell;
    if (const auto* p = std::get_if<PointLight>(&scene.lights[k])) {
      shell = Shell::ofSphere(p->position, 0);
      extent = std::max(extent, largestCoordinate(p->position));
    } else if (const auto* q = std::get_if<QuadLight>(&scene.lights[k])) {
      Bounds3f b;
      for (const Vec3f& v : {q->corner(), q->corner() + q->edge1(), q->corner() + q->edge2(),
                             q->corner() + q->edge1() + q->edge2()})
        b.extend(v);
      shell = Shell::ofBox(b);
      extent = std::max({extent, largestCoordinate(b.lo), largestCoordinate(b.hi)});
    } else if (const auto* d = std::get_if<DiskLight>(&scene.lights[k])) {
      const Bounds3f b = bounds(Disk{d->center(), d->normal(), d->radius()});
      shell = Shell::ofBox(b);
      extent = std::max({extent, largestCoordinate(b.lo), largestCoordinate(b.hi)});
    }
    if (!shell) continue;
    origins.push_back(*shell);
    originOf.push_back({Origin::Light, k});
  }
  for (size_t i = 0; i < objects_.size(); ++i) {
    const Geometry& g = world[objects_[i].geom];
    if (!entrySendsRaysOn(scene, g)) continue;
    origins.push_back(targets[i].sphere ? targets[i] : Shell::ofBox(entryBox[objects_[i].geom]));
    originOf.push_back({Origin::Entry, objects_[i].geom});
  }
  pad_ = kRelativePad * std::max(extent, 1.0);
  if (resolution <= 0) classes_ = DirectionClasses(defaultResolution(objects_.size()));

  stats_.objects = objects_.size();
  stats_.origins = origins.size();
  stats_.classes = classes_.count();
  // A world past float's range gets no rows: every ray takes the fallback.
  if (std::isfinite(pad_)) buildRows(origins, targets, pairBudget, wordBudget);

  rowOfEntry_.assign(world.size(), -1);
  rowOfLight_.assign(scene.lights.size(), -1);
  for (size_t r = 0; r < rows_.size(); ++r) {
    const int row = static_cast<int>(r);
    switch (originOf[r].kind) {
      case Origin::Eye:
        eyeRow_ = row;
        break;
      case Origin::Light:
        rowOfLight_[originOf[r].index] = row;
        break;
      case Origin::Entry:
        rowOfEntry_[originOf[r].index] = row;
        break;
    }
  }
  stats_.rows = rows_.size();
  stats_.bytes = objects_.size() * sizeof(Object);
  for (const Row& r : rows_)
    stats_.bytes += (r.offsets.size() + r.objects.size()) * sizeof(uint32_t) +
                    r.nearest.size() * sizeof(float) + r.origin.vertices.size() * sizeof(Vec3d) +
                    sizeof(Row);
  for (const BoxTree& t : meshTrees_) stats_.bytes += t.bytes();
  for (const BoxTree& t : groupTrees_) stats_.bytes += t.bytes();
  stats_.buildSeconds = secondsSince(start);
}

void RayCoherence::buildRows(const std::vector<Shell>& origins, const std::vector<Shell>& targets,
                             size_t pairBudget, size_t wordBudget) {
  const size_t n = targets.size(), d = classes_.count();
  // Targets are done in blocks of at most this many, and of no more than the words left can
  // hold if each listed every class, so a row over budget is given up at most one target's
  // classes past it.
  constexpr size_t kBlock = 4096;
  size_t words = 0;
  for (const Shell& origin : origins) {
    if (stats_.pairs + n > pairBudget || words + d + 1 > wordBudget) return;
    stats_.pairs += n;
    std::vector<std::vector<uint32_t>> classesOf(n);
    size_t listed = 0;
    bool over = false;
    for (size_t begin = 0, end = 0; begin < n && !over; begin = end) {
      const size_t used = words + d + 1 + 2 * listed;
      const size_t room = wordBudget > used ? wordBudget - used : 0;
      end = std::min({n, begin + kBlock, begin + 1 + room / (2 * d)});
      tbb::parallel_for(begin, end, [&](size_t k) {
        const VisibilitySet set = visibilitySet(origin, targets[k], pad_);
        classes_.forEachClassMeeting(set, [&](uint32_t c) { classesOf[k].push_back(c); });
      });
      for (size_t k = begin; k < end; ++k) listed += classesOf[k].size();
      over = words + d + 1 + 2 * listed > wordBudget;
    }
    if (over) return;
    Row row;
    row.origin = origin;
    row.offsets.assign(d + 1, 0);
    for (const auto& cs : classesOf)
      for (uint32_t c : cs) ++row.offsets[c + 1];
    for (size_t c = 0; c < d; ++c) row.offsets[c + 1] += row.offsets[c];
    // Each list nearest first, so that a closest-hit query stops at the first object farther
    // than its hit (rounded down to float, so the bound stays a lower bound).
    std::vector<float> nearest(n);
    std::vector<uint32_t> order(n);
    for (uint32_t k = 0; k < n; ++k) {
      order[k] = k;
      nearest[k] = nextFloatDown(float(shellDistance(origin, targets[k], pad_)));
    }
    std::stable_sort(order.begin(), order.end(),
                     [&](uint32_t a, uint32_t b) { return nearest[a] < nearest[b]; });
    row.objects.resize(listed);
    row.nearest.resize(listed);
    std::vector<uint32_t> next(row.offsets.begin(), row.offsets.end() - 1);
    for (uint32_t k : order)
      for (uint32_t c : classesOf[k]) {
        row.nearest[next[c]] = std::max(0.0f, nearest[k]);
        row.objects[next[c]++] = k;
      }
    words += d + 1 + 2 * listed;
    stats_.references += listed;
    rows_.push_back(std::move(row));
  }
}

int RayCoherence::rowOf(const Ray& ray, bool& reversed) const {
  const uint32_t tag = ray.origin;
  reversed = false;
  if (tag == ray_origin::kNone) return -1;
  int row = -1;
  Vec3f from = ray.o;
  if (tag < ray_origin::kLightBit) {
    if (tag < rowOfEntry_.size()) row = rowOfEntry_[tag];
  } else if (tag == ray_origin::kEye) {
    row = eyeRow_;
  } else {
    const uint32_t k = tag & ~ray_origin::kLightBit;
    if (k < rowOfLight_.size() && ray.tMax <= 1) row = rowOfLight_[k];
    from = ray.o + ray.d;
    reversed = true;
  }
  if (row < 0) return -1;
  const Vec3f& d = ray.d;
  if (!(std::isfinite(d.x) && std::isfinite(d.y) && std::isfinite(d.z)) ||
      (d.x == 0 && d.y == 0 && d.z == 0))
    return -1;
  // Half the pad the sets were grown by: the rest covers the rounding of `from`.
  return rows_[size_t(row)].origin.holds(from, 0.5 * pad_) ? row : -1;
}

std::vector<uint32_t> RayCoherence::list(int row, uint32_t directionClass) const {
  const Row& r = rows_[size_t(row)];
  std::vector<uint32_t> out;
  for (uint32_t k = r.offsets[directionClass]; k < r.offsets[directionClass + 1]; ++k)
    out.push_back(objects_[r.objects[k]].geom);
  return out;
}

template <bool AnyHit, class Counter>
bool RayCoherence::inTree(const BoxTree& tree, uint32_t groupId, const Ray& ray, uint32_t instId,
                          Hit& hit, Counter count) const {
  return tree.traverse<AnyHit>(
      ray, hit,
      [&](const PrimitiveBox& p) {
        count.test();
        return intersectPrimitive(scene_, groupId, p.geom, p.prim, ray, instId, hit,
                                  intoInstance(count));
      },
      count);
}

template <bool AnyHit, class Counter>
bool RayCoherence::traverse(uint32_t groupId, const Ray& ray, uint32_t instId, Hit& hit,
                            Counter count) const {
  if (groupId != 0) return inTree<AnyHit>(groupTrees_[groupId], groupId, ray, instId, hit, count);
  bool reversed = false;
  const int row = rowOf(ray, reversed);
  if (row < 0) return inTree<AnyHit>(groupTrees_[0], 0, ray, instId, hit, count);
  count.step();
  const Row& r = rows_[size_t(row)];
  const uint32_t c = classes_.classOf(reversed ? -ray.d : ray.d);
  // Distances along the ray from its origin: a reversed row orders its lists from the light.
  const float length = reversed || AnyHit ? 0 : std::sqrt(dot(ray.d, ray.d));
  bool found = false;
  for (uint32_t k = r.offsets[c]; k < r.offsets[c + 1]; ++k) {
    // Every object left is at least r.nearest[k] away: none holds a closer hit. The product is
    // rounded up by a margin far above its rounding error.
    if (found && length > 0 && hit.t * length * (1 + 1e-5f) < r.nearest[k]) break;
    const Object& o = objects_[r.objects[k]];
    bool h;
    if (o.tree >= 0) {
      h = inTree<AnyHit>(meshTrees_[size_t(o.tree)], 0, ray, instId, hit, count);
    } else {
      count.test();
      h = intersectPrimitive(scene_, 0, o.geom, 0, ray, instId, hit, intoInstance(count));
    }
    if (h) {
      if constexpr (AnyHit) return true;
      found = true;
    }
  }
  return found;
}

}  // namespace glint
