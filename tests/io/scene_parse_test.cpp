#include <gtest/gtest.h>

#include "camera/camera.h"
#include "test_util.h"

namespace glint {
namespace {

using test::sceneFromText;

// The eye at the world origin: scenes load into render space, world minus the eye
// (io/placement.h), so here render space is world space and positions read as written.
const char* kHeader = R"(
  "camera": { "eye": [0, 0, 0], "look_at": [0, 0, -5] },
  "materials": { "m": { "type": "phong", "kd": [0.5, 0.5, 0.5] } },
)";

Scene withObjects(const std::string& objects, const std::string& extra = "") {
  return sceneFromText("{" + std::string(kHeader) + extra + "\"objects\": [" + objects + "]}");
}

TEST(SceneParse, ASeedOfMinusZeroIsZeroAndANegativeOneIsRefused) {
  // JSON writes zero as -0 too: it was refused with "must be a non-negative integer, got 0".
  const auto withSeed = [](const std::string& seed) {
    return R"({"render": {"seed": )" + seed +
           R"(}, "camera": {"eye": [0, 0, 5], "look_at": [0, 0, 0]}, "objects": []})";
  };
  EXPECT_EQ(sceneFromText(withSeed("-0")).render.seed, 0u);
  EXPECT_EQ(test::sceneErrorOf(withSeed("-1")),
            "scene.json:1: render.seed: must be a non-negative integer, got -1");
}

TEST(SceneParse, UvRotateTakesWholeTurnsOffFirst) {
  // 368730° is 1024 turns and 90°: the transform of 90°, bit for bit (fmod is exact). At 3e38°
  // the angle in radians overflowed float, and the sine and cosine of infinity (NaN) blackened
  // the texture; it is now a rotation like any other.
  const auto transformOf = [](const std::string& degrees) {
    const Scene s = sceneFromText(R"({"camera": {"eye": [0, 0, 5], "look_at": [0, 0, 0]},
      "materials": {"m": {"type": "phong", "kd": {"image": ")" +
                                  test::writeHalfMatte() + R"(", "uv_rotate": )" + degrees +
                                  R"(}}}, "objects": []})");
    for (const Material& m : s.materials)
      if (m.name == "m") return m.surface.kd.uvTransform;
    ADD_FAILURE() << "no material m";
    return UvTransform{};
  };
  const UvTransform quarter = transformOf("90"), turned = transformOf("368730");
  EXPECT_EQ(turned.m00, quarter.m00);
  EXPECT_EQ(turned.m01, quarter.m01);
  EXPECT_EQ(turned.m10, quarter.m10);
  EXPECT_EQ(turned.m11, quarter.m11);
  const UvTransform huge = transformOf("3e38");
  EXPECT_NEAR(huge.m00 * huge.m00 + huge.m10 * huge.m10, 1, 1e-6);  // a unit column: a rotation
  EXPECT_NEAR(huge.m00, huge.m11, 1e-6);
}

TEST(SceneParse, DirectionsAreReadAtAnyScale) {
  // Only a direction's direction counts. Past about 1e19 a component's square overflowed float,
  // and normalising gave zero: a directional light at [0, -1e20, -1e20] went dark, a plane
  // placed by a scale of 1e-20 along its normal vanished, and an up of [0, 1e20, 0] was refused
  // as parallel to the view; [0, -1e-30, -1e-30] underflowed and was refused as zero. Each now
  // reads as its unit vector, to float rounding (1e-7).
  const auto load = [](const std::string& light, const std::string& up,
                       const std::string& planeScale) {
    return sceneFromText(R"({"camera": {"eye": [0, 0, 5], "look_at": [0, 0, 0], "up": )" + up +
                         R"(}, "lights": [{"type": "directional", "direction": )" + light +
                         R"(}], "materials": {"m": {"type": "phong"}}, "objects": [{"type": "plane",
                         "point": [0, 0, 0], "normal": [0, 1, 0], "material": "m", "transform": {"scale": )" +
                         planeScale + "}}]}");
  };
  const Scene unit = load("[0, -1, -1]", "[0, 1, 0]", "[1, 1, 1]");
  for (const Scene& s : {load("[0, -1e20, -1e20]", "[0, 1e20, 0]", "[1, 1e-20, 1]"),
                         load("[0, -1e-30, -1e-30]", "[0, 1e-30, 0]", "[1, 1e20, 1]")}) {
    const Vec3f d = std::get<DirectionalLight>(s.lights[0]).direction;
    const Vec3f expected = std::get<DirectionalLight>(unit.lights[0]).direction;
    EXPECT_NEAR(d.x, expected.x, 1e-7);
    EXPECT_NEAR(d.y, expected.y, 1e-7);
    EXPECT_NEAR(d.z, expected.z, 1e-7);
    ASSERT_EQ(s.planes.size(), 1u);
    EXPECT_NEAR(s.planes[0].normal.y, 1, 1e-7);
    const Camera camera(s.cameraDesc, 8, 8), unitCamera(unit.cameraDesc, 8, 8);
    const Ray r = camera.generateRay(1.5f, 2.5f), expectedRay = unitCamera.generateRay(1.5f, 2.5f);
    EXPECT_NEAR(r.d.x, expectedRay.d.x, 1e-7);
    EXPECT_NEAR(r.d.y, expectedRay.d.y, 1e-7);
    EXPECT_NEAR(r.d.z, expectedRay.d.z, 1e-7);
  }
}

TEST(SceneParse, RenderBlockAndDefaults) {
  // Comments are allowed anywhere (SCENE_FORMAT.md).
  const Scene s = sceneFromText(R"({
    // a comment
    "render": { "width": 32, "height": 16, "spp": 4, "max_depth": 3, "seed": 9,
                "sampler": "random", "background": [0.1, 0.2, 0.3], "ambient": [1, 1, 1] },
    /* another */
    "camera": { "eye": [0, 0, 5], "look_at": [0, 0, 0] },
    "objects": []
  })");
  EXPECT_EQ(s.render.width, 32);
  EXPECT_EQ(s.render.height, 16);
  EXPECT_EQ(s.render.spp, 4);
  EXPECT_EQ(s.render.maxDepth, 3);
  EXPECT_EQ(s.render.seed, 9u);
  EXPECT_EQ(s.render.sampler, SamplerKind::Random);
  EXPECT_EQ(s.render.background, (Rgb{0.1f, 0.2f, 0.3f}));
  // Defaults: pinhole, shutter [0, 0], focus at the look-at distance.
  EXPECT_EQ(s.cameraDesc.apertureRadius, 0);
  EXPECT_EQ(s.cameraDesc.shutterClose, 0);
  EXPECT_FLOAT_EQ(s.cameraDesc.focusDistance, 5);
}

TEST(SceneParse, BothCameraTypes) {
  const Scene p = sceneFromText(R"({"camera": {"type": "perspective", "eye": [0,0,5],
      "look_at": [0,0,0], "vfov": 30}, "objects": []})");
  EXPECT_EQ(p.cameraDesc.projection, Projection::Perspective);
  EXPECT_EQ(p.cameraDesc.vfovDegrees, 30);
  const Scene o = sceneFromText(R"({"camera": {"type": "orthographic", "eye": [0,0,5],
      "look_at": [0,0,0], "height": 3}, "objects": []})");
  EXPECT_EQ(o.cameraDesc.projection, Projection::Orthographic);
  EXPECT_EQ(o.cameraDesc.orthoHeight, 3);
}

