// The command line of passes: the estimate in --stats-json and the EXR, --resume (and what it
// refuses), --preview-every, and `glint converge --from-render`.
#include <gtest/gtest.h>

#include <OpenImageIO/imageio.h>

#include <nlohmann/json.hpp>
#include <utility>
#include <vector>

#include "film/exr_output.h"
#include "test_util.h"

namespace glint {
namespace {

std::string tmp(const std::string& name) { return (test::tempDir() / name).string(); }

std::string soft(const std::string& more) {
  return std::string(GLINT_SCENES_DIR) + "/soft_shadows.json --quiet --width 48 --height 32 " +
         more;
}

TEST(PassesCli, StatsAndMetadataCarryTheEstimateAndThePasses) {
  const std::string out = tmp("est.exr"), stats = tmp("est.json");
  ASSERT_EQ(
      test::runGlint("render " + soft("--spp 32 -o " + out + " --stats-json " + stats)).exitCode,
      0);
  const nlohmann::json j = nlohmann::json::parse(test::readFile(stats));
  ASSERT_TRUE(j["estimated_rmse"].is_number());
  ASSERT_EQ(j["passes"].size(), 3u);  // to 8, 16, 32 spp
  EXPECT_EQ(j["passes"][2]["spp"], 32);
  // The last pass's estimate is the frame's.
  EXPECT_EQ(j["passes"][2]["estimated_rmse"], j["estimated_rmse"]);
  auto in = OIIO::ImageInput::open(out);
  ASSERT_TRUE(in);
  EXPECT_FLOAT_EQ(in->spec().get_float_attribute("glint:estimated_rmse"),
                  j["estimated_rmse"].get<float>());
  EXPECT_EQ(nlohmann::json::parse(in->spec().get_string_attribute("glint:passes")), j["passes"]);
  // A plain frame carries no resume state (it would triple the file for nothing).
  EXPECT_EQ(in->spec().channelindex("glint_resume.00"), -1);
  // One sample: no estimate, null rather than a made-up number.
  ASSERT_EQ(
      test::runGlint("render " + soft("--spp 1 -o " + out + " --stats-json " + stats)).exitCode, 0);
  EXPECT_TRUE(nlohmann::json::parse(test::readFile(stats))["estimated_rmse"].is_null());
}

TEST(PassesCli, AnAdaptiveOrTimeLimitedFrameRecordsWhereItsPixelsMayStop) {
  // glint:spp is the scene's 16; an adaptive frame's pixels go past it, to --max-spp, and its
  // record said neither where they may stop nor what it aimed at.
  const std::string out = tmp("bounds.exr");
  ASSERT_EQ(test::runGlint("render " + soft("--target-rmse 0.001 --max-spp 64 -o " + out)).exitCode,
            0);
  {
    auto in = OIIO::ImageInput::open(out);
    ASSERT_TRUE(in);
    EXPECT_EQ(in->spec().get_int_attribute("glint:spp"), 16);
    EXPECT_EQ(in->spec().get_int_attribute("glint:max_spp"), 64);
    EXPECT_EQ(in->spec().get_string_attribute("glint:resume_sampling"), "target-rmse 0.001");
    EXPECT_EQ(in->spec().find_attribute("glint:time_limit_seconds"), nullptr);
  }
  ASSERT_EQ(test::runGlint("render " + soft("--time-limit 60 --max-spp 32 -o " + out)).exitCode, 0);
  {
    auto in = OIIO::ImageInput::open(out);
    ASSERT_TRUE(in);
    EXPECT_EQ(in->spec().get_int_attribute("glint:max_spp"), 32);
    EXPECT_EQ(in->spec().get_float_attribute("glint:time_limit_seconds"), 60.0f);
  }
  // A plain frame's pixels all take glint:spp: nothing more to say.
  ASSERT_EQ(test::runGlint("render " + soft("--spp 8 -o " + out)).exitCode, 0);
  auto in = OIIO::ImageInput::open(out);
  ASSERT_TRUE(in);
  EXPECT_EQ(in->spec().find_attribute("glint:max_spp"), nullptr);
}

TEST(PassesCli, ResumeGivesTheStraightRendersPixelsAndRefusesAnotherFrame) {
  const std::string part = tmp("resume-part.exr"), straight = tmp("resume-straight.exr");
  ASSERT_EQ(test::runGlint("render " + soft("--resumable --spp 8 -o " + part)).exitCode, 0);
  ASSERT_EQ(test::runGlint("render " + soft("--resumable --spp 32 -o " + straight)).exitCode, 0);
  // -o names the partial itself: it is replaced by the continued frame.
  const std::string stats = tmp("resume.json");
  const auto run = test::runGlint(
      "render " + soft("--spp 32 --resume " + part + " -o " + part + " --stats-json " + stats));
  ASSERT_EQ(run.exitCode, 0) << run.output;
  EXPECT_EQ(readImage(part).pixels, readImage(straight).pixels);
  // The passes of both renders, 8 (the first's) then 16 and 32, on one time axis: the continued
  // render's start where the first's ended, so its last pass ends later than its own render time.
  const nlohmann::json j = nlohmann::json::parse(test::readFile(stats));
  ASSERT_EQ(j["passes"].size(), 3u);
  for (size_t i = 1; i < 3; ++i)
    EXPECT_GE(j["passes"][i]["seconds"].get<double>(), j["passes"][i - 1]["seconds"].get<double>());
  EXPECT_GT(j["passes"][2]["seconds"].get<double>(), j["seconds"].get<double>());
  // Another seed, another setting, a frame without state: exit 2, the frame and what differs
  // named.
  for (const auto& [other, named] : std::vector<std::pair<std::string, std::string>>{
           {"--seed 9", "seed: the frame's "}, {"--max-depth 2", "max depth: the frame's "}}) {
    const auto r = test::runGlint("render " + soft("--spp 32 " + other + " --resume " + straight +
                                                   " -o " + tmp("resume-x.exr")));
    EXPECT_EQ(r.exitCode, 2) << other << r.output;
    EXPECT_NE(r.output.find(straight), std::string::npos) << r.output;
    EXPECT_NE(r.output.find(named), std::string::npos) << r.output;
  }
  // Targets apart by less than 1e-6 are other targets: they read alike (six decimals) and a
  // frame rendered to one was continued to the other.
  const std::string fine = tmp("resume-fine-target.exr");
  ASSERT_EQ(test::runGlint("render " + soft("--target-relmse 0.0000002 --max-spp 16 --resumable "
                                            "-o " +
                                            fine))
                .exitCode,
            0);
  const auto target = test::runGlint("render " + soft("--target-relmse 0.0000004 --max-spp 32 "
                                                      "--resume " +
                                                      fine + " -o " + tmp("resume-y.exr")));
  EXPECT_EQ(target.exitCode, 2) << target.output;
  EXPECT_NE(target.output.find("targets and first pass: the frame's target-relmse 2e-07, this "
                               "render's target-relmse 4e-07"),
            std::string::npos)
      << target.output;
  // The variance AOV and half floats change what is written, not the samples: a frame continues
  // with them (from 8 spp: `part` is the continued frame now, `straight` at 32 is continued).
  const std::string withVariance = tmp("resume-variance.exr");
  const auto v = test::runGlint(
      "render " + soft("--spp 32 --aov variance --resume " + straight + " -o " + withVariance));
  ASSERT_EQ(v.exitCode, 0) << v.output;
  const auto rgbaOf = [](const Image& image) {
    std::vector<float> rgba;
    for (size_t p = 0; p < image.pixels.size(); p += size_t(image.channels))
      rgba.insert(rgba.end(), image.pixels.begin() + long(p), image.pixels.begin() + long(p) + 4);
    return rgba;
  };
  EXPECT_EQ(rgbaOf(readImage(withVariance)), rgbaOf(readImage(straight)));
  const auto h = test::runGlint(
      "render " + soft("--spp 32 --half --resume " + straight + " -o " + tmp("resume-half.exr")));
  EXPECT_EQ(h.exitCode, 0) << h.output;
  const std::string plain = tmp("resume-plain.exr");
  ASSERT_EQ(test::runGlint("render " + soft("--spp 8 -o " + plain)).exitCode, 0);
  // A frame without state, whatever its settings (here another spp, which a stratified frame's
  // hash also tells): it holds nothing to continue, and is told so.
  for (const char* spp : {"8", "16"}) {
    const auto r = test::runGlint("render " + soft(std::string("--spp ") + spp + " --resume " +
                                                   plain + " -o " + tmp("y.exr")));
    EXPECT_EQ(r.exitCode, 2) << r.output;
    EXPECT_NE(r.output.find("holds no resume state"), std::string::npos) << r.output;
  }
}

TEST(PassesCli, OnlyTheFrameIsWrittenOverTheFrameItContinues) {
  // --stats-json naming the --resume frame replaced it with JSON, exit 0; --frames with --resume
  // rendered the first frame, then failed on the second.
  const std::string part = tmp("resume-kept.exr");
  ASSERT_EQ(test::runGlint("render " + soft("--resumable --spp 4 -o " + part)).exitCode, 0);
  const std::string before = test::readFile(part);
  const auto stats =
      test::runGlint("render " + soft("--spp 8 --resume " + part + " -o " + tmp("resume-next.exr") +
                                      " --stats-json " + part));
  EXPECT_EQ(stats.exitCode, 2) << stats.output;
  EXPECT_NE(stats.output.find("--stats-json " + part + " names the frame --resume continues"),
            std::string::npos)
      << stats.output;
  EXPECT_EQ(test::readFile(part), before);
  const auto frames = test::runGlint(
      "render " + soft("--spp 8 --resume " + part + " --frames 3-5 -o " + tmp("f.####.exr")));
  EXPECT_EQ(frames.exitCode, 2) << frames.output;
  EXPECT_NE(frames.output.find("--resume continues one frame; --frames 3-5 names several"),
            std::string::npos)
      << frames.output;
  EXPECT_FALSE(std::filesystem::exists(tmp("f.0003.exr")));
}

TEST(PassesCli, AResumeStateConvertedToFloatIsNamedAsAltered) {
  // A frame another tool rewrote (oiiotool writes its UINT words as float) was said to hold no
  // resume state, though its channels are there.
  const std::string frame = tmp("resume-to-float.exr"), converted = tmp("resume-float.exr");
  ASSERT_EQ(test::runGlint("render " + soft("--resumable --spp 4 -o " + frame)).exitCode, 0);
  {
    auto in = OIIO::ImageInput::open(frame);
    ASSERT_TRUE(in);
    OIIO::ImageSpec spec = in->spec();
    std::vector<float> pixels(spec.image_pixels() * size_t(spec.nchannels));
    ASSERT_TRUE(in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, pixels.data()));
    spec.set_format(OIIO::TypeDesc::FLOAT);
    spec.channelformats.clear();
    auto out = OIIO::ImageOutput::create(converted);
    ASSERT_TRUE(out && out->open(converted, spec));
    ASSERT_TRUE(out->write_image(OIIO::TypeDesc::FLOAT, pixels.data()));
    ASSERT_TRUE(out->close());
  }
  const auto r =
      test::runGlint("render " + soft("--spp 8 --resume " + converted + " -o " + tmp("rf.exr")));
  EXPECT_EQ(r.exitCode, 2) << r.output;
  EXPECT_NE(r.output.find(converted + "'s resume state is altered: its channel glint_resume.00 "
                                      "is float, not UINT"),
            std::string::npos)
      << r.output;
}

TEST(PassesCli, AMultipartFrameKeepsItsResumeStateWithTheBeautyAndResumes) {
  // The resume state stays in part 0 with the beauty: as a part of its own, --resume (which
  // reads part 0) found none, and Blender, which cannot name its channels, failed that part.
  const std::string part = tmp("resume-mp-part.exr"), straight = tmp("resume-mp-straight.exr"),
                    continued = tmp("resume-mp-continued.exr");
  const std::string flags = "--resumable --multipart --aov variance ";
  ASSERT_EQ(test::runGlint("render " + soft(flags + "--spp 8 -o " + part)).exitCode, 0);
  ASSERT_EQ(test::runGlint("render " + soft(flags + "--spp 32 -o " + straight)).exitCode, 0);
  const auto run =
      test::runGlint("render " + soft(flags + "--spp 32 --resume " + part + " -o " + continued));
  ASSERT_EQ(run.exitCode, 0) << run.output;
  // Part 0 (R, G, B, A and the state) is the straight render's, and so is the variance part.
  EXPECT_EQ(readImage(continued).pixels, readImage(straight).pixels);
  auto a = OIIO::ImageInput::open(continued), b = OIIO::ImageInput::open(straight);
  ASSERT_TRUE(a && b);
  std::vector<std::string> parts;
  for (int sub = 0; a->seek_subimage(sub, 0); ++sub) {
    parts.push_back(a->spec().get_string_attribute("name"));
    ASSERT_TRUE(b->seek_subimage(sub, 0));
    std::vector<float> pa(size_t(a->spec().image_pixels()) * size_t(a->spec().nchannels)),
        pb(pa.size());
    ASSERT_TRUE(a->read_image(sub, 0, 0, a->spec().nchannels, OIIO::TypeDesc::FLOAT, pa.data()));
    ASSERT_TRUE(b->read_image(sub, 0, 0, b->spec().nchannels, OIIO::TypeDesc::FLOAT, pb.data()));
    EXPECT_EQ(pa, pb) << "part " << sub;
  }
  EXPECT_EQ(parts, (std::vector<std::string>{"rgba", "variance"}));
  ASSERT_TRUE(a->seek_subimage(0, 0));
  EXPECT_NE(a->spec().channelindex("glint_resume.00"), -1);
}

TEST(PassesCli, ATexturedFrameResumesToTheStraightRendersPixels) {
  // Image textures filter over each sample's footprint, a share of its pixel that narrows with
  // the samples (integrator/footprint.h). A frame that may be continued filters every sample as
  // for the most samples, or its first 8 would be filtered for 8 and the continued frame would
  // not be the straight one (it differed by up to 0.012 on this scene).
  const std::string assets =
      std::string(GLINT_SCENES_DIR) + "/real_assets.json --quiet --width 48 --height 32 ";
  const std::string part = tmp("textured-part.exr"), straight = tmp("textured-straight.exr");
  ASSERT_EQ(test::runGlint("render " + assets + "--resumable --spp 8 -o " + part).exitCode, 0);
  ASSERT_EQ(test::runGlint("render " + assets + "--resumable --spp 32 -o " + straight).exitCode, 0);
  const auto run = test::runGlint("render " + assets + "--spp 32 --resume " + part + " -o " + part);
  ASSERT_EQ(run.exitCode, 0) << run.output;
  EXPECT_EQ(readImage(part).pixels, readImage(straight).pixels);
}

// Writes `bad`: the frame `good` with the words of pixel 0's resume channels named in `words`
// replaced and the resume channels from glint_resume.`dropFrom` on left out, all else (the resume
// hash included) kept.
void rewriteResumeWords(const std::string& good, const std::string& bad,
                        const std::vector<std::pair<std::string, uint32_t>>& words,
                        int dropFrom = 100) {
  auto in = OIIO::ImageInput::open(good);
  ASSERT_TRUE(in);
  OIIO::ImageSpec spec = in->spec();
  std::vector<float> pixels(size_t(spec.image_pixels()) * size_t(spec.nchannels));
  ASSERT_TRUE(in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, pixels.data()));
  in->close();
  // Every channel as float keeps the beauty; the UINT state channels are rewritten as UINT.
  std::vector<OIIO::TypeDesc> formats(size_t(spec.nchannels), OIIO::TypeDesc::FLOAT);
  auto raw = OIIO::ImageInput::open(good);
  std::vector<uint32_t> state(pixels.size());
  ASSERT_TRUE(raw->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::UINT, state.data()));
  for (int c = 0; c < spec.nchannels; ++c)
    if (spec.channelformat(c) == OIIO::TypeDesc::UINT) formats[size_t(c)] = OIIO::TypeDesc::UINT;
  spec.channelformats = formats;
  for (const auto& [name, word] : words) {
    const int c = spec.channelindex(name);
    ASSERT_GE(c, 0) << name;
    state[size_t(c)] = word;
  }
  std::vector<int> kept;
  OIIO::ImageSpec written = spec;
  written.channelnames.clear();
  written.channelformats.clear();
  for (int c = 0; c < spec.nchannels; ++c) {
    const std::string& name = spec.channelnames[size_t(c)];
    if (name.rfind("glint_resume.", 0) == 0 && std::stoi(name.substr(13)) >= dropFrom) continue;
    kept.push_back(c);
    written.channelnames.push_back(name);
    written.channelformats.push_back(formats[size_t(c)]);
  }
  written.nchannels = int(kept.size());
  written.alpha_channel = written.channelindex("A");
  auto outFile = OIIO::ImageOutput::create(bad);
  ASSERT_TRUE(outFile && outFile->open(bad, written));
  // Per channel, from the buffer its type was read into.
  std::vector<unsigned char> mixed;
  for (size_t p = 0; p < size_t(spec.image_pixels()); ++p)
    for (const int c : kept) {
      const size_t i = p * size_t(spec.nchannels) + size_t(c);
      const auto* bytes = formats[size_t(c)] == OIIO::TypeDesc::UINT
                              ? reinterpret_cast<const unsigned char*>(&state[i])
                              : reinterpret_cast<const unsigned char*>(&pixels[i]);
      mixed.insert(mixed.end(), bytes, bytes + 4);
    }
  ASSERT_TRUE(outFile->write_image(OIIO::TypeDesc::UNKNOWN, mixed.data()));
  outFile->close();
}

