// The frame record (render/frame_record.h): every field written reads back as written, and each
// field a frame may hold wrongly is refused by name, with the file.
#include "render/frame_record.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <functional>
#include <string>
#include <vector>

#include "core/error.h"
#include "film/exr_output.h"
#include "scene/scene.h"
#include "test_util.h"

namespace glint {
namespace {

std::string tmp(const std::string& name) { return (test::tempDir() / name).string(); }

// The error `f` throws, or "(accepted)".
std::string errorOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const GlintError& e) {
    return e.what();
  }
  return "(accepted)";
}

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

// A 4 x 3 frame's crop [1, 3) x [0, 2), resumable: a still scene of 8 spp, continued to any
// spp (Sobol), with a target.
struct Fixture {
  Scene scene;
  FrameSettings settings;
  PassPlan plan;
  PixelWindow window{1, 3, 0, 2};
  std::vector<PixelEstimate> estimates;
  PassPosition position;
  FrameRecord record;

  Fixture() {
    scene.sourcePath = "frames/a.json";
    scene.sourceHash = 0x0123456789abcdefULL;
    scene.render.width = 4;
    scene.render.height = 3;
    scene.render.spp = 8;
    scene.render.maxDepth = 5;
    scene.render.seed = 9223372036854775813ULL;  // 2^63 + 5: past a double's exact integers
    scene.render.sampler = SamplerKind::Sobol;
    settings.accel = "bvh";
    settings.integrator = "production";
    settings.aovs = "variance";
    settings.sampling.target.relmse = 0.01;
    settings.sampling.progressive = true;
    settings.commandLine = "glint render a.json --crop 1 3 0 2";
    plan = PassPlan::make(8, SamplerKind::Sobol, settings.sampling);
    // Passes finished to 4 spp, the pass to 8 cut with pixels 0 and 3 chosen: those may hold
    // more than 4 samples, up to 8.
    position = {4, 8, {1, 0, 0, 1}};
    for (const int samples : {6, 4, 4, 5}) {
      PixelEstimate e;
      for (int h = 0; h < 2; ++h) {
        HalfEstimate& half = e.half[h];
        half.count = halfSampleCount(samples, h);
        half.mean[0] = 0.25 * (h + 1);
        half.mean[1] = 0.5;
        half.mean[2] = 0.75;
        half.alpha = half.count;
        half.rays = 3 * uint64_t(half.count);
      }
      estimates.push_back(e);
    }
    FrameRecord& r = record;
    r.version = "0.1.0-test";
    r.scene = scene.sourcePath;
    r.sceneHash = "0123456789abcdef";
    r.settingsHash = "fedcba9876543210";
    r.integrator = "production";
    r.sampler = SamplerKind::Sobol;
    PassRecord first{2, 2.0, 0.25, {0.5, 0.125}, 4};
    PassRecord second{4, 3.5, 0.75, {std::nullopt, std::nullopt}, 3};
    r.passes = std::vector<PassRecord>{first, second};
    r.resumeHash = resumeHash(scene, settings, plan);
    r.resumeSampling = "target-relmse 0.01";
    r.accel = "bvh";
    r.seed = scene.render.seed;
    r.crop = window;
    r.commandLine = settings.commandLine;
    r.colorspace = "lin_rec709";
    r.spp = 8;
    r.maxSpp = 64;
    r.timeLimitSeconds = 2.5f;
    r.maxDepth = 5;
    r.partial = true;
    r.minPixelSpp = 4;
    r.maxPixelSpp = 6;
    r.frame = -3;
    r.renderSeconds = 1.5f;
    r.rays = 57.0f;
    r.estimatedRmse = 0.5f;
    r.estimatedRelmse = 0.125f;
    Mat4 toCamera, toNdc;
    for (int i = 0; i < 16; ++i) {
      toCamera.m[size_t(i)] = float(i) / 4;  // quarters: exact in a float
      toNdc.m[size_t(i)] = -float(i) / 8;
    }
    r.worldToCamera = toCamera;
    r.worldToNdc = toNdc;
    r.pixelAspectRatio = 0.75f;
    r.frameWidth = 4;
    r.frameHeight = 3;
  }