TEST(SceneParse, WindowObliquePlaneAndAPhotographersLens) {
  const Scene p = sceneFromText(R"({"camera": {"eye": [0,1,6], "look_at": [0,0.5,0],
      "window": [-0.6, 0.4, -0.3, 0.3], "image_plane_normal": [0, 0.2, 1],
      "focal_length": 0.05, "f_number": 2.0, "focus_distance": 6}, "objects": []})");
  ASSERT_TRUE(p.cameraDesc.window && p.cameraDesc.imagePlaneNormal);
  EXPECT_EQ(p.cameraDesc.window->l, -0.6f);
  EXPECT_EQ(p.cameraDesc.window->t, 0.3f);
  // Seed 002 §9.3: D = F/a = 0.025, so the radius is F/(2a) = 0.0125, exactly as computed.
  EXPECT_EQ(p.cameraDesc.apertureRadius, 0.05f / (2 * 2.0f));
  // An orthographic window needs no height.
  const Scene o = sceneFromText(R"({"camera": {"type": "orthographic", "eye": [0,0,5],
      "look_at": [0,0,0], "window": [0, 2, -1, 0]}, "objects": []})");
  EXPECT_EQ(o.cameraDesc.window->r, 2.0f);
}

TEST(SceneParse, MaterialsKeepEveryKey) {
  const Scene s = sceneFromText(R"({"camera": {"eye": [0,0,0], "look_at": [0,0,-5]},
    "materials": {
      "p": {"type": "phong", "ka": [0.1,0,0], "kd": {"checker": {"scale": 2, "a": [1,1,1], "b": [0,0,0]}},
            "ks": [0.3,0.3,0.3], "exponent": 100, "specular_model": "phong", "km": [0.2,0.2,0.2]},
      "m": {"type": "mirror", "km": [0.9, 0.8, 0.7], "ks": [0.1,0.1,0.1], "ke": [2,2,2]},
      "g": {"type": "dielectric", "ior": 1.33, "attenuation": [0.9, 1, 0.9], "fresnel": "schlick",
            "ks": [0.5,0.5,0.5], "exponent": 80, "blur": 0.1}
    }, "objects": []})");
  ASSERT_EQ(s.materials.size(), 3u);
  const auto named = [&](const std::string& name) -> const Material& {
    for (const auto& m : s.materials)
      if (m.name == name) return m;
    throw std::runtime_error("no material " + name);
  };
  const Surface& p = named("p").surface;
  EXPECT_EQ(named("p").kind, MaterialKind::Phong);
  EXPECT_EQ(p.kd.pattern, TexturePattern::Checker);
  EXPECT_EQ(p.kd.scale, 2);
  EXPECT_EQ(p.ka.constant, (Rgb{0.1f, 0, 0}));
  EXPECT_FALSE(p.ambientFollowsDiffuse);  // its own ka: the ambient term must evaluate it
  EXPECT_EQ(p.specularModel, SpecularModel::Phong);
  EXPECT_EQ(p.exponent, 100);
  EXPECT_EQ(p.km.constant, (Rgb{0.2f, 0.2f, 0.2f}));
  // A mirror takes the general surface's keys: a highlight and emission.
  const Material& m = named("m");
  EXPECT_EQ(m.kind, MaterialKind::Mirror);
  EXPECT_EQ(m.surface.km.constant, (Rgb{0.9f, 0.8f, 0.7f}));
  EXPECT_EQ(m.surface.ks.constant, (Rgb{0.1f, 0.1f, 0.1f}));
  EXPECT_EQ(m.surface.ke.constant, (Rgb{2, 2, 2}));
  EXPECT_TRUE(m.surface.kd.isBlack());  // the mirror's default
  // So does a dielectric, besides its interface.
  const Material& g = named("g");
  EXPECT_TRUE(g.refracts());
  EXPECT_FLOAT_EQ(g.dielectric.ior, 1.33f);
  EXPECT_EQ(g.dielectric.fresnel, FresnelModel::Schlick);
  EXPECT_EQ(g.dielectric.absorption.attenuation(), (Rgb{0.9f, 1, 0.9f}));
  EXPECT_EQ(g.dielectric.blur, 0.1f);
  EXPECT_EQ(g.surface.ks.constant, (Rgb{0.5f, 0.5f, 0.5f}));
  EXPECT_EQ(g.surface.exponent, 80);
  EXPECT_TRUE(s.features.absorption);
  EXPECT_TRUE(s.features.textures);
  EXPECT_TRUE(s.features.emission);
  EXPECT_TRUE(s.features.specular);
}

