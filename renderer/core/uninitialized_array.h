#pragma once
// N objects of T whose storage is not written when the array is made, for scratch queues whose
// slots are always written before they are read: an array of T would run T's default member
// initialisers on every slot each time a queue is made.
#include <cstddef>
#include <new>
#include <type_traits>

namespace glint {

template <class T, int N>
class UninitializedArray {
  // Writing a member of such a T in the bytes creates it (C++20 implicit object creation).
  static_assert(std::is_trivially_copyable_v<T> && std::is_trivially_destructible_v<T>);

 public:
  T& operator[](std::size_t i) { return data()[i]; }
  const T& operator[](std::size_t i) const { return data()[i]; }
  T* data() { return std::launder(reinterpret_cast<T*>(bytes_)); }
  const T* data() const { return std::launder(reinterpret_cast<const T*>(bytes_)); }

 private:
  alignas(T) std::byte bytes_[sizeof(T) * N];
};

}  // namespace glint