TEST(PassesCli, AResumeStateThatNoRenderLeavesIsRefused) {
  // A resumable frame whose first pixel's state is rewritten to what no render leaves: the
  // state is refused, naming the file and the pixel.
  const std::string good = tmp("state-good.exr");
  ASSERT_EQ(test::runGlint("render " + soft("--resumable --spp 4 -o " + good)).exitCode, 0);
  // Half 0's mean R as NaN's bits (channels 00, 01: its high and low words); half 0's rays as
  // none (channels 09, 10), though its 2 samples traced at least their camera rays; and as
  // 2^62 + 1, more than the two halves' sum may hold.
  const std::vector<std::vector<std::pair<std::string, uint32_t>>> lies = {
      {{"glint_resume.00", 0x7ff80000u}, {"glint_resume.01", 0}},
      {{"glint_resume.09", 0}, {"glint_resume.10", 0}},
      {{"glint_resume.09", 0x40000000u}, {"glint_resume.10", 1}}};
  for (size_t i = 0; i < lies.size(); ++i) {
    const std::string bad = tmp("state-bad-" + std::to_string(i) + ".exr");
    rewriteResumeWords(good, bad, lies[i]);
    const auto r =
        test::runGlint("render " + soft("--spp 8 --resume " + bad + " -o " + tmp("z.exr")));
    EXPECT_EQ(r.exitCode, 2) << r.output;
    EXPECT_NE(r.output.find("pixel (0, 0)"), std::string::npos) << r.output;
  }
  // Exactly 2^62 rays in a half is the most a state may hold (both halves' sum, 2^63, fits in
  // 64 bits): it passes the checks of the values, and is refused only as a state its render did
  // not write (glint:resume_checksum), as is any edit that leaves the values plausible: a word
  // of a mean (a tool that read the channels as float and wrote them back changed every one).
  const std::vector<std::vector<std::pair<std::string, uint32_t>>> plausible = {
      {{"glint_resume.09", 0x40000000u}, {"glint_resume.10", 0}}, {{"glint_resume.01", 12345u}}};
  for (const auto& words : plausible) {
    const std::string edited = tmp("state-edited.exr");
    rewriteResumeWords(good, edited, words);
    const auto r =
        test::runGlint("render " + soft("--spp 8 --resume " + edited + " -o " + tmp("z.exr")));
    EXPECT_EQ(r.exitCode, 2) << r.output;
    EXPECT_NE(r.output.find("resume state is not the one its render wrote"), std::string::npos)
        << r.output;
  }
}

