// What a scene uses (scene/features.h): which materials read texture coordinates, and that
// only their hits compute them.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <limits>
#include <vector>

#include "film/image_file.h"
#include "io/scene_loader.h"
#include "scene/scene.h"
#include "test_util.h"

namespace glint {
namespace {

// Three materials on three quads seen head on: a constant colour, an image in kd, a normal
// map; the image is 2 × 2 mid grey (any image will do: only the slot's kind matters here).
Scene threeQuads() {
  const std::string image = (test::tempDir() / "features_grey.png").string();
  // Written once: a file the run has read may not be replaced (core/input_files.h).
  if (!std::filesystem::exists(image))
    writeRgbImage(image, 2, 2, 8, std::vector<uint16_t>(12, 128));
  const std::string text = R"({
    "camera": {"eye": [0, 0, 5], "look_at": [0, 0, 0]},
    "materials": {
      "plain": {"type": "phong", "kd": [0.5, 0.5, 0.5]},
      "textured": {"type": "phong", "kd": {"image": "features_grey.png"}},
      "mapped": {"type": "phong", "kd": [0.5, 0.5, 0.5],
                 "normal_map": {"image": "features_grey.png"}}
    },
    "objects": [
      {"type": "quad", "corner": [-3, 0, 0], "edge1": [1, 0, 0], "edge2": [0, 1, 0],
       "material": "plain"},
      {"type": "quad", "corner": [0, 0, 0], "edge1": [1, 0, 0], "edge2": [0, 1, 0],
       "material": "textured"},
      {"type": "quad", "corner": [3, 0, 0], "edge1": [1, 0, 0], "edge2": [0, 1, 0],
       "material": "mapped"}
    ]})";
  return loadSceneText(text, test::writeTemp("features.json", text), test::tempDir().string());
}

// The material id a quad's entry in the world carries.
uint32_t quadMaterial(const Scene& s, uint32_t quad) {
  for (const Geometry& g : s.groups[0].geometries)
    if (g.kind == GeomKind::Quad && g.index == quad) return g.materialId;
  ADD_FAILURE() << "no quad " << quad;
  return 0;
}

TEST(Features, OnlyMaterialsWithImagesOrMapsReadTextureCoordinates) {
  const Scene s = threeQuads();
  EXPECT_TRUE(s.features.surfaceCoordinates);
  EXPECT_FALSE(s.features.readsCoordinates(quadMaterial(s, 0)));
  EXPECT_TRUE(s.features.readsCoordinates(quadMaterial(s, 1)));
  EXPECT_TRUE(s.features.readsCoordinates(quadMaterial(s, 2)));
  // An id the list does not hold (a scene built by hand): read, to be safe.
  EXPECT_TRUE(s.features.readsCoordinates(std::numeric_limits<uint32_t>::max()));
}

TEST(Features, OnlyHitsOnMaterialsThatReadThemComputeTextureCoordinates) {
  const Scene s = threeQuads();
  // A quad's (u, v) is the hit's own (u, v) and its tangents are its edges: (0.25, 0.75) and
  // (1, 0, 0), (0, 1, 0) exactly where computed. On the plain quad they keep the values a
  // ShadingPoint starts with, marked here by NaN.
  for (uint32_t quad = 0; quad < 3; ++quad) {
    uint32_t entry = 0;
    while (s.groups[0].geometries[entry].kind != GeomKind::Quad ||
           s.groups[0].geometries[entry].index != quad)
      ++entry;
    const float x = -3.0f + 3.0f * float(quad) + 0.25f;
    const Ray ray{{x, 0.75f, 5}, {0, 0, -1}};
    const Hit hit{5, 0.25f, 0.75f, entry, 0, kInvalidId};
    ShadingPoint sp;
    const float nan = std::numeric_limits<float>::quiet_NaN();
    sp.uv = {nan, nan};
    s.shadingPoint(ray, hit, sp);
    if (quad == 0) {
      EXPECT_TRUE(std::isnan(sp.uv.x)) << "the plain quad computed its coordinates";
    } else {
      EXPECT_EQ(sp.uv.x, 0.25f) << quad;
      EXPECT_EQ(sp.uv.y, 0.75f) << quad;
      EXPECT_EQ(sp.dpdu.x, 1.0f) << quad;
      EXPECT_EQ(sp.dpdv.y, 1.0f) << quad;
    }
  }
}

}  // namespace
}  // namespace glint
