// The reference integrator (integrator/reference.h, seed 002's Trace written depth first) is
// the oracle of the production kernel (integrator/batched_kernel.h): every bundled scene renders
// to the same image through both (oracle_util.h states when and why a difference is allowed).
// The stress suite holds every stress scene to the same (stress/stress_util.h).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
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

// A small room for the shadow queue's cases: a floor, a matte sphere, a mirror and a glass
// sphere under `lights`, `transparent` choosing whether shadows pass the glass.
std::string room(const std::string& render, const std::string& lights, bool transparent) {
  return R"({ "render": { )" + render + R"(, "max_depth": 3, "seed": 7,
      "background": [0.05, 0.05, 0.06], "ambient": [0.05, 0.05, 0.05],
      "transparent_shadows": )" +
         (transparent ? "true" : "false") + R"( },
    "camera": { "eye": [0, 3.5, 6.5], "look_at": [0, 0.5, 0], "vfov": 40 },
    "materials": { "floor": { "type": "phong", "kd": [0.75, 0.75, 0.75] },
      "red": { "type": "phong", "kd": [0.8, 0.2, 0.15], "ks": [0.2, 0.2, 0.2], "exponent": 30 },
      "chrome": { "type": "mirror", "km": [0.85, 0.85, 0.88] },
      "glass": { "type": "dielectric", "ior": 1.5, "attenuation": [0.9, 0.6, 0.3] } },
    "lights": [ )" +
         lights + R"( ],
    "objects": [
      { "type": "plane", "point": [0, 0, 0], "normal": [0, 1, 0], "material": "floor" },
      { "type": "sphere", "center": [-1.2, 0.7, 0], "radius": 0.7, "material": "red" },
      { "type": "sphere", "center": [0.4, 0.8, -1], "radius": 0.8, "material": "chrome" },
      { "type": "sphere", "center": [1.3, 0.5, 0.8], "radius": 0.5, "material": "glass" } ] })";
}

TEST(ReferenceIntegrator, AgreesWhereOnePointsShadowRaysOutnumberTheQueue) {
  // 1024 samples of one light and a point light: a lit point's 1025 shadow rays are more than
  // the kernel's queue holds (512), so they are traced in pieces and each light's sum runs on
  // across them; opaque (coherent streams) and transparent (one ray per interface) alike.
  const std::string lights =
      R"({ "type": "quad", "corner": [-2.5, 4, -0.5], "edge1": [1.5, 0, 0], "edge2": [0, 0, 1.5],
           "intensity": [0.7, 0.65, 0.6], "samples": 1024 },
         { "type": "point", "position": [3, 5, 4], "intensity": [0.3, 0.3, 0.35] })";
  for (const bool transparent : {false, true}) {
    const Scene scene =
        test::sceneFromText(room(R"("width": 12, "height": 8, "spp": 1)", lights, transparent));
    const auto accel = makeAccelerator(AccelKind::Embree, scene);
    const RenderResult production = renderScene(scene, *accel, quiet());
    // About 94 lit points (camera hits off the glass and mirror, and the mirror's reflections)
    // of up to 1025 rays each: 96351 opaque; a piece lost at the queue's edge costs 512 a point.
    EXPECT_GE(production.stats.rays.shadow, 1025u * 90) << transparent;
    EXPECT_EQ(test::expectReferenceAgrees(scene, *accel, quiet(), production, "1024 samples"), 0)
        << transparent;
  }
}