TEST(SceneParse, SeedTwosLobesAndCoefficients) {
  // Seed 002 §9.3's Phong lobe for gloss and blur, and its constant k_t (eq. 9.22); seed 000's
  // square stays the number form.
  const Scene s = sceneFromText(R"({"camera": {"eye": [0,0,0], "look_at": [0,0,-5]},
    "materials": {
      "lobe": {"type": "mirror", "gloss": {"phong": 50}},
      "square": {"type": "mirror", "gloss": 0.2},
      "hemisphere": {"type": "mirror", "gloss": {"phong": 0}},
      "glass": {"type": "dielectric", "fresnel": "none", "kt": [0.9, 0.8, 0.7], "km": [0.1,0.1,0.1],
                "blur": {"phong": 200}, "attenuation": [0.5, 0.5, 0.5]}
    }, "objects": []})");
  const auto named = [&](const std::string& name) -> const Material& {
    for (const auto& m : s.materials)
      if (m.name == name) return m;
    throw std::runtime_error("no material " + name);
  };
  EXPECT_EQ(named("lobe").surface.glossShape, GlossShape::Phong);
  EXPECT_EQ(named("lobe").surface.gloss, 50);
  EXPECT_EQ(named("square").surface.glossShape, GlossShape::Square);
  EXPECT_EQ(named("square").surface.gloss, 0.2f);
  // n = 0 is a lobe too: uniform over the hemisphere about the mirror direction.
  EXPECT_TRUE(named("hemisphere").surface.glossy());
  const Dielectric& g = named("glass").dielectric;
  EXPECT_TRUE(g.constantCoefficients());
  EXPECT_EQ(g.kt, (Rgb{0.9f, 0.8f, 0.7f}));
  EXPECT_EQ(g.blurShape, GlossShape::Phong);
  EXPECT_EQ(g.blur, 200);
  EXPECT_TRUE(g.blurs());
  EXPECT_EQ(g.absorption.attenuation(), (Rgb{0.5f, 0.5f, 0.5f}));
  EXPECT_TRUE(s.features.gloss);
  // Fresnel stays the default: no k_t read.
  const Scene plain = sceneFromText(R"({"camera": {"eye": [0,0,0], "look_at": [0,0,-5]},
    "materials": {"glass": {"type": "dielectric"}}, "objects": []})");
  EXPECT_EQ(plain.materials[0].dielectric.fresnel, FresnelModel::Exact);
  EXPECT_FALSE(plain.materials[0].dielectric.constantCoefficients());
  EXPECT_FALSE(plain.features.gloss);
}

