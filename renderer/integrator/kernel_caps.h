#pragma once
// Leave out what a scene does not need (DESIGN.md §3): the integrator and the per-sample loop
// are compiled once per combination of these capabilities, and a render runs the instantiation
// that has exactly the ones its scene uses. A plain Phong scene then carries no interior list,
// draws no light, gloss, lens or time samples and tests no branch for them. `kAll` is the
// general path (`glint render --no-specialize`); every instantiation gives the same bytes as it
// for the scenes it accepts (tests/render/specialization_test.cpp).
#include <string>

namespace glint {

struct Features;

namespace cap {
inline constexpr unsigned kDielectrics =
    1u << 0;  // refraction, nested media, Beer, see-through shadows
inline constexpr unsigned kAreaLights = 1u << 1;     // lights averaged over several samples
inline constexpr unsigned kGloss = 1u << 2;          // glossy reflection, blurred translucency
inline constexpr unsigned kCameraSamples = 1u << 3;  // lens or shutter-time dimensions
inline constexpr unsigned kAovs = 1u << 4;           // AOV records of the camera hit
inline constexpr unsigned kCount = 5;
inline constexpr unsigned kAll = (1u << kCount) - 1;
}  // namespace cap

// The capabilities a scene needs; `aovs` when AOVs were asked for.
unsigned kernelCaps(const Features& features, bool aovs);
// "general" for kAll, "plain" for none, else the capability names joined by '+'.
std::string kernelName(unsigned caps);

}  // namespace glint
