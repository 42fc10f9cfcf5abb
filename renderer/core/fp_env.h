#pragma once
// Flush-to-zero and denormals-are-zero, as Embree asks of every thread that traces: denormals
// cost ~100 cycles each and carry no meaning for radiance.
#include <pmmintrin.h>
#include <xmmintrin.h>

namespace glint {

inline void enableFlushToZero() {
  _MM_SET_FLUSH_ZERO_MODE(_MM_FLUSH_ZERO_ON);
  _MM_SET_DENORMALS_ZERO_MODE(_MM_DENORMALS_ZERO_ON);
}

}  // namespace glint