  // Writes the record and the state to `name`, `edit` changing the metadata first.
  std::string write(const std::string& name,
                    const std::function<void(ExrMetadata&)>& edit = nullptr,
                    bool withState = true) const {
    Film film(4, 3, window);
    for (int y = window.y0; y < window.y1; ++y)
      for (int x = window.x0; x < window.x1; ++x) film.setPixel(x, y, 0.5, 0.5, 0.5, 1);
    ExrMetadata m;
    writeFrameRecord(record, m);
    if (withState) writeResumeState(film, m, estimates, position, record);
    if (edit) edit(m);
    const std::string path = tmp(name);
    writeExr(path, film, m);
    return path;
  }

  ResumedFrame resume(const std::string& path, const FrameSettings& s) const {
    return readResumable(path, scene, s, plan, window);
  }
};

// Leaves `key` out of the metadata, whatever its type.
void drop(ExrMetadata& m, const std::string& key) {
  const auto named = [&](const auto& kv) { return kv.first == key; };
  std::erase_if(m.strings, named);
  std::erase_if(m.ints, named);
  std::erase_if(m.floats, named);
  std::erase_if(m.matrices, named);
}

void setText(ExrMetadata& m, const std::string& key, const std::string& value) {
  drop(m, key);
  m.strings.emplace_back(key, value);
}

void setInt(ExrMetadata& m, const std::string& key, int value) {
  drop(m, key);
  m.ints.emplace_back(key, value);
}

TEST(FrameRecord, EveryFieldReadsBackAsWritten) {
  const Fixture f;
  const std::string path = f.write("record-whole.exr");
  const FrameRecord r = readFrameRecord(path);
  EXPECT_EQ(r.version, "0.1.0-test");
  EXPECT_EQ(r.scene, "frames/a.json");
  EXPECT_EQ(r.sceneHash, "0123456789abcdef");
  EXPECT_EQ(r.settingsHash, "fedcba9876543210");
  EXPECT_EQ(r.integrator, "production");
  EXPECT_EQ(r.sampler, SamplerKind::Sobol);
  ASSERT_TRUE(r.passes && r.passes->size() == 2);
  const PassRecord& p0 = (*r.passes)[0];
  const PassRecord& p1 = (*r.passes)[1];
  EXPECT_EQ(p0.spp, 2);
  EXPECT_EQ(p0.meanSpp, 2.0);
  EXPECT_EQ(p0.seconds, 0.25);
  EXPECT_EQ(p0.estimated.rmse, 0.5);
  EXPECT_EQ(p0.estimated.relmse, 0.125);
  EXPECT_EQ(p0.pixelsSampled, 4);
  EXPECT_EQ(p1.spp, 4);
  EXPECT_EQ(p1.meanSpp, 3.5);
  EXPECT_EQ(p1.seconds, 0.75);
  EXPECT_FALSE(p1.estimated.rmse);  // null: a pass without an estimate stays without one
  EXPECT_FALSE(p1.estimated.relmse);
  EXPECT_EQ(p1.pixelsSampled, 3);
  EXPECT_EQ(r.resumeHash, f.record.resumeHash);
  EXPECT_EQ(r.resumeSampling, "target-relmse 0.01");
  EXPECT_EQ(r.accel, "bvh");
  EXPECT_EQ(r.seed, 9223372036854775813ULL);  // exact: kept as text
  ASSERT_TRUE(r.crop);
  EXPECT_EQ(r.crop->x0, 1);
  EXPECT_EQ(r.crop->x1, 3);
  EXPECT_EQ(r.crop->y0, 0);
  EXPECT_EQ(r.crop->y1, 2);
  EXPECT_EQ(r.commandLine, "glint render a.json --crop 1 3 0 2");
  EXPECT_EQ(r.colorspace, "lin_rec709");
  EXPECT_EQ(r.spp, 8);
  EXPECT_EQ(r.maxSpp, 64);
  EXPECT_EQ(r.timeLimitSeconds, 2.5f);
  EXPECT_EQ(r.maxDepth, 5);
  EXPECT_EQ(r.partial, true);
  EXPECT_EQ(r.minPixelSpp, 4);
  EXPECT_EQ(r.maxPixelSpp, 6);
  EXPECT_EQ(r.frame, -3);
  EXPECT_EQ(r.renderSeconds, 1.5f);
  EXPECT_EQ(r.rays, 57.0f);
  EXPECT_EQ(r.estimatedRmse, 0.5f);
  EXPECT_EQ(r.estimatedRelmse, 0.125f);
  ASSERT_TRUE(r.worldToCamera && r.worldToNdc);
  EXPECT_EQ(r.worldToCamera->m[6], 1.5f);   // row 1, column 2: 6 / 4
  EXPECT_EQ(r.worldToNdc->m[13], -1.625f);  // row 3, column 1: -13 / 8
  EXPECT_EQ(r.worldToCamera, f.record.worldToCamera);
  EXPECT_EQ(r.worldToNdc, f.record.worldToNdc);
  EXPECT_EQ(r.pixelAspectRatio, 0.75f);
  EXPECT_EQ(r.frameWidth, 4);
  EXPECT_EQ(r.frameHeight, 3);
  // Written with the pixels: writeExr counts no clamped value, the state its checksum.
  EXPECT_EQ(r.clampedValues, 0);
  EXPECT_FALSE(r.mergedCrops);
  EXPECT_TRUE(r.resumeChecksum);
  EXPECT_TRUE(r.holdsState);
  FrameRecord expected = f.record;
  expected.clampedValues = 0;
  expected.resumeChecksum = r.resumeChecksum;
  expected.holdsState = true;
  EXPECT_TRUE(r == expected);

  // The state and the passes --resume continues from, bit for bit.
  const ResumedFrame resumed = f.resume(path, f.settings);
  EXPECT_EQ(resumed.state.position, f.position);
  ASSERT_EQ(resumed.state.estimates.size(), 4u);
  for (size_t p = 0; p < 4; ++p)
    for (int h = 0; h < 2; ++h) {
      const HalfEstimate &got = resumed.state.estimates[p].half[h], &want = f.estimates[p].half[h];
      EXPECT_EQ(got.count, want.count) << p << " " << h;
      EXPECT_EQ(got.rays, want.rays) << p << " " << h;
      EXPECT_EQ(got.alpha, want.alpha) << p << " " << h;
      for (int c = 0; c < 3; ++c) EXPECT_EQ(got.mean[c], want.mean[c]) << p << " " << h;
    }
  ASSERT_EQ(resumed.passes.size(), 2u);
  EXPECT_EQ(resumed.passes[1].spp, 4);

  // Merge's share of it.
  const CropRecord crop = cropRecord(path);
  EXPECT_EQ(crop.settingsHash, "fedcba9876543210");
  EXPECT_EQ(crop.sceneHash, "0123456789abcdef");
  EXPECT_TRUE(crop.partial);
  EXPECT_EQ(crop.renderSeconds, 1.5f);
  EXPECT_EQ(crop.rays, 57.0f);
}