TEST(SceneParse, AScreenCameraBecomesLookAtAndAWindow) {
  // Seed 001 §8: the eye 2 from the window's centre (1, 1, 0), the window 3 × 2 wide: at
  // distance 1, ±0.75 × ±0.5; render space puts the eye at the origin.
  const Scene s = sceneFromText(R"({"camera": {"eye": [1, 1, 2],
      "screen": {"corner_min": [-0.5, 0, 0], "corner_max": [2.5, 2, 0]}}, "objects": []})");
  const CameraDesc& c = s.cameraDesc;
  EXPECT_EQ(c.lookAt, (Vec3f{0, 0, -2}));
  ASSERT_TRUE(c.window);
  EXPECT_EQ(c.window->l, -0.75f);
  EXPECT_EQ(c.window->r, 0.75f);
  EXPECT_EQ(c.window->b, -0.5f);
  EXPECT_EQ(c.window->t, 0.5f);
  EXPECT_EQ(c.focusDistance, 2.0f);
  EXPECT_EQ(s.worldOrigin, (Vec3d{1, 1, 2}));
}

TEST(SceneParse, InterfaceKeysBelongToDielectricsOnly) {
  EXPECT_EQ(test::sceneErrorOf(R"({"camera": {"eye": [0,0,0], "look_at": [0,0,-5]},
    "materials": {"p": {"type": "phong",
      "ior": 1.5}}, "objects": []})"),
            "scene.json:3: materials.p.ior: belongs to a \"dielectric\" material, not a \"phong\" "
            "one");
}