TEST(PassesCli, AResumeStateWithoutTheRaysChannelsNamesTheGlintThatWroteIt) {
  // An older Glint wrote glint_resume.00 to .17, without the rays traced: the refusal says so.
  // A state that lacks an earlier channel is no such file, and is not said to be.
  const std::string good = tmp("state-whole.exr");
  ASSERT_EQ(test::runGlint("render " + soft("--resumable --spp 4 -o " + good)).exitCode, 0);
  for (const int dropFrom : {18, 5}) {
    const std::string bad = tmp("state-from-" + std::to_string(dropFrom) + ".exr");
    rewriteResumeWords(good, bad, {}, dropFrom);
    const auto r =
        test::runGlint("render " + soft("--spp 8 --resume " + bad + " -o " + tmp("w.exr")));
    EXPECT_EQ(r.exitCode, 2) << r.output;
    const std::string missing = dropFrom == 18 ? "glint_resume.18" : "glint_resume.05";
    EXPECT_NE(r.output.find("holds no resume state (" + missing + ")"), std::string::npos)
        << r.output;
    EXPECT_EQ(r.output.find("before the rays channels") != std::string::npos, dropFrom == 18)
        << r.output;
  }
}

TEST(PassesCli, SettingsThatCannotMeanWhatTheySayAreRefusedAndSaidWhy) {
  struct Case {
    std::string args, says;
  };
  const std::vector<Case> cases = {
      // Without a target or a time limit every pixel takes the spp: --max-spp rendered 8 where
      // the frame's glint:spp said 16.
      {"--spp 16 --max-spp 8", "give --spp 8 instead"},
      // A state that --resume would refuse to continue (the AOVs' sums are not kept).
      {"--resumable --aov depth", "drop --resumable, or those AOVs"},
      // Read as "not in range 0 to 1.8e308" (0 reads as in range) and "abc" as out of range.
      {"--target-rmse 0", "must be a finite number above 0, got 0"},
      {"--time-limit abc", "must be a number, got abc"},
      {"--preview-every 0.5s", "must be a number, got 0.5s"}};
  for (const Case& c : cases) {
    const auto r = test::runGlint("render " + soft(c.args + " -o " + tmp("never.exr")));
    EXPECT_EQ(r.exitCode, 2) << c.args << "\n" << r.output;
    EXPECT_NE(r.output.find(c.says), std::string::npos) << c.args << "\n" << r.output;
  }
}