TEST(FrameRecord, AttributesAFrameLacksAreAbsentNotInvented) {
  // A crop another tool wrote may carry glint:settings_hash alone, any text; merge asks for no
  // more (ExrInput.NegativeAndOutsideDataWindowsAreReadOrRefusedByMerge).
  Fixture f;
  f.record = FrameRecord{};
  f.record.settingsHash = "abc";
  const std::string path = f.write("record-bare.exr", nullptr, false);
  const FrameRecord r = readFrameRecord(path);
  EXPECT_EQ(r.settingsHash, "abc");
  EXPECT_FALSE(r.passes);
  EXPECT_FALSE(r.seed);
  EXPECT_FALSE(r.partial);
  EXPECT_FALSE(r.holdsState);
  const CropRecord crop = cropRecord(path);
  EXPECT_EQ(crop.sceneHash, "");
  EXPECT_FALSE(crop.partial);
  EXPECT_EQ(crop.renderSeconds, 0.0f);
}

TEST(FrameRecord, AnAttributeNotAsGlintWritesItIsRefusedByName) {
  const Fixture f;
  struct Case {
    std::string name;
    std::function<void(ExrMetadata&)> edit;
    std::string says;
  };
  const std::vector<Case> cases = {
      // Another type than Glint writes.
      {"seed-int", [](ExrMetadata& m) { setInt(m, "glint:seed", 7); },
       "glint:seed is of type int, not string"},
      {"spp-text", [](ExrMetadata& m) { setText(m, "glint:spp", "8"); },
       "glint:spp is of type string, not int"},
      // Malformed values.
      {"seed-sign", [](ExrMetadata& m) { setText(m, "glint:seed", "-1"); },
       "glint:seed is \"-1\", not a whole number from 0 to 2^64 - 1"},
      {"hash-short", [](ExrMetadata& m) { setText(m, "glint:resume_hash", "abc"); },
       "glint:resume_hash is \"abc\", not 16 lowercase hex digits"},
      {"settings-hash-int", [](ExrMetadata& m) { setInt(m, "glint:settings_hash", 7); },
       "glint:settings_hash is of type int, not string"},
      {"crop-three", [](ExrMetadata& m) { setText(m, "glint:crop", "1 3 0"); },
       "glint:crop is \"1 3 0\", not a window"},
      {"crop-empty", [](ExrMetadata& m) { setText(m, "glint:crop", "3 1 0 2"); },
       "glint:crop is \"3 1 0 2\", not a window"},
      {"sampler", [](ExrMetadata& m) { setText(m, "glint:sampler", "halton"); },
       "glint:sampler is \"halton\", not regular, random, stratified or sobol"},
      {"integrator", [](ExrMetadata& m) { setText(m, "glint:integrator", "fast"); },
       "glint:integrator is \"fast\", not production or reference"},
      {"partial", [](ExrMetadata& m) { setInt(m, "glint:partial", 2); },
       "glint:partial is 2, not from 0 to 1"},
      {"finished-end-text", [](ExrMetadata& m) { setText(m, "glint:resume_finished_end", "4"); },
       "glint:resume_finished_end is of type string, not int"},
      // A malformed glint:passes entry: the entry and its field are named.
      {"passes-not-json", [](ExrMetadata& m) { setText(m, "glint:passes", "[{"); },
       "its glint:passes is not JSON"},
      {"passes-object", [](ExrMetadata& m) { setText(m, "glint:passes", R"({"spp": 2})"); },
       "its glint:passes is not a list of passes"},
      {"passes-entry",
       [](ExrMetadata& m) {
         setText(m, "glint:passes",
                 R"([{"spp": 2, "mean_spp": 2, "seconds": 0.1, "estimated_rmse": 0.1,
                      "estimated_relmse": 0.1, "pixels_sampled": 4},
                     {"spp": 4, "mean_spp": 3, "seconds": "soon", "estimated_rmse": 0.1,
                      "estimated_relmse": 0.1, "pixels_sampled": 4}])");
       },
       "glint:passes[1].seconds is not a number"},
      {"passes-key",
       [](ExrMetadata& m) {
         setText(m, "glint:passes",
                 R"([{"spp": 2, "mean_spp": 2, "seconds": 0.1, "estimated_rmse": null,
                      "estimated_relmse": null}])");
       },
       "glint:passes[0] has no \"pixels_sampled\""},
      {"passes-spp",
       [](ExrMetadata& m) {
         setText(m, "glint:passes",
                 R"([{"spp": 2.5, "mean_spp": 2, "seconds": 0.1, "estimated_rmse": null,
                      "estimated_relmse": null, "pixels_sampled": 4}])");
       },
       "glint:passes[0].spp is not a whole number"},
  };
  for (const Case& c : cases) {
    const std::string path = f.write("record-" + c.name + ".exr", c.edit);
    const std::string error = errorOf([&] { readFrameRecord(path); });
    EXPECT_TRUE(contains(error, path + ": ")) << c.name << ": " << error;
    EXPECT_TRUE(contains(error, c.says)) << c.name << ": " << error;
    // --resume and merge read through the same reader, so they refuse it alike.
    EXPECT_EQ(errorOf([&] { f.resume(path, f.settings); }), error) << c.name;
    EXPECT_EQ(errorOf([&] { cropRecord(path); }), error) << c.name;
  }
}

