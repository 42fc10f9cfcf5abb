#pragma once
// A std::allocator whose containers leave new elements' bytes unwritten where they would be
// value-initialised (vector(n), resize(n)): the frame's large buffers are then first written
// by the render's threads, in parallel, instead of zeroed by one thread before the first pass,
// and pages nothing writes are never touched. Every element must be written before it is read;
// copies and elements made from a value are constructed as usual. Large buffers lie on huge
// pages (core/huge_pages.h).
#include <cstddef>
#include <memory>
#include <new>
#include <type_traits>
#include <utility>

#include "core/huge_pages.h"

namespace glint {

template <class T>
class UnwrittenAllocator : public std::allocator<T> {
  // Such a T is created by writing it in the allocated bytes (C++20 implicit object creation).
  static_assert(std::is_trivially_copyable_v<T> && std::is_trivially_destructible_v<T>);

 public:
  using value_type = T;
  template <class U>
  struct rebind {
    using other = UnwrittenAllocator<U>;
  };
  UnwrittenAllocator() = default;
  template <class U>
  UnwrittenAllocator(const UnwrittenAllocator<U>&) noexcept {}

  T* allocate(std::size_t n) {
    if (n > std::size_t(-1) / sizeof(T)) throw std::bad_array_new_length();
    return static_cast<T*>(allocateBuffer(n * sizeof(T)));
  }
  void deallocate(T* p, std::size_t n) noexcept { freeBuffer(p, n * sizeof(T)); }

  template <class U>
  void construct(U*) noexcept {}
  template <class U, class... Args>
  void construct(U* p, Args&&... args) {
    ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }
};

template <class T, class U>
bool operator==(const UnwrittenAllocator<T>&, const UnwrittenAllocator<U>&) {
  return true;
}

}  // namespace glint
