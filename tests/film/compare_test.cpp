// The one image-comparison routine against hand-computed metrics.
#include <gtest/gtest.h>

#include "film/compare.h"
#include "test_util.h"

namespace glint {
namespace {

Image constant(int w, int h, float r, float g, float b) {
  Image img;
  img.width = w;
  img.height = h;
  img.channels = 4;
  img.pixels.resize(size_t(w) * size_t(h) * 4);
  for (size_t i = 0; i < img.pixels.size(); i += 4) {
    img.pixels[i] = r;
    img.pixels[i + 1] = g;
    img.pixels[i + 2] = b;
    img.pixels[i + 3] = 1;
  }
  return img;
}

TEST(Compare, ConstantOffset) {
  // Every channel off by 0.1 against a reference of 0.4: RMSE = MAE = max = 0.1;
  // relMSE = 0.01 / (0.16 + 0.01); PSNR = 10·log10(1/0.01) = 20 dB; every pixel above 0.05.
  const ImageErrors e =
      compareImages(constant(4, 3, 0.5f, 0.5f, 0.5f), constant(4, 3, 0.4f, 0.4f, 0.4f), 0.05);
  EXPECT_NEAR(e.rmse, 0.1, 1e-7);
  EXPECT_NEAR(e.mae, 0.1, 1e-7);
  EXPECT_NEAR(e.maxAbs, 0.1, 1e-7);
  EXPECT_NEAR(e.relmse, 0.01 / 0.17, 1e-6);
  EXPECT_NEAR(e.psnr, 20, 1e-5);
  EXPECT_EQ(e.aboveThreshold, 1.0);
  EXPECT_EQ(e.pixels, 12u);
}

TEST(Compare, OnePixelOffAndIdentical) {
  Image a = constant(2, 2, 0, 0, 0), b = a;
  EXPECT_EQ(compareImages(a, b).rmse, 0.0);
  EXPECT_TRUE(std::isinf(compareImages(a, b).psnr));
  a.pixels[0] = 1;  // one channel of one pixel off by 1: MSE = 1/12, share above = 1/4
  const ImageErrors e = compareImages(a, b);
  EXPECT_NEAR(e.rmse, std::sqrt(1.0 / 12), 1e-12);
  EXPECT_NEAR(e.maxAbs, 1, 0);
  EXPECT_EQ(e.aboveThreshold, 0.25);
  EXPECT_EQ(e.nonfinitePixels, 0u);
  a.pixels[4] = std::nanf("");  // a non-finite value is an infinite error, not a silent pass
  EXPECT_TRUE(std::isinf(compareImages(a, b).maxAbs));
  // ... and counted, so that a null PSNR from it is told from identical images' +∞: the NaN in
  // the test image and an infinity in the reference, two pixels.
  b.pixels[8] = std::numeric_limits<float>::infinity();
  const ImageErrors broken = compareImages(a, b, 1e-2, {"a.exr", "b.exr"});
  EXPECT_EQ(broken.nonfinitePixels, 2u);
  EXPECT_EQ(nonfiniteNote(broken, {"a.exr", "b.exr"}),
            "a.exr against b.exr: 2 of 4 pixels hold a NaN or infinite R, G or B, whose errors "
            "count as infinite");
}

TEST(Compare, AnInfinityInTheReferenceAloneIsAnInfiniteErrorInEveryMeasure) {
  // The relative MSE divides by the reference's square: ∞/∞ would make it NaN, which reads as
  // "not measured", where the test image's own infinity gives +∞.
  Image a = constant(2, 2, 0.5f, 0.5f, 0.5f), b = a;
  b.pixels[5] = std::numeric_limits<float>::infinity();
  const ImageErrors e = compareImages(a, b);
  EXPECT_EQ(e.nonfinitePixels, 1u);
  for (const double v : {e.rmse, e.relmse, e.mae, e.maxAbs})
    EXPECT_EQ(v, std::numeric_limits<double>::infinity());
  EXPECT_EQ(compareImages(b, a).relmse, std::numeric_limits<double>::infinity());
}

TEST(Compare, SizeMismatchIsAUsageErrorNamingBothImages) {
  EXPECT_THROW(compareImages(constant(2, 2, 0, 0, 0), constant(2, 3, 0, 0, 0)), UsageError);
  try {
    compareImages(constant(2, 2, 0, 0, 0), constant(2, 3, 0, 0, 0), 1e-2, {"t.exr", "r.exr"});
    ADD_FAILURE() << "images of other sizes were compared";
  } catch (const UsageError& e) {
    EXPECT_STREQ(e.what(), "images differ in size: t.exr is 2x2, r.exr 2x3");
  }
}

TEST(Compare, CommandLineWritesJsonAndDiff) {
  const auto dir = test::tempDir();
  const std::string scene =
      test::writeTemp("cmp.json", R"({"render": {"width": 16, "height": 8, "spp": 1},
    "camera": {"eye": [0,0,5], "look_at": [0,0,0]}, "materials": {"m": {"type": "phong"}},
    "lights": [{"type": "point", "position": [1,2,3]}],
    "objects": [{"type": "sphere", "center": [0,0,0], "radius": 1, "material": "m"}]})");
  ASSERT_EQ(test::runGlint("render " + scene + " --quiet -o " + (dir / "a.exr").string()).exitCode,
            0);
  ASSERT_EQ(test::runGlint("render " + scene + " --quiet --spp 4 -o " + (dir / "b.exr").string())
                .exitCode,
            0);
  const auto r = test::runGlint("compare " + (dir / "a.exr").string() + " " +
                                (dir / "b.exr").string() + " --json " + (dir / "c.json").string() +
                                " --diff " + (dir / "d.png").string());
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_TRUE(std::filesystem::exists(dir / "d.png"));
  std::ifstream f(dir / "c.json");
  const std::string json((std::istreambuf_iterator<char>(f)), {});
  for (const char* key : {"\"rmse\"", "\"relmse\"", "\"mae\"", "\"max_abs\"", "\"psnr\""})
    EXPECT_NE(json.find(key), std::string::npos) << key;
}

}  // namespace
}  // namespace glint