TEST(FrameRecord, ResumeRefusesAFrameItCannotContinueNamingWhy) {
  const Fixture f;
  // No resume hash, no checksum: written by no Glint that keeps where its passes stood.
  const std::string noHash =
      f.write("resume-no-hash.exr", [](ExrMetadata& m) { drop(m, "glint:resume_hash"); });
  EXPECT_TRUE(contains(errorOf([&] { f.resume(noHash, f.settings); }),
                       noHash + " has no glint:resume_hash"));
  const std::string noChecksum =
      f.write("resume-no-checksum.exr", [](ExrMetadata& m) { drop(m, "glint:resume_checksum"); });
  EXPECT_TRUE(contains(errorOf([&] { f.resume(noChecksum, f.settings); }),
                       noChecksum + " was left by an older Glint"));
  // No state at all.
  const std::string plain = f.write("resume-plain.exr", nullptr, false);
  EXPECT_TRUE(
      contains(errorOf([&] { f.resume(plain, f.settings); }), plain + " holds no resume state"));
  // The checksum of another state: the state was edited, or is another frame's.
  const std::string edited = f.write("resume-checksum.exr", [](ExrMetadata& m) {
    setText(m, "glint:resume_checksum", "0000000000000000");
  });
  EXPECT_TRUE(contains(errorOf([&] { f.resume(edited, f.settings); }),
                       edited + "'s resume state is not the one its render wrote"));
  // Another backend changes the resume hash; the record names what differs.
  const std::string whole = f.write("resume-whole.exr");
  FrameSettings embree = f.settings;
  embree.accel = "embree";
  EXPECT_TRUE(contains(errorOf([&] { f.resume(whole, embree); }),
                       whole + " differs from this render (backend: the frame's bvh, this "
                               "render's embree)"));
  // A frame whose hash was made with sample revision 1: the samples are drawn otherwise now.
  Fixture older;
  older.record.resumeHash = resumeHash(older.scene, older.settings, older.plan, 1);
  ASSERT_NE(older.record.resumeHash, f.record.resumeHash);
  const std::string revision = older.write("resume-revision.exr");
  EXPECT_TRUE(contains(errorOf([&] { older.resume(revision, older.settings); }),
                       revision + " was left by a Glint that draws or shades samples otherwise "
                                  "(sample revision 1, this Glint's 2)"));
  // A plain render's partial frame drew from stratified sets, which a time-limited (adaptive,
  // --resumable) continuation cannot extend: the refusal says so, where it had claimed that
  // every setting but --time-limit may differ and named only the samplers.
  Fixture stratified;
  stratified.scene.render.sampler = SamplerKind::Stratified;
  stratified.settings.sampling = {};
  stratified.plan = PassPlan::make(8, SamplerKind::Stratified, stratified.settings.sampling);
  stratified.record.sampler = SamplerKind::Stratified;
  stratified.record.resumeHash = resumeHash(stratified.scene, stratified.settings, stratified.plan);
  const std::string plainPartial = stratified.write("resume-stratified.exr");
  const std::string timeLimited =
      errorOf([&] { readResumable(plainPartial, stratified.scene, f.settings, f.plan, f.window); });
  EXPECT_TRUE(contains(timeLimited, "sampler: the frame's stratified, this render's sobol"))
      << timeLimited;
  EXPECT_TRUE(contains(timeLimited,
                       "which cannot continue the frame's stratified sets: resume "
                       "it without them"))
      << timeLimited;
}

