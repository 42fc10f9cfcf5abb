#include "accel/ray_classification.h"

#include <algorithm>
#include <cmath>

namespace glint {

namespace {

// The narrowest w_min taken: about 5·log₂(2/w) levels of cells, so 100 at most.
constexpr double kNarrowestWMin = 1e-6;
// The rounding pad of the beam test: each cell's origin box grows by this share of E's side
// (plus a relative 10⁻⁶ of E's coordinates), and its direction rectangle by this much in (u, v),
// before an object's box is tested against its beam. It covers the rounding of the ray's
// classification (its entry point, (u, v)) and of the shared intersection tests, which may
// report a hit for a ray passing a hair outside the object's box.
constexpr double kPad = 1e-4;

// The five coordinates of a ray: its entry point in E scaled to [0, 1]³, then (u, v) in [−1, 1]².
constexpr int kDims = 5;
constexpr double kRootLo[kDims] = {0, 0, 0, -1, -1};
constexpr double kRootWidth[kDims] = {1, 1, 1, 2, 2};

// The longest axis of a cell, the first of equals.
int longestAxis(const double* w) {
  int axis = 0;
  for (int k = 1; k < kDims; ++k)
    if (w[k] > w[axis]) axis = k;
  return axis;
}

// The rays of a cell in the space of its group: origins in the box [lo, hi], directions
// ±x_a + u·x_b + v·x_c (b, c the axes after a) with u, v in [dLo, dHi].
struct Beam {
  int a = 0;
  bool negative = false;
  double lo[3], hi[3], dLo[2], dHi[2];
};

// Whether `box` may meet the beam: over the distances s along the dominant axis at which the
// beam crosses the box's slab in that axis, the beam's extent in each other axis (o + u·s with
// o and u in intervals and s ≥ 0: bounded by its values at the two ends of the range of s)
// must overlap the box's. Never false when some ray of the beam meets the box.
bool meets(const Beam& beam, const Bounds3f& box) {
  const int a = beam.a;
  double sLo, sHi;
  if (beam.negative) {
    sLo = beam.lo[a] - double(box.hi[a]);
    sHi = beam.hi[a] - double(box.lo[a]);
  } else {
    sLo = double(box.lo[a]) - beam.hi[a];
    sHi = double(box.hi[a]) - beam.lo[a];
  }
  if (sHi < 0) return false;  // the box lies behind every origin
  sLo = std::max(sLo, 0.0);
  for (int j = 0; j < 2; ++j) {
    const int k = (a + 1 + j) % 3;
    const double lo = beam.lo[k] + std::min(beam.dLo[j] * sLo, beam.dLo[j] * sHi);
    const double hi = beam.hi[k] + std::max(beam.dHi[j] * sLo, beam.dHi[j] * sHi);
    if (hi < double(box.lo[k]) || lo > double(box.hi[k])) return false;
  }
  return true;
}

}  // namespace

struct RayClassification::Cell {
  std::unique_ptr<uint32_t[]> own;  // the list's storage (a root's is its group's `all`)
  const uint32_t* refs = nullptr;   // the candidate list, ascending
  uint32_t count = 0;
  // The halves below and above the middle of the cell's longest axis, each made when a ray first
  // needs it and published once, by the thread that won the race to make it; `closed`: that
  // half was wanted past the memory cap, and this cell answers for it for good.
  std::atomic<Cell*> child[2] = {nullptr, nullptr};
  std::atomic<bool> closed[2] = {false, false};
  ~Cell() {
    for (auto& c : child) delete c.load(std::memory_order_relaxed);
  }
};

struct RayClassification::Hyperset {
  std::vector<PrimitiveBox> prims;
  Bounds3f box;              // of the prims
  double lo[3] = {0, 0, 0};  // the cube E: [lo, lo + side]³
  double side = 0, pad = 0;  // pad: the origin box's rounding pad
  bool classifies = false;   // E is a finite cube of some size
  std::vector<uint32_t> all;
  Cell roots[6];  // faces +x, −x, +y, −y, +z, −z
};

size_t RayClassification::defaultCapBytes(size_t primitives) {
  return (size_t(256) << 20) + size_t(sizeof(uint32_t) * referenceBudget(primitives));
}

RayClassification::RayClassification(const Scene& scene, const RayClassSettings& settings)
    : TwoLevelAccelerator(scene), settings_(settings) {
  settings_.wMin = std::max(settings_.wMin, kNarrowestWMin);
  sets_.resize(scene.groups.size());
  size_t primitives = 0;
  // Instanced groups first (they follow their parents): an instance's box is its group's box.
  for (size_t g = scene.groups.size(); g-- > 0;) {
    auto h = std::make_unique<Hyperset>();
    h->prims = groupPrimitives(scene, uint32_t(g), [&](uint32_t child) {
      return sets_[child] ? sets_[child]->box : Bounds3f{};
    });
    for (const PrimitiveBox& p : h->prims) h->box.extend(p.box);
    h->all.resize(h->prims.size());
    for (uint32_t i = 0; i < h->all.size(); ++i) h->all[i] = i;
    for (Cell& root : h->roots) {
      root.refs = h->all.data();
      root.count = uint32_t(h->all.size());
    }
    if (!h->prims.empty()) {
      double extent = 0, largest = 0;
      for (int a = 0; a < 3; ++a) extent = std::max(extent, double(h->box.hi[a]) - h->box.lo[a]);
      // A hair larger than the box, so that no box touches E's faces.
      h->side = extent * (1 + 1e-5);
      for (int a = 0; a < 3; ++a) {
        h->lo[a] = 0.5 * (double(h->box.lo[a]) + h->box.hi[a]) - 0.5 * h->side;
        largest = std::max({largest, std::fabs(h->lo[a]), std::fabs(h->lo[a] + h->side)});
      }
      h->classifies = h->side > 0 && std::isfinite(h->side) && std::isfinite(largest);
      h->pad = kPad * h->side + 1e-6 * largest;
    }
    primitives += h->prims.size();
    sets_[g] = std::move(h);
  }
  capBytes_ = settings_.capBytes ? settings_.capBytes : defaultCapBytes(primitives);
  testBudget_ =
      settings_.testBudget ? settings_.testBudget : size_t(256 * referenceBudget(primitives));
}

RayClassification::~RayClassification() = default;

RayClassStats RayClassification::stats() const {
  RayClassStats s;
  s.cells = cells_.load();
  s.references = references_.load();
  s.lazyBytes = lazyBytes_.load();
  s.capBytes = capBytes_;
  s.beamTests = beamTests_.load();
  s.testBudget = testBudget_;
  for (const auto& h : sets_) {
    s.primitives += h->prims.size();
    s.fixedBytes += sizeof(Hyperset) + h->prims.size() * (sizeof(PrimitiveBox) + sizeof(uint32_t));
  }
  return s;
}

RayClassification::Cell* RayClassification::makeChild(const Hyperset& h, int face, Cell& parent,
                                                      int half, const double* lo,
                                                      const double* w) const {
  const size_t n = parent.count;
  // Work is bounded as memory is: a cell that keeps all its parent's objects costs only its own
  // bytes, so objects that span every beam (a fan of scene-wide triangles) would otherwise have
  // every ray make ~log2(1/w_min) such cells at n beam tests each. Past the budget of tests the
  // parent answers for the half, as past the memory cap.
  if (beamTests_.fetch_add(n, std::memory_order_relaxed) + n > testBudget_) {
    beamTests_.fetch_sub(n, std::memory_order_relaxed);
    parent.closed[half].store(true, std::memory_order_relaxed);
    return nullptr;
  }
  // The most it holds at once: the cell, its list at the longest and the exact copy of it.
  const size_t most = sizeof(Cell) + 2 * n * sizeof(uint32_t);
  if (lazyBytes_.fetch_add(most, std::memory_order_relaxed) + most > capBytes_) {
    lazyBytes_.fetch_sub(most, std::memory_order_relaxed);
    parent.closed[half].store(true, std::memory_order_relaxed);
    return nullptr;
  }
  Beam beam;
  beam.a = face / 2;
  beam.negative = face % 2;
  for (int i = 0; i < 3; ++i) {
    beam.lo[i] = h.lo[i] + lo[i] * h.side - h.pad;
    beam.hi[i] = h.lo[i] + (lo[i] + w[i]) * h.side + h.pad;
  }
  for (int j = 0; j < 2; ++j) {
    beam.dLo[j] = lo[3 + j] - kPad;
    beam.dHi[j] = lo[3 + j] + w[3 + j] + kPad;
  }
  std::vector<uint32_t> list;
  list.reserve(n);
  for (size_t i = 0; i < n; ++i)
    if (meets(beam, h.prims[parent.refs[i]].box)) list.push_back(parent.refs[i]);
  auto cell = std::make_unique<Cell>();
  cell->count = uint32_t(list.size());
  if (list.size() == n) {
    // The beam meets all its parent's objects (as near the roots, where the cells are wide):
    // the parent's list, which outlives its children, serves as it is.
    cell->refs = parent.refs;
  } else {
    cell->own = std::make_unique<uint32_t[]>(list.size());
    std::copy(list.begin(), list.end(), cell->own.get());
    cell->refs = cell->own.get();
  }
  const size_t owned = cell->own ? list.size() : 0;
  const size_t bytes = sizeof(Cell) + owned * sizeof(uint32_t);
  Cell* published = nullptr;
  if (parent.child[half].compare_exchange_strong(published, cell.get(), std::memory_order_acq_rel,
                                                 std::memory_order_acquire)) {
    lazyBytes_.fetch_sub(most - bytes, std::memory_order_relaxed);
    cells_.fetch_add(1, std::memory_order_relaxed);
    references_.fetch_add(owned, std::memory_order_relaxed);
    return cell.release();
  }
  // Another thread made this half first: its list is the same; ours is dropped.
  lazyBytes_.fetch_sub(most, std::memory_order_relaxed);
  return published;
}

template <class Counter>
const RayClassification::Cell* RayClassification::classify(const Hyperset& h, const Ray& ray,
                                                           float tEnd, Counter count) const {
  int a = 0;
  for (int k = 1; k < 3; ++k)
    if (std::fabs(ray.d[k]) > std::fabs(ray.d[a])) a = k;
  const double m = std::fabs(double(ray.d[a]));
  if (!h.classifies || !(m > 0) || !isFinite(ray.d) || !isFinite(ray.o)) {
    count.step();
    return &h.roots[0];  // its list is the whole group
  }
  // The segment's part in E grown by the beams' pad (the margin the beams keep for rounding,
  // so that E's own, below a float step far from the origin, never decides alone), in double:
  // its start, clamped into E, is the ray's point in the 5-D space.
  double t0 = ray.tMin, t1 = std::min(ray.tMax, tEnd);
  for (int i = 0; i < 3; ++i) {
    const double o = ray.o[i], d = ray.d[i], lo = h.lo[i] - h.pad, hi = h.lo[i] + h.side + h.pad;
    if (d == 0) {
      if (o < lo || o > hi) return nullptr;
      continue;
    }
    double ta = (lo - o) / d, tb = (hi - o) / d;
    if (ta > tb) std::swap(ta, tb);
    t0 = std::max(t0, ta);
    t1 = std::min(t1, tb);
  }
  if (!(t0 <= t1)) return nullptr;
  double x[kDims];
  for (int i = 0; i < 3; ++i)
    x[i] = std::clamp((ray.o[i] + t0 * ray.d[i] - h.lo[i]) / h.side, 0.0, 1.0);
  x[3] = std::clamp(ray.d[(a + 1) % 3] / m, -1.0, 1.0);
  x[4] = std::clamp(ray.d[(a + 2) % 3] / m, -1.0, 1.0);
  const int face = 2 * a + (ray.d[a] < 0);

  double lo[kDims], w[kDims];
  std::copy(kRootLo, kRootLo + kDims, lo);
  std::copy(kRootWidth, kRootWidth + kDims, w);
  const Cell* cell = &h.roots[face];
  while (true) {
    count.step();
    if (cell->count <= settings_.nMin || *std::min_element(w, w + kDims) <= settings_.wMin)
      return cell;
    const int axis = longestAxis(w);
    w[axis] /= 2;
    const int half = x[axis] >= lo[axis] + w[axis];
    if (half) lo[axis] += w[axis];
    const Cell* next = cell->child[half].load(std::memory_order_acquire);
    if (!next) {
      // The cells are the structure's, made on demand: constness is the callers' view of it.
      Cell& parent = const_cast<Cell&>(*cell);
      if (parent.closed[half].load(std::memory_order_relaxed)) return cell;
      next = makeChild(h, face, parent, half, lo, w);
      if (!next) return cell;
    }
    cell = next;
  }
}

template <bool AnyHit, class Counter>
bool RayClassification::traverse(uint32_t groupId, const Ray& ray, uint32_t instId, Hit& hit,
                                 Counter count) const {
  const Hyperset& h = *sets_[groupId];
  if (h.prims.empty()) return false;
  const Cell* cell = classify(h, ray, hit.t, count);
  if (!cell) return false;
  return testList<AnyHit>(groupId, h.prims.data(), cell->refs, cell->count, ray, instId, hit,
                          count);
}

}  // namespace glint