// Without "ka" the ambient reflectance is the diffuse texture (SCENE_FORMAT.md), and the
// integrator reuses the diffuse lookup for it, so the flag must say so.
TEST(SceneParse, AmbientFollowsDiffuseWithoutKa) {
  const Scene s = sceneFromText(R"({"camera": {"eye": [0,0,0], "look_at": [0,0,-5]},
    "materials": {"p": {"type": "phong", "kd": {"checker": {"scale": 2, "a": [1,0,0], "b": [0,0,1]}}}},
    "objects": []})");
  const Surface& p = s.materials.at(0).surface;
  EXPECT_TRUE(p.ambientFollowsDiffuse);
  EXPECT_EQ(p.ka.pattern, TexturePattern::Checker);
  EXPECT_EQ(p.ka.a, p.kd.a);
  EXPECT_EQ(p.ka.b, p.kd.b);
  EXPECT_EQ(p.ka.scale, p.kd.scale);
}

TEST(SceneParse, AVisibleAreaLightIsAlsoASurface) {
  // A visible quad light adds a quad to the world whose material emits its radiance; an
  // invisible one adds nothing.
  const Scene s = sceneFromText(R"({"camera": {"eye": [0,0,0], "look_at": [0,0,-5]},
    "lights": [{"type": "quad", "corner": [-1,3,-1], "edge1": [2,0,0], "edge2": [0,0,2],
                "intensity": [2,2,2], "emission": "radiance", "visible": true},
               {"type": "disk", "center": [0,3,0], "normal": [0,-1,0], "radius": 1,
                "intensity": [2,2,2]}],
    "materials": {"m": {"type": "phong"}},
    "objects": [{"type": "sphere", "center": [0,0,-5], "radius": 1, "material": "m"}]})");
  ASSERT_EQ(s.groups[0].geometries.size(), 2u);
  const Geometry& g = s.groups[0].geometries[1];
  EXPECT_EQ(g.kind, GeomKind::Quad);
  EXPECT_EQ(g.objectId, 1u);  // after the one object
  const Material& m = s.materials.at(g.materialId);
  EXPECT_EQ(m.name, "lights[0]");
  EXPECT_EQ(m.surface.ke.constant, (Rgb{2, 2, 2}));
  EXPECT_EQ(m.surface.emissionSides, EmissionSides::Front);
  EXPECT_FALSE(m.surface.reflectsLights());
  EXPECT_TRUE(s.features.emission);
}

