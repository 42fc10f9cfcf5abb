// Materials as a whole (materials/material.h): each type's defaults, and the rays a hit sends
// on (coherentRays), in Trace's order, with their weights.
#include "materials/material.h"

#include <gtest/gtest.h>

#include <vector>

namespace glint {
namespace {

ShadingPoint pointFacingUp() {
  ShadingPoint sp;
  sp.ng = sp.ns = {0, 1, 0};
  return sp;
}

// One ray a hit sends on, as forEachCoherentRay hands it over.
struct CoherentRay {
  Vec3f direction;
  Rgb weight;
  bool crosses = false;
};

// The rays material m sends on for unit d arriving at sp, from etaI into etaT.
std::vector<CoherentRay> raysFrom(const Material& m, const ShadingPoint& sp, const Vec3f& d,
                                  const SampleKey& key, float etaI = 1, float etaT = 1.5f) {
  std::vector<CoherentRay> out;
  forEachCoherentRay(m, sp, lookUp(m.surface, sp, -d, 0, {}), d, etaI, etaT, lobeSamples(m, key, 0),
                     [&](const Vec3f& direction, const Rgb& weight, bool crosses) {
                       out.push_back({direction, weight, crosses});
                     });
  EXPECT_LE(out.size(), size_t(kMaxCoherentRays));
  return out;
}

struct Arrival {
  const Sampler sampler{SamplerKind::Stratified, 1, 0};
  const SampleKey key{&sampler, 0, 0, 0};
  const ShadingPoint sp = pointFacingUp();