TEST(FrameRecord, StateChannelsOfAnotherShapeAreRefused) {
  const Fixture f;
  // Another window than this render's crop.
  const std::string whole = f.write("shape-window.exr");
  EXPECT_TRUE(contains(errorOf([&] {
                         readResumable(whole, f.scene, f.settings, f.plan, PixelWindow{0, 2, 0, 2});
                       }),
                       whole + " covers pixels [1,3) x [0,2) of a 4x3 frame"));
  // A state of 5 channels: the sixth, glint_resume.05, is named.
  Film film(4, 3, f.window);
  std::vector<std::string> five;
  for (int i = 0; i < 5; ++i) five.push_back("glint_resume.0" + std::to_string(i));
  film.addPlane(kResumeLayer, five, true);
  ExrMetadata m;
  writeFrameRecord(f.record, m);
  m.ints.emplace_back("glint:resume_finished_end", 4);
  m.ints.emplace_back("glint:resume_cut_end", 8);
  m.strings.emplace_back("glint:resume_checksum", "0000000000000000");
  const std::string shortState = tmp("shape-five.exr");
  writeExr(shortState, film, m);
  EXPECT_TRUE(contains(errorOf([&] { f.resume(shortState, f.settings); }),
                       shortState + " holds no resume state (glint_resume.05)"));
}

}  // namespace
}  // namespace glint