TEST(SceneParse, EveryObjectType) {
  const Scene s = withObjects(R"(
    {"type": "sphere", "center": [0,1,0], "radius": 1, "material": "m"},
    {"type": "plane", "point": [0,0,0], "normal": [0,2,0], "material": "m"},
    {"type": "quad", "corner": [0,0,0], "edge1": [1,0,0], "edge2": [0,1,0], "material": "m"},
    {"type": "box", "min": [-1,0,-1], "max": [1,1,1], "material": "m"},
    {"type": "triangle", "vertices": [[0,0,0],[1,0,0],[0,1,0]], "material": "m"},
    {"type": "polygon", "vertices": [[0,0,0],[1,0,0],[1,1,0],[0,1,0]], "material": "m"},
    {"type": "mesh", "positions": [[0,0,0],[1,0,0],[0,1,0],[1,1,0]], "indices": [[0,1,2],[1,3,2]], "material": "m"},
    {"type": "mesh", "file": "meshes/wuson.obj", "material": "m"}
  )");
  ASSERT_EQ(s.groups[0].geometries.size(), 8u);
  EXPECT_EQ(s.spheres.size(), 1u);
  EXPECT_EQ(s.planes.size(), 1u);
  EXPECT_FLOAT_EQ(s.planes[0].normal.y, 1);  // normalised
  EXPECT_EQ(s.quads.size(), 1u);
  ASSERT_EQ(s.meshes.size(), 5u);
  EXPECT_EQ(s.meshes[0].triangleCount(), 12u);  // box: 6 faces × 2
  EXPECT_EQ(s.meshes[1].triangleCount(), 1u);
  EXPECT_EQ(s.meshes[2].triangleCount(), 2u);  // square polygon
  EXPECT_EQ(s.meshes[3].triangleCount(), 2u);
  EXPECT_GT(s.meshes[4].triangleCount(), 1000u);  // the Wuson model from assimp-testmodels
  for (uint32_t i = 0; i < 8; ++i) EXPECT_EQ(s.groups[0].geometries[i].objectId, i);
}

TEST(SceneParse, BoxNormalsPointOutward) {
  const Scene s =
      withObjects(R"({"type": "box", "min": [-1,-1,-1], "max": [1,1,1], "material": "m"})");
  const TriangleMesh& m = s.meshes[0];
  for (uint32_t t = 0; t < m.triangleCount(); ++t) {
    const Vec3f c = (m.vertex(t, 0) + m.vertex(t, 1) + m.vertex(t, 2)) / 3.0f;
    const Vec3f n = cross(m.vertex(t, 1) - m.vertex(t, 0), m.vertex(t, 2) - m.vertex(t, 0));
    EXPECT_GT(dot(n, c), 0) << "triangle " << t;
  }
}

TEST(SceneParse, TransformsApplyScaleRotateTranslate) {
  const Scene s = withObjects(R"(
    {"type": "sphere", "center": [1,0,0], "radius": 1, "material": "m",
     "transform": {"scale": [2,2,2], "rotate": [0,0,1,90], "translate": [0,0,5]}},
    {"type": "quad", "corner": [0,0,0], "edge1": [1,0,0], "edge2": [0,1,0], "material": "m",
     "transform": {"translate": [1,2,3]}},
    {"type": "triangle", "vertices": [[1,0,0],[0,1,0],[0,0,1]], "material": "m",
     "transform": {"matrix": [1,0,0,10, 0,1,0,0, 0,0,1,0, 0,0,0,1]}}
  )");
  // Centre (1,0,0) → ×2 → (2,0,0) → 90° about z → (0,2,0) → +(0,0,5); radius 1 × 2.
  EXPECT_NEAR(s.spheres[0].center.x, 0, 1e-6);
  EXPECT_NEAR(s.spheres[0].center.y, 2, 1e-6);
  EXPECT_NEAR(s.spheres[0].center.z, 5, 1e-6);
  EXPECT_NEAR(s.spheres[0].radius, 2, 1e-6);
  EXPECT_EQ(s.quads[0].corner, (Vec3f{1, 2, 3}));
  EXPECT_EQ(s.meshes[0].positions[0], (Vec3f{11, 0, 0}));
}

TEST(SceneParse, NonUniformSphereBecomesAnInstance) {
  const Scene s = withObjects(R"({"type": "sphere", "center": [0,0,0], "radius": 1,
      "material": "m", "transform": {"scale": [2,1,1]}})");
  ASSERT_EQ(s.instances.size(), 1u);
  EXPECT_EQ(s.groups.size(), 2u);
  EXPECT_EQ(s.groups[0].geometries[0].kind, GeomKind::Instance);
  EXPECT_EQ(s.spheres[0].radius, 1);  // the exact sphere, in object space
}

