#pragma once
// std::sin and std::cos of many floats at once, with the very floats the C library gives one at
// a time. Glibc (2.28 and later) works a float's sine and cosine out in double: the argument
// reduced by the nearest multiple of π/2, then two short polynomials, rounded to float once;
// on a CPU with FMA and AVX2 it takes its build of that code with fused multiply-adds. The
// lanes below repeat those operations in the same order, four arguments side by side, where
// the C library would run that build; elsewhere, and for arguments outside the reduction's
// range (|x| ≥ 120, infinities, NaN), they call std::sin and std::cos themselves.

namespace glint {

// s[i] = std::sin(x[i]) and c[i] = std::cos(x[i]) for i in [0, n), bit for bit.
void sinCos(const float* x, int n, float* s, float* c);

// Whether sinCos runs its lanes on this CPU (else it calls the C library throughout).
bool sinCosInLanes();

}  // namespace glint