TEST(PassesCli, PreviewsAreWrittenAndTheFinalFrameIsComplete) {
  const std::string out = tmp("preview.exr");
  const auto r = test::runGlint("render " + std::string(GLINT_SCENES_DIR) +
                                "/soft_shadows.json --width 48 --height 32 --spp 32 "
                                "--preview-every 0.000001 -o " +
                                out);
  ASSERT_EQ(r.exitCode, 0) << r.output;
  // Passes end at 8, 16 and 32: a preview after each but the last.
  for (const char* spp : {"at 8 spp", "at 16 spp"})
    EXPECT_NE(r.output.find(std::string("preview: ") + out + " " + spp), std::string::npos)
        << r.output;
  auto in = OIIO::ImageInput::open(out);
  ASSERT_TRUE(in);
  EXPECT_EQ(in->spec().get_int_attribute("glint:partial", -1), 0);
  EXPECT_EQ(in->spec().get_int_attribute("glint:min_pixel_spp", -1), 32);
}

TEST(PassesCli, ConvergeFromRenderReadsThePassesOfAFrame) {
  const std::string out = tmp("from-render.exr"), json = tmp("from-render.json");
  ASSERT_EQ(test::runGlint("render " + soft("--spp 64 -o " + out)).exitCode, 0);
  const auto r = test::runGlint("converge --from-render " + out + " --json " + json);
  ASSERT_EQ(r.exitCode, 0) << r.output;
  const nlohmann::json j = nlohmann::json::parse(test::readFile(json));
  const nlohmann::json& points = j["series"][0]["points"];
  ASSERT_EQ(points.size(), 4u);  // the passes to 8, 16, 32, 64
  EXPECT_EQ(points[3]["spp"], 64);
  // The estimated error falls from pass to pass (each halves the variance or better).
  for (size_t i = 1; i < points.size(); ++i)
    EXPECT_LT(points[i]["rmse"].get<double>(), points[i - 1]["rmse"].get<double>());
  // A file without passes: exit 2, named.
  const std::string png = test::writeTemp("not-a-render.exr", "not an EXR at all");
  const auto bad = test::runGlint("converge --from-render " + png);
  EXPECT_EQ(bad.exitCode, 2) << bad.output;
  // A record no render can have left (edited, or damaged): refused, naming the pass and value.
  const std::string edited = test::writeTemp(
      "edited-passes.json",
      R"({"passes": [{"spp": -2, "seconds": 0.1, "estimated_rmse": 0.1, "estimated_relmse": 0.1}]})");
  const auto lying = test::runGlint("converge --from-render " + edited);
  EXPECT_EQ(lying.exitCode, 2) << lying.output;
  EXPECT_NE(lying.output.find("passes[0].spp is -2"), std::string::npos) << lying.output;
}

}  // namespace
}  // namespace glint
