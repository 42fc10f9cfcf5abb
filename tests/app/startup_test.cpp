// What a run loads (issue 22): the shared libraries the dynamic loader maps, read from its own
// list (LD_DEBUG=files), not from timings. OpenImageIO and its ~260 dependencies are loaded only
// by the runs that need it, through libglint_oiio.so (film/oiio_module.h).
#include <gtest/gtest.h>

#include <OpenImageIO/imageio.h>

#include "test_util.h"

namespace glint {
namespace {

using test::runGlint;

std::string tmp(const std::string& name) { return (test::tempDir() / name).string(); }

const char* kSphere = R"({
  "render": {"width": 16, "height": 16, "spp": 1},
  "camera": {"eye": [0,0,4], "look_at": [0,0,0], "vfov": 40},
  "materials": {"m": {"type": "phong", "kd": [0.8,0.2,0.2]}},
  "lights": [{"type": "point", "position": [2,3,4], "intensity": [1,1,1]}],
  "objects": [{"type": "sphere", "center": [0,0,0], "radius": 1, "material": "m"}]})";

// The run's output with the dynamic loader's list of the files it opened (`file=NAME [0];`
// lines: one for each shared library mapped, at start-up or by dlopen).
test::RunResult loaderList(const std::string& args) { return runGlint(args, "LD_DEBUG=files"); }

bool loaded(const test::RunResult& r, const std::string& library) {
  return r.output.find("file=" + library) != std::string::npos;
}

TEST(Startup, VersionHelpAndAnExrRenderLoadNoOpenImageIO) {
  const std::string scene = test::writeTemp("startup-sphere.json", kSphere);
  for (const std::string& args : {std::string("--version"), std::string("--help"),
                                  "render " + scene + " --quiet -o " + tmp("startup.exr"),
                                  "render " + scene + " --quiet -o " + tmp("startup2.exr") +
                                      " --display " + tmp("startup.png")}) {
    const test::RunResult r = loaderList(args);
    EXPECT_EQ(r.exitCode, 0) << args;
    // The list is live: the C library is in every process's list.
    EXPECT_TRUE(loaded(r, "libc.so")) << args << "\n" << r.output.substr(0, 2000);
    EXPECT_FALSE(loaded(r, "libOpenImageIO")) << args;
    EXPECT_FALSE(loaded(r, "libglint_oiio")) << args;
  }
}

TEST(Startup, JpegPngAndHdrTexturesLoadNoOpenImageIO) {
  // real_assets.json: the spider's JPEG maps (OBJ and MTL), the glTF box's PNG; sky.json: a
  // Radiance HDR environment. Their corners only.
  for (const char* scene : {"real_assets", "sky"}) {
    const std::string args = "render " + std::string(GLINT_SOURCE_DIR) + "/scenes/" + scene +
                             ".json --quiet --crop 0 8 0 8 -o " + tmp("textures.exr");
    const test::RunResult r = loaderList(args);
    ASSERT_EQ(r.exitCode, 0) << scene << "\n" << r.output.substr(0, 2000);
    EXPECT_TRUE(loaded(r, "libc.so")) << scene;  // the list is live
    EXPECT_FALSE(loaded(r, "libOpenImageIO")) << scene;
    EXPECT_FALSE(loaded(r, "libglint_oiio")) << scene;
  }
}

TEST(Startup, ATiffDisplayImageLoadsOpenImageIOThroughItsModule) {
  const std::string scene = test::writeTemp("startup-tiff.json", kSphere);
  const test::RunResult r = loaderList("render " + scene + " --quiet -o " + tmp("tiff.exr") +
                                       " --display " + tmp("tiff.tif"));
  ASSERT_EQ(r.exitCode, 0) << r.output.substr(0, 2000);
  EXPECT_TRUE(loaded(r, "libOpenImageIO")) << r.output.substr(0, 2000);
  EXPECT_NE(r.output.find("libglint_oiio.so"), std::string::npos);
  // A real 16-bit TIFF of the frame's size.
  auto in = OIIO::ImageInput::open(tmp("tiff.tif"));
  ASSERT_TRUE(in);
  EXPECT_EQ(in->format_name(), std::string("tiff"));
  EXPECT_EQ(in->spec().width, 16);
  EXPECT_EQ(in->spec().format, OIIO::TypeDesc::UINT16);
}

}  // namespace
}  // namespace glint