TEST(ReferenceIntegrator, AgreesWhereOnePointsLightsOutnumberTheQueue) {
  // 600 point lights on a sphere about the scene, half of them below the floor: a lit point's
  // runs (one per light, empty where the light is behind it) outnumber the queue's 512.
  std::string lights;
  for (int i = 0; i < 600; ++i) {
    const double z = 1 - (i + 0.5) / 300.0, r = std::sqrt(1 - z * z), phi = 2.39996 * i;
    lights += (i ? ", " : "") + std::string(R"({ "type": "point", "position": [)") +
              std::to_string(6 * r * std::cos(phi)) + ", " + std::to_string(6 * z) + ", " +
              std::to_string(6 * r * std::sin(phi)) + R"(], "intensity": [0.004, 0.004, 0.004] })";
  }
  const Scene scene =
      test::sceneFromText(room(R"("width": 8, "height": 6, "spp": 1)", lights, false));
  ASSERT_EQ(scene.lights.size(), 600u);
  const auto accel = makeAccelerator(AccelKind::Embree, scene);
  const RenderResult production = renderScene(scene, *accel, quiet());
  EXPECT_EQ(test::expectReferenceAgrees(scene, *accel, quiet(), production, "600 lights"), 0);
}

TEST(ReferenceIntegrator, AgreesBitForBitOnTheDocumentsDistributedShading) {
  // Seed 002's Phong lobes for gloss and blur, its constant k_t with transparent shadows and
  // Beer inside, and seed 001's screen-corner camera, under each sampler: the same rays, drawn
  // from the same dimensions, summed in the same order.
  for (const char* sampler : {"stratified", "sobol", "regular", "random"}) {
    const Scene scene = test::sceneFromText(R"({ "render": { "width": 24, "height": 16, "spp": 4,
        "max_depth": 4, "seed": 9, "sampler": ")" +
                                            std::string(sampler) + R"(",
        "background": [0.2, 0.25, 0.3], "ambient": [0.05, 0.05, 0.05],
        "transparent_shadows": true },
      "camera": { "eye": [0, 1.5, 6], "up": [0, 1, 0],
                  "screen": { "corner_min": [-1.6, 0.3, 3], "corner_max": [1.6, 2.7, 3] } },
      "materials": {
        "floor": { "type": "phong", "kd": { "checker": { "scale": 0.5, "a": [0.8, 0.8, 0.8],
                                                         "b": [0.2, 0.2, 0.2] } } },
        "satin": { "type": "mirror", "km": [0.8, 0.7, 0.6], "gloss": { "phong": 30 } },
        "matte": { "type": "phong", "kd": [0.3, 0.5, 0.2], "km": [0.2, 0.2, 0.2],
                   "gloss": { "phong": 0 } },
        "frosted": { "type": "dielectric", "ior": 1.4, "fresnel": "none", "kt": [0.8, 0.7, 0.9],
                     "km": [0.1, 0.1, 0.1], "gloss": { "phong": 100 }, "blur": { "phong": 60 },
                     "attenuation": [0.7, 0.8, 0.9] },
        "glass": { "type": "dielectric", "blur": { "phong": 500 } } },
      "lights": [ { "type": "point", "position": [2, 5, 3], "intensity": [0.8, 0.8, 0.8] },
                  { "type": "quad", "corner": [-2, 4, -1], "edge1": [1, 0, 0],
                    "edge2": [0, 0, 1], "intensity": [0.4, 0.4, 0.4], "samples": 2 } ],
      "objects": [
        { "type": "plane", "point": [0, 0, 0], "normal": [0, 1, 0], "material": "floor" },
        { "type": "sphere", "center": [-1.2, 0.7, 0], "radius": 0.7, "material": "satin" },
        { "type": "sphere", "center": [1.3, 0.6, 0.3], "radius": 0.6, "material": "matte" },
        { "type": "box", "min": [-0.4, 0, 0.8], "max": [0.4, 1.2, 1.2], "material": "frosted" },
        { "type": "sphere", "center": [0.2, 0.4, 2], "radius": 0.4, "material": "glass" } ] })");
    ASSERT_TRUE(scene.features.gloss);
    for (const AccelKind kind : {AccelKind::Bvh, AccelKind::Embree}) {
      const auto accel = makeAccelerator(kind, scene);
      const RenderResult production = renderScene(scene, *accel, quiet());
      EXPECT_GT(production.stats.rays.refraction, 0u);
      EXPECT_EQ(test::expectReferenceAgrees(scene, *accel, quiet(), production, sampler), 0)
          << sampler << " " << accelName(kind);
    }
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