TEST(SceneParse, GroupsArePlacedByInstancesNotCopied) {
  const Scene s = withObjects(R"(
      {"type": "instance", "group": "tree", "transform": {"translate": [1,0,0]}},
      {"type": "instance", "group": "tree", "transform": {"translate": [-1,0,0]}})",
                              R"("groups": {"tree": [
          {"type": "triangle", "vertices": [[0,0,0],[1,0,0],[0,1,0]], "material": "m"}]},)");
  EXPECT_EQ(s.meshes.size(), 1u);  // one copy of the geometry
  EXPECT_EQ(s.instances.size(), 2u);
  EXPECT_EQ(s.instances[0].groupId, 1u);
  EXPECT_TRUE(s.features.instancing);
}

TEST(SceneParse, EveryBundledSceneLoads) {
  // The examples are documentation; a format change that breaks one must fail here.
  int count = 0;
  for (const auto& e : std::filesystem::directory_iterator(GLINT_SCENES_DIR)) {
    if (e.path().extension() != ".json") continue;
    ++count;
    EXPECT_NO_THROW(loadSceneFile(e.path().string())) << e.path();
  }
  EXPECT_GE(count, 4);
}

TEST(SceneParse, MeshFilesInPlyAndGltf) {
  // square.ply: the unit square as 2 triangles. triangle.gltf: one triangle (0,0,0), (2,0,0),
  // (0,2,0) under a node translated by (0,0,1): node transforms are applied at load.
  const Scene s = test::sceneFromText(R"({"camera": {"eye": [0,0,0], "look_at": [0,0,-5]},
    "materials": {"m": {"type": "phong"}}, "objects": [
      {"type": "mesh", "file": ")" + std::string(GLINT_TEST_DATA) +
                                      R"(/square.ply", "material": "m"},
      {"type": "mesh", "file": ")" + std::string(GLINT_TEST_DATA) +
                                      R"(/triangle.gltf", "material": "m"}]})");
  ASSERT_EQ(s.meshes.size(), 2u);
  EXPECT_EQ(s.meshes[0].triangleCount(), 2u);
  EXPECT_EQ(s.meshes[0].bounds().hi, (Vec3f{1, 1, 0}));
  ASSERT_EQ(s.meshes[1].triangleCount(), 1u);
  EXPECT_EQ(s.meshes[1].bounds().lo, (Vec3f{0, 0, 1}));
  EXPECT_EQ(s.meshes[1].bounds().hi, (Vec3f{2, 2, 1}));
}

TEST(SceneParse, MirroringTransformsKeepNormalsOutward) {
  // scale x by −1 mirrors: the box's triangles and the quad must keep their normals pointing
  // away from the solid (box) and along the mirrored normal (quad: (0,0,1) stays (0,0,1)).
  const Scene s = test::sceneFromText(R"({"camera": {"eye": [0,0,0], "look_at": [0,0,-5]},
    "materials": {"m": {"type": "phong"}}, "objects": [
      {"type": "box", "min": [1,-1,-1], "max": [3,1,1], "material": "m", "transform": {"scale": [-1,1,1]}},
      {"type": "quad", "corner": [0,0,0], "edge1": [1,0,0], "edge2": [0,1,0], "material": "m",
       "transform": {"scale": [-1,1,1]}}]})");
  const TriangleMesh& m = s.meshes[0];
  const Vec3f centre{-2, 0, 0};
  for (uint32_t t = 0; t < m.triangleCount(); ++t) {
    const Vec3f c = (m.vertex(t, 0) + m.vertex(t, 1) + m.vertex(t, 2)) / 3.0f;
    const Vec3f n = cross(m.vertex(t, 1) - m.vertex(t, 0), m.vertex(t, 2) - m.vertex(t, 0));
    EXPECT_GT(dot(n, c - centre), 0) << "triangle " << t;
  }
  EXPECT_GT(cross(s.quads[0].edge1, s.quads[0].edge2).z, 0);
}

