#pragma once
// Flush-to-zero and denormals-are-zero, as Embree asks of every thread that traces: denormals
// cost ~100 cycles each and carry no meaning for radiance.
#include <pmmintrin.h>
#include <xmmintrin.h>

namespace glint {

// Flush-to-zero for a scope, the thread's previous modes restored at its end: the thread that
// calls a render joins its task arena and traces too, and its caller's arithmetic after the
// render must not lose denormals (std::nextafter(0, 1) read 0 in a test that ran after one).
class FlushToZeroScope {
 public:
  FlushToZeroScope()
      : flushZero_(_MM_GET_FLUSH_ZERO_MODE()), denormalsZero_(_MM_GET_DENORMALS_ZERO_MODE()) {
    _MM_SET_FLUSH_ZERO_MODE(_MM_FLUSH_ZERO_ON);
    _MM_SET_DENORMALS_ZERO_MODE(_MM_DENORMALS_ZERO_ON);
  }
  ~FlushToZeroScope() {
    _MM_SET_FLUSH_ZERO_MODE(flushZero_);
    _MM_SET_DENORMALS_ZERO_MODE(denormalsZero_);
  }
  FlushToZeroScope(const FlushToZeroScope&) = delete;
  FlushToZeroScope& operator=(const FlushToZeroScope&) = delete;

 private:
  unsigned flushZero_, denormalsZero_;
};

}  // namespace glint
