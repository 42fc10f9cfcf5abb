// The reference integrator (integrator/reference.h, seed 002's Trace written depth first) is
// the oracle of the production kernel (integrator/batched_kernel.h): every bundled scene renders
// to the same image through both (oracle_util.h states when and why a difference is allowed).
// The stress suite holds every stress scene to the same (stress/stress_util.h).
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>

#include "io/scene_loader.h"
#include "oracle_util.h"
#include "test_util.h"

namespace glint {
namespace {

// A bundled scene at a small size: every pixel still runs the whole path, with the scene's own
// effects and depth limit, at no more than `spp` samples.
Scene small(const std::string& path, int width, int height, int spp) {
  Scene scene = loadSceneFile(path);
  scene.render.width = width;
  scene.render.height = height;
  scene.render.spp = std::min(scene.render.spp, spp);
  return scene;
}

RenderOptions quiet() {
  RenderOptions opt;
  opt.progress = false;
  return opt;
}

struct Bundled {
  std::string name;
  Scene scene;
};

std::vector<Bundled> bundledScenes() {
  std::vector<Bundled> out;
  for (const auto& dir : {std::string(GLINT_SCENES_DIR), std::string(GLINT_SCENES_DIR) + "/peers"})
    for (const auto& e : std::filesystem::directory_iterator(dir)) {
      if (e.path().extension() != ".json") continue;
      try {
        out.push_back({e.path().filename().string(), small(e.path().string(), 48, 32, 4)});
      } catch (const SceneError&) {
        continue;  // a peer scene whose mesh is not installed (cornell_box: embree-tools)
      }
    }
  return out;
}

TEST(ReferenceIntegrator, AgreesWithTheProductionKernelOnEveryBundledScene) {
  const std::vector<Bundled> scenes = bundledScenes();
  ASSERT_GE(scenes.size(), 14u);
  // Among them glTF's per-texel maps, wrap modes and second texture coordinates.
  EXPECT_TRUE(std::any_of(scenes.begin(), scenes.end(),
                          [](const Bundled& b) { return b.name == "gltf_materials.json"; }));
  for (const Bundled& b : scenes) {
    const auto accel = makeAccelerator(AccelKind::Embree, b.scene);
    const RenderResult production = renderScene(b.scene, *accel, quiet());
    test::expectReferenceAgrees(b.scene, *accel, quiet(), production, b.name);
  }
}

TEST(ReferenceIntegrator, AgreesBitForBitWhereOneKernelTracesEveryRay) {
  // Glint's reference BVH answers a batch of rays one at a time with the same code as a single
  // ray: then no difference is allowed anywhere, moving scenes included.
  for (const char* name : {"animation.json", "motion_blur.json", "whitted.json"}) {
    const Scene scene = small(std::string(GLINT_SCENES_DIR) + "/" + name, 40, 30, 2);
    const auto accel = makeAccelerator(AccelKind::Bvh, scene);
    const RenderResult production = renderScene(scene, *accel, quiet());
    EXPECT_EQ(test::expectReferenceAgrees(scene, *accel, quiet(), production, name), 0) << name;
  }
}

TEST(ReferenceIntegrator, CountsTheSameRays) {
  // Both trace the same tree: the same camera, shadow, reflection and refraction rays.
  const Scene scene = small(std::string(GLINT_SCENES_DIR) + "/whitted.json", 32, 24, 2);
  RenderOptions opt = quiet();
  const auto accel = makeAccelerator(AccelKind::Embree, scene);
  const RayCounters production = renderScene(scene, *accel, opt).stats.rays;
  opt.integrator = IntegratorKind::Reference;
  const RayCounters reference = renderScene(scene, *accel, opt).stats.rays;
  EXPECT_EQ(production.camera, reference.camera);
  EXPECT_EQ(production.shadow, reference.shadow);
  EXPECT_EQ(production.reflection, reference.reflection);
  EXPECT_EQ(production.refraction, reference.refraction);
  EXPECT_GT(reference.refraction, 0u);
}

}  // namespace
}  // namespace glint