  // The rays material m sends on for a ray straight down.
  std::vector<CoherentRay> rays(const Material& m) const {
    return raysFrom(m, sp, {0, -1, 0}, key);
  }
};

TEST(Material, EachTypeHasItsDefaults) {
  const Material phong = defaultMaterial(MaterialKind::Phong);
  EXPECT_EQ(phong.surface.kd.constant, (Rgb{0.5f, 0.5f, 0.5f}));
  EXPECT_TRUE(phong.surface.ambientFollowsDiffuse);
  EXPECT_TRUE(phong.surface.reflectsLights());
  EXPECT_FALSE(phong.surface.reflectsCoherently() || phong.surface.emits() || phong.refracts());
  const Material mirror = defaultMaterial(MaterialKind::Mirror);
  EXPECT_EQ(mirror.surface.km.constant, (Rgb{1, 1, 1}));
  EXPECT_FALSE(mirror.surface.reflectsLights() || mirror.refracts());
  const Material glass = defaultMaterial(MaterialKind::Dielectric);
  EXPECT_TRUE(glass.refracts());
  EXPECT_EQ(glass.dielectric.ior, 1.5f);
  EXPECT_FALSE(glass.surface.reflectsLights() || glass.surface.reflectsCoherently());
}

TEST(Material, AMirrorSendsOneRayWeightedByKm) {
  Material mirror = defaultMaterial(MaterialKind::Mirror);
  mirror.surface.km = ColorTexture::uniform({0.9f, 0.8f, 0.7f});
  const auto out = Arrival{}.rays(mirror);
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(out[0].direction, (Vec3f{0, 1, 0}));
  EXPECT_EQ(out[0].weight, (Rgb{0.9f, 0.8f, 0.7f}));
  EXPECT_FALSE(out[0].crosses);
  EXPECT_TRUE(Arrival{}.rays(defaultMaterial(MaterialKind::Phong)).empty());  // k_m black: none
}

TEST(Material, GlassReflectsThenRefracts) {
  const auto out = Arrival{}.rays(defaultMaterial(MaterialKind::Dielectric));
  ASSERT_EQ(out.size(), 2u);
  // Fresnel's 0.04 back up, the other 0.96 down across the surface.
  EXPECT_EQ(out[0].direction, (Vec3f{0, 1, 0}));
  EXPECT_NEAR(out[0].weight.r, 0.04f, 1e-7);
  EXPECT_FALSE(out[0].crosses);
  EXPECT_EQ(out[1].direction, (Vec3f{0, -1, 0}));
  EXPECT_NEAR(out[1].weight.g, 0.96f, 1e-7);
  EXPECT_TRUE(out[1].crosses);
}

TEST(Material, GlassWithKmReflectsItsSurfaceFirst) {
  // The surface's k_m is a reflection of its own, before the interface's (Trace's order:
  // reflection, then refraction).
  Material glass = defaultMaterial(MaterialKind::Dielectric);
  glass.surface.km = ColorTexture::uniform({0.1f, 0.1f, 0.1f});
  const auto out = Arrival{}.rays(glass);
  ASSERT_EQ(out.size(), 3u);
  EXPECT_EQ(out[0].weight, (Rgb{0.1f, 0.1f, 0.1f}));
  EXPECT_NEAR(out[1].weight.b, 0.04f, 1e-7);
  EXPECT_TRUE(out[2].crosses);
}

TEST(Material, TotalInternalReflectionSendsOneRay) {
  // Straight down at a 45° tilted surface from inside glass: past the critical angle.
  Arrival hit;
  const Material glass = defaultMaterial(MaterialKind::Dielectric);
  ShadingPoint sp;
  sp.ng = sp.ns = normalize(Vec3f{1, 1, 0});
  const auto out = raysFrom(glass, sp, {0, -1, 0}, hit.key, 1.5f, 1);
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(out[0].weight, (Rgb{1, 1, 1}));
  EXPECT_NEAR(out[0].direction.x, 1, 1e-6);  // reflected off the 45° face: sideways
}

TEST(Material, CoherentGainIsTheMostTheRaysWeightsAddUpTo) {
  // coherentGain bounds, in every channel, the summed weights of the rays a hit sends: the
  // integrators divide a branch's share by it where it is above 1 (integrator/radiance.h).
  // Each case: the material, and its gain from k_m (+ 1 for a Fresnel interface, + k_t with
  // constant coefficients).
  Material mirror = defaultMaterial(MaterialKind::Mirror);
  mirror.surface.km = ColorTexture::uniform({0.9f, 0.8f, 0.7f});
  Material coated = defaultMaterial(MaterialKind::Dielectric);
  coated.surface.km = ColorTexture::uniform({0.2f, 0.5f, 0.1f});
  // distributed_shading.json's slab: k_m + k_t stays at or below 1, so it gains nothing.
  Material slab = defaultMaterial(MaterialKind::Dielectric);
  slab.dielectric.fresnel = FresnelModel::None;
  slab.dielectric.kt = {0.55f, 0.75f, 0.9f};
  slab.surface.km = ColorTexture::uniform({0.08f, 0.08f, 0.08f});
  Material bright = slab;
  bright.dielectric.kt = {1, 1, 1};
  bright.surface.km = ColorTexture::uniform({0.6f, 0.6f, 0.6f});
  const struct {
    const char* name;
    Material m;
    float gain;
  } cases[] = {{"phong", defaultMaterial(MaterialKind::Phong), 0},
               {"mirror", mirror, 0.9f},
               {"glass", defaultMaterial(MaterialKind::Dielectric), 1},
               {"coated glass", coated, 1.5f},
               {"slab", slab, 0.98f},
               {"bright slab", bright, 1.6f}};
  const Arrival hit;
  for (const auto& c : cases) {
    const SurfacePoint at = lookUp(c.m.surface, hit.sp, {0, 1, 0}, 0, {});
    const float gain = coherentGain(c.m, at);
    EXPECT_NEAR(gain, c.gain, 1e-6) << c.name;
    Rgb sum;
    for (const CoherentRay& ray : hit.rays(c.m)) sum += ray.weight;
    // Fresnel's R and 1 − R add to 1 within a rounding.
    EXPECT_LE(sum.maxChannel(), gain + 1e-6f) << c.name;
  }
}

TEST(Material, BlurredRefractionThatTurnsBackIsDropped) {
  // A frosted glass with a square far wider than the refracted ray's angle to the surface: some
  // perturbed rays end up on the incoming side and return black; the others still cross.
  Material frosted = defaultMaterial(MaterialKind::Dielectric);
  frosted.dielectric.blur = 40;
  ShadingPoint sp;
  sp.ng = sp.ns = {0, 1, 0};
  const Vec3f d = normalize(Vec3f{1, -0.05f, 0});  // grazing
  int dropped = 0, crossing = 0;
  for (int i = 0; i < 64; ++i) {
    const Sampler sampler(SamplerKind::Random, 1, static_cast<uint64_t>(i));
    const SampleKey key(&sampler, 0, 0, 0);
    const auto out = raysFrom(frosted, sp, d, key);
    if (out.size() == 2) {
      EXPECT_LT(out[1].direction.y, 0);  // a kept refracted ray goes into the glass
      ++crossing;
    } else {
      EXPECT_EQ(out.size(), 1u);
      ++dropped;
    }
  }
  EXPECT_GT(dropped, 0);
  EXPECT_GT(crossing, 0);
}

TEST(Material, LobeSamplesDrawnTogetherAreEachRaysOwn) {
  // The kernel draws a chunk's lobe samples side by side (drawLobeSamples); each must be the
  // sample the reference integrator draws for that ray alone (lobeSamples), bit for bit, or
  // the two integrators' images part. Rays of several pixels and both halves (of different
  // sizes at an odd spp), runs of one pixel half, and materials drawing none, one or both.
  // Whatever the order: the kernel writes each to its ray's slot.
  Material phong = defaultMaterial(MaterialKind::Phong);
  Material glossy = defaultMaterial(MaterialKind::Mirror);
  glossy.surface.gloss = 0.2f;
  Material frosted = defaultMaterial(MaterialKind::Dielectric);
  frosted.dielectric.blur = 0.3f;
  Material both = frosted;
  both.surface.km = ColorTexture::uniform({0.2f, 0.2f, 0.2f});
  both.surface.gloss = 12;
  both.surface.glossShape = GlossShape::Phong;
  const Material* kinds[] = {&glossy, &frosted, &both, &phong};
  for (SamplerKind kind : {SamplerKind::Stratified, SamplerKind::Sobol, SamplerKind::Random}) {
    const Sampler sampler(kind, 7, 3);
    constexpr int kRays = 40;
    SampleKey keys[kRays];
    const SampleKey* keyOf[kRays];
    const Material* materialOf[kRays];
    int slot[kRays];
    for (int i = 0; i < kRays; ++i) {
      const int px = i / 9, half = (i / 3) % 2;
      keys[i] = SampleKey(&sampler, px, 2, i % 3, sampler.pixelKey(px, 2), half);
      keyOf[i] = &keys[i];
      materialOf[i] = kinds[(i * 7) % 4];
      slot[i] = kRays - 1 - i;  // written out of order, as the kernel's rays that draw
    }
    LobeSamples out[kRays];
    drawLobeSamples(materialOf, keyOf, slot, 2, kRays, out);
    for (int i = 0; i < kRays; ++i) {
      const LobeSamples alone = lobeSamples(*materialOf[i], keys[i], 2);
      const LobeSamples& drawn = out[slot[i]];
      EXPECT_EQ(drawn.gloss.x, alone.gloss.x) << i;
      EXPECT_EQ(drawn.gloss.y, alone.gloss.y) << i;
      EXPECT_EQ(drawn.blur.x, alone.blur.x) << i;
      EXPECT_EQ(drawn.blur.y, alone.blur.y) << i;
    }
    // Not a vacuous match: the glossy and blurred rays did draw.
    EXPECT_NE(out[slot[0]].gloss.x, 0.0f);  // glossy
    EXPECT_NE(out[slot[2]].gloss.x, 0.0f);  // both
    EXPECT_NE(out[slot[2]].blur.x, 0.0f);
    EXPECT_NE(out[slot[3]].blur.x, 0.0f);  // frosted
  }
}

TEST(Material, AlbedoIsKdElseKmAndOneForGlass) {
  const Arrival hit;
  Material m = defaultMaterial(MaterialKind::Phong);
  EXPECT_EQ(albedo(m, lookUp(m.surface, hit.sp, {0, 1, 0}, 0, {})), (Rgb{0.5f, 0.5f, 0.5f}));
  m = defaultMaterial(MaterialKind::Mirror);
  EXPECT_EQ(albedo(m, lookUp(m.surface, hit.sp, {0, 1, 0}, 0, {})), (Rgb{1, 1, 1}));
  m = defaultMaterial(MaterialKind::Dielectric);
  EXPECT_EQ(albedo(m, lookUp(m.surface, hit.sp, {0, 1, 0}, 0, {})), (Rgb{1, 1, 1}));
}

}  // namespace
}  // namespace glint
