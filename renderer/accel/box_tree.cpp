#include "accel/box_tree.h"

#include <algorithm>

namespace glint {

BoxTree::BoxTree(std::vector<PrimitiveBox> prims) : prims_(std::move(prims)) {
  for (const PrimitiveBox& p : prims_) box_.extend(p.box);
  if (prims_.empty()) return;
  nodes_.reserve(2 * prims_.size());
  build(0, prims_.size());
}

void BoxTree::build(size_t begin, size_t end) {
  const auto index = nodes_.size();
  nodes_.emplace_back();
  Bounds3f box, centres;
  for (size_t i = begin; i < end; ++i) {
    box.extend(prims_[i].box);
    // Halved before adding: exact, and no overflow near float's largest values.
    centres.extend(0.5f * prims_[i].box.lo + 0.5f * prims_[i].box.hi);
  }
  nodes_[index].box = box;
  if (end - begin <= 4) {
    nodes_[index].first = static_cast<uint32_t>(begin);
    nodes_[index].count = static_cast<uint32_t>(end - begin);
    return;
  }
  const Vec3f extent = centres.hi - centres.lo;
  const int axis =
      extent.x >= extent.y ? (extent.x >= extent.z ? 0 : 2) : (extent.y >= extent.z ? 1 : 2);
  const size_t mid = begin + (end - begin) / 2;
  std::nth_element(prims_.begin() + long(begin), prims_.begin() + long(mid),
                   prims_.begin() + long(end), [&](const PrimitiveBox& a, const PrimitiveBox& b) {
                     return 0.5f * a.box.lo[axis] + 0.5f * a.box.hi[axis] <
                            0.5f * b.box.lo[axis] + 0.5f * b.box.hi[axis];
                   });
  nodes_[index].axis = static_cast<uint32_t>(axis);
  build(begin, mid);
  nodes_[index].first = static_cast<uint32_t>(nodes_.size());
  build(mid, end);
}

}  // namespace glint
