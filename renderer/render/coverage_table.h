#pragma once
// How many of a pixel's samples saw each id (an object or a material), in a fixed table: the
// per-sample path neither allocates nor throws. Ids past the capacity are not counted (their
// coverage is lost, and docs/output.md says so); at Glint's scenes' sizes a pixel meets far
// fewer.
#include <algorithm>
#include <cstdint>

namespace glint {

class CoverageTable {
 public:
  static constexpr int kCapacity = 16;
  struct Entry {
    uint32_t id;
    uint32_t count;
  };

  void clear() { size_ = 0; }
  void add(uint32_t id, uint32_t count = 1) {
    for (int i = 0; i < size_; ++i)
      if (entries_[i].id == id) {
        entries_[i].count += count;
        return;
      }
    if (size_ < kCapacity) entries_[size_++] = {id, count};
  }
  // Adds another table's counts (a pass's to the pixel's).
  void add(const CoverageTable& other) {
    for (int i = 0; i < other.size_; ++i) add(other.entries_[i].id, other.entries_[i].count);
  }
  // The entries sorted by count, most first; equal counts by id, smaller first, so the order
  // does not depend on which sample came first.
  CoverageTable ranked() const {
    CoverageTable r = *this;
    std::sort(r.entries_, r.entries_ + r.size_, [](const Entry& a, const Entry& b) {
      return a.count != b.count ? a.count > b.count : a.id < b.id;
    });
    return r;
  }
  int size() const { return size_; }
  const Entry& operator[](int i) const { return entries_[i]; }

 private:
  Entry entries_[kCapacity];
  int size_ = 0;
};

}  // namespace glint