TEST(SceneParse, PositionsLoadIntoRenderSpaceAroundTheEye) {
  // Everything is placed in double and shifted by −eye before rounding to float
  // (io/placement.h). At 1e5 float spacing is 0.0078, so without the shift 0.3 would come back
  // as 0.296875 or 0.3046875; with it every offset below is exact in float.
  const Scene s = test::sceneFromText(R"({
    "camera": {"eye": [100000.25, 0, 0], "look_at": [100000.25, 0, -1]},
    "materials": {"m": {"type": "phong"}},
    "lights": [{"type": "point", "position": [100000.5, 2, 0]}],
    "groups": {"g": [{"type": "sphere", "center": [0.5, 0, 0], "radius": 0.1, "material": "m"}]},
    "objects": [
      {"type": "sphere", "center": [100000.75, 0, -3], "radius": 0.1, "material": "m"},
      {"type": "quad", "corner": [100000, 1, -2], "edge1": [0.3, 0, 0], "edge2": [0, 0.3, 0],
       "material": "m"},
      {"type": "triangle", "vertices": [[0.5,0,0],[0,0.5,0],[0,0,0.5]], "material": "m",
       "transform": {"translate": [100000, 0, 0]}},
      {"type": "instance", "group": "g", "transform": {"translate": [100001, 0, 0]}},
      {"type": "instance", "group": "g",
       "motion": {"transform": [{"translate": [100001, 0, 0]}, {"translate": [100002, 0, 0]}]}}]})");
  EXPECT_EQ(s.worldOrigin, (Vec3d{100000.25, 0, 0}));
  EXPECT_EQ(s.cameraDesc.eye, (Vec3f{0, 0, 0}));
  EXPECT_EQ(s.cameraDesc.lookAt, (Vec3f{0, 0, -1}));
  EXPECT_EQ(std::get<PointLight>(s.lights[0]).position, (Vec3f{0.25f, 2, 0}));
  EXPECT_EQ(s.spheres[1].center, (Vec3f{0.5f, 0, -3}));  // spheres[0] is the group's
  EXPECT_EQ(s.quads[0].corner, (Vec3f{-0.25f, 1, -2}));
  EXPECT_EQ(s.meshes[0].positions[0], (Vec3f{0.25f, 0, 0}));  // 100000.5 − 100000.25
  // Groups keep their own space; the instances that place them are shifted.
  EXPECT_EQ(s.spheres[0].center, (Vec3f{0.5f, 0, 0}));
  EXPECT_EQ(s.instances[0].worldFromObject.matrix()(0, 3), 0.75f);
  EXPECT_EQ(s.instances[1].motion[0].translation, (Vec3f{0.75f, 0, 0}));
  EXPECT_EQ(s.instances[1].motion[1].translation, (Vec3f{1.75f, 0, 0}));
}

TEST(SceneParse, EqualMotionKeysLoadAsAStaticObject) {
  // Interpolating between equal keys in float need not return the key itself, so equal keys
  // are collapsed at load: no motion, no time steps, the static image bit for bit.
  const Scene s = test::sceneFromText(R"({"camera": {"eye": [0,0,5], "look_at": [0,0,0]},
    "materials": {"m": {"type": "phong"}},
    "objects": [{"type": "sphere", "center": [0.3,0,0], "radius": 1, "material": "m",
                 "motion": {"center": [[0.3,0,0], [0.3,0,0], [0.3,0,0]]}},
                {"type": "quad", "corner": [0,0,0], "edge1": [1,0,0], "edge2": [0,1,0],
                 "material": "m", "motion": {"transform": [{"rotate": [0,1,0,30]},
                                                           {"rotate": [0,1,0,30]}]}}]})");
  EXPECT_TRUE(s.sphereCenterKeys[0].empty());
  ASSERT_EQ(s.instances.size(), 1u);
  EXPECT_TRUE(s.instances[0].motion.empty());
  EXPECT_FALSE(s.features.motion);
}

}  // namespace
}  // namespace glint
