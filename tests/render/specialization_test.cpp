// Leaving out what a scene does not need must not change a byte: every bundled scene renders
// identically through the integrator compiled for its capabilities and through the general one.
#include <gtest/gtest.h>

#include <filesystem>

#include "io/scene_loader.h"
#include "render/render_job.h"
#include "test_util.h"

namespace glint {
namespace {

RenderResult renderSmall(Scene scene, bool specialize, const std::string& aovs = "") {
  // Small frames keep the suite fast; every pixel still runs the full per-sample path.
  scene.render.width = 40;
  scene.render.height = 30;
  scene.render.spp = 4;
  const auto accel = makeAccelerator(AccelKind::Embree, scene);
  RenderOptions opt;
  opt.progress = false;
  opt.specialize = specialize;
  opt.aovs = AovSet::parse(aovs);
  return renderScene(scene, *accel, opt);
}

TEST(Specialization, EveryBundledSceneMatchesTheGeneralPathBitForBit) {
  int scenes = 0;
  unsigned kernelsSeen = 0;  // one bit per capability set met
  for (const auto& e : std::filesystem::directory_iterator(GLINT_SCENES_DIR)) {
    if (e.path().extension() != ".json") continue;
    const Scene scene = loadSceneFile(e.path().string());
    const RenderResult special = renderSmall(scene, true);
    const RenderResult general = renderSmall(scene, false);
    EXPECT_EQ(special.stats.kernelCaps, kernelCaps(scene.features, false)) << e.path();
    EXPECT_EQ(general.stats.kernelCaps, cap::kAll) << e.path();
    EXPECT_EQ(special.film.toFloatRgba(), general.film.toFloatRgba()) << e.path();
    // The same rays, too: a specialised kernel leaves out code, never work the image needs.
    EXPECT_EQ(special.stats.rays.total(), general.stats.rays.total()) << e.path();
    kernelsSeen |= 1u << special.stats.kernelCaps;
    ++scenes;
  }
  EXPECT_GE(scenes, 10);
  // The bundled scenes exercise the plain kernel and several specialised ones.
  EXPECT_TRUE(kernelsSeen & 1u) << "no scene ran the plain kernel";
  EXPECT_GE(__builtin_popcount(kernelsSeen), 4);
}

TEST(Specialization, AovsOnlyWhenAskedAndTheSameEitherWay) {
  const Scene scene = loadSceneFile(std::string(GLINT_SCENES_DIR) + "/whitted.json");
  const RenderResult special = renderSmall(scene, true, "depth,normal,direct,indirect,lights");
  const RenderResult general = renderSmall(scene, false, "depth,normal,direct,indirect,lights");
  EXPECT_NE(special.stats.kernelCaps & cap::kAovs, 0u);
  EXPECT_EQ(special.film.toFloatRgba(), general.film.toFloatRgba());
  ASSERT_EQ(special.film.planes().size(), general.film.planes().size());
  ASSERT_GE(special.film.planes().size(), 4u);
  for (size_t i = 0; i < special.film.planes().size(); ++i)
    EXPECT_EQ(special.film.planes()[i].values, general.film.planes()[i].values)
        << special.film.planes()[i].name;
}

}  // namespace
}  // namespace glint
