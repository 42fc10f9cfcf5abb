// `glint` under an address-space limit (ulimit -v, as `prlimit --as` and batch systems set it):
// every run ends with an image (exit 0) or exit 1 and "out of memory" naming what was being
// read, never a signal, std::terminate or a hang (docs/hardening.md, "Memory").
#include <gtest/gtest.h>
#include <zlib.h>

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "test_util.h"

namespace glint {
namespace {

#define SKIP_UNDER_ASAN()                                                                      \
  if (test::kAddressSanitizer)                                                                 \
  GTEST_SKIP() << "AddressSanitizer's shadow memory needs terabytes of address space: no run " \
                  "fits an address-space limit"

struct Outcome {
  int status = -1;  // exit status; 128 + N for signal N (137: killed by the 60 s timeout)
  std::string output;
};

// `glint ARGS` with its address space limited to `limitMb` megabytes (ulimit -v's kilobytes).
Outcome underLimit(int limitMb, const std::string& args) {
  const std::string log = (test::tempDir() / "memory-limit.log").string();
  const std::string cmd = "bash -c 'ulimit -v " + std::to_string(limitMb * 1000) +
                          "; exec timeout -s KILL 60 " + std::string(GLINT_BINARY) + " " + args +
                          "' > " + log + " 2>&1";
  const int status = std::system(cmd.c_str());
  return {WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status), test::readFile(log)};
}

void appendChunk(std::string& png, const char* type, const std::string& data) {
  const auto be32 = [&](uint32_t v) {
    for (int s = 24; s >= 0; s -= 8) png += char((v >> s) & 0xff);
  };
  be32(uint32_t(data.size()));
  const std::string typed = std::string(type) + data;
  png += typed;
  be32(uint32_t(crc32(0, reinterpret_cast<const Bytef*>(typed.data()), uInt(typed.size()))));
}

// An 8-bit RGB PNG of side × side black pixels, in about a megabyte for 20000: one band of 100
// rows is deflated once (with a full flush, so that it refers to nothing before it) and
// repeated; no encoder has to compress the 1.2 GB.
std::string writeBlackPng(const std::string& name, int side) {
  const size_t rowBytes = 1 + 3 * size_t(side);  // the filter byte, then the pixels
  const int bandRows = 100;
  const std::vector<unsigned char> band(rowBytes * bandRows, 0);
  z_stream z{};
  EXPECT_EQ(deflateInit2(&z, 9, Z_DEFLATED, -15, 9, Z_DEFAULT_STRATEGY), Z_OK);
  std::string deflated(deflateBound(&z, uLong(band.size())) + 64, '\0');
  z.next_in = const_cast<Bytef*>(band.data());
  z.avail_in = uInt(band.size());
  z.next_out = reinterpret_cast<Bytef*>(deflated.data());
  z.avail_out = uInt(deflated.size());
  EXPECT_EQ(deflate(&z, Z_FULL_FLUSH), Z_OK);
  EXPECT_EQ(z.avail_in, 0u);
  deflated.resize(deflated.size() - z.avail_out);
  deflateEnd(&z);
  std::string idat = "\x78\x01";  // zlib header: deflate, 32 kB window
  for (int y = 0; y < side; y += bandRows) idat += deflated;
  idat += std::string("\x03\x00", 2);  // an empty final block
  // Adler-32 of zeros: s1 stays 1, s2 gains 1 per byte.
  const uint64_t bytes = uint64_t(rowBytes) * uint64_t(side);
  const uint32_t adler = uint32_t((bytes % 65521) << 16) | 1;
  for (int s = 24; s >= 0; s -= 8) idat += char((adler >> s) & 0xff);
  std::string ihdr;
  for (int k = 0; k < 2; ++k)
    for (int s = 24; s >= 0; s -= 8) ihdr += char((uint32_t(side) >> s) & 0xff);
  ihdr += std::string("\x08\x02\x00\x00\x00", 5);  // 8 bits, RGB, deflate, no filter, no interlace
  std::string png = "\x89PNG\r\n\x1a\n";
  appendChunk(png, "IHDR", ihdr);
  appendChunk(png, "IDAT", idat);
  appendChunk(png, "IEND", "");
  const std::string path = (test::tempDir() / name).string();
  std::ofstream(path, std::ios::binary) << png;
  return path;
}

std::string texturedScene(const std::string& name, const std::string& image) {
  return test::writeTemp(name, R"({"camera": {"eye": [0,0,4], "look_at": [0,0,0]},
    "materials": {"m": {"type": "phong", "kd": {"image": ")" +
                                   image + R"("}}},
    "lights": [{"type": "point", "position": [0,3,4], "intensity": [5,5,5]}],
    "objects": [{"type": "sphere", "center": [0,0,0], "radius": 1, "material": "m"}]})");
}

TEST(MemoryLimits, AHugeTextureIsRefusedFromItsHeaderBeforeAnyTexelIsRead) {
  SKIP_UNDER_ASAN();
  // 20000 x 20000 8-bit RGB in 1.2 MB: 1.2 GB of texels, 6.4 GB as a MIP pyramid of floats
  // (4/3 of them, 4 bytes a channel: io/texture_file.cpp). Under a 1.5 GB limit it cannot fit:
  // refused by its header with exit 1 naming it. OpenImageIO, left to try, failed to allocate it
  // and then decoded the whole file again for every tile, for hours.
  const std::string png = writeBlackPng("huge-black.png", 20000);
  const std::string scene = texturedScene("huge-texture.json", png);
  const Outcome o = underLimit(1500, "render " + scene + " -o " +
                                         (test::tempDir() / "huge-texture.exr").string() +
                                         " --width 8 --height 8 --spp 1 --quiet");
  EXPECT_EQ(o.status, 1) << o.output;
  EXPECT_NE(o.output.find("out of memory: texture " + png +
                          " (20000x20000, 3 channels of 1 byte, read into a MIP pyramid of floats) "
                          "needs 6.4 GB, more than the "),
            std::string::npos)
      << o.output;
  EXPECT_NE(o.output.find("address space that the limit (ulimit -v, RLIMIT_AS) leaves"),
            std::string::npos)
      << o.output;
}

// The peak resident memory of `glint ARGS` in kB, through Python's view of its children.
long peakKbOf(const std::string& args, std::string& output) {
  const std::string log = (test::tempDir() / "peak-rss.log").string();
  const std::string cmd =
      "python3 -c 'import resource, subprocess, sys; subprocess.run(sys.argv[1:]); "
      "print(\"peak\", resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss)' " +
      std::string(GLINT_BINARY) + " " + args + " > " + log + " 2>&1";
  EXPECT_EQ(std::system(cmd.c_str()), 0);
  output = test::readFile(log);
  const size_t at = output.rfind("peak ");
  return at == std::string::npos ? -1 : std::stol(output.substr(at + 5));
}

TEST(MemoryLimits, ATextureWhoseDataEndsEarlyFailsBeforeItsDeclaredSizeIsTouched) {
  SKIP_UNDER_ASAN();
  // 8000 x 8000 8-bit RGB declared over one deflated kilobyte of zeros: 768 MB of texels as
  // floats, which were zeroed whole before the first row failed. Grown a band at a time, the
  // run touches a band (a few MB) beside what an untextured render does: 200 MB bounds it with
  // room for either, and no run that zeroes the declared size fits.
  std::string ihdr;
  for (int k = 0; k < 2; ++k)
    for (int shift = 24; shift >= 0; shift -= 8) ihdr += char((8000u >> shift) & 0xff);
  ihdr += std::string("\x08\x02\x00\x00\x00", 5);  // 8 bits, RGB, no interlace
  const std::vector<unsigned char> zeros(1000, 0);
  std::string idat(compressBound(uLong(zeros.size())), '\0');
  uLongf idatSize = uLongf(idat.size());
  ASSERT_EQ(
      compress(reinterpret_cast<Bytef*>(idat.data()), &idatSize, zeros.data(), uLong(zeros.size())),
      Z_OK);
  idat.resize(idatSize);
  std::string png = "\x89PNG\r\n\x1a\n";
  appendChunk(png, "IHDR", ihdr);
  appendChunk(png, "IDAT", idat);
  appendChunk(png, "IEND", "");
  const std::string path = (test::tempDir() / "ends-early.png").string();
  std::ofstream(path, std::ios::binary) << png;
  const std::string scene = texturedScene("ends-early.json", path);
  std::string output;
  const long peak =
      peakKbOf("render " + scene + " -o " + (test::tempDir() / "ends-early.exr").string() +
                   " --width 8 --height 8 --spp 1 --quiet",
               output);
  EXPECT_NE(
      output.find("cannot read texture " + path + ": invalid PNG data: Not enough image data"),
      std::string::npos)
      << output;
  EXPECT_GT(peak, 0) << output;
  EXPECT_LT(peak, 200 * 1000) << output;
}

TEST(MemoryLimits, TheImageModuleIsNotLoadedWithoutTheAddressSpaceItNeeds) {
  SKIP_UNDER_ASAN();
  // Loading OpenImageIO's ~270 libraries under too small a limit aborted in log4cplus (a thread
  // that could not start), crashed in OpenImageIO, or failed with "Resource temporarily
  // unavailable". 300 MB leaves about 220 MB after Glint's own mappings: refused before dlopen,
  // with what it needs and what is left. A TIFF: PNG textures are read without the module.
  const std::string tiff = (test::tempDir() / "module-limit.tif").string();
  writeRgbImage(tiff, 2, 2, 8, std::vector<uint16_t>(12, 128));
  const std::string scene = texturedScene("module-limit.json", tiff);
  const Outcome o =
      underLimit(300, "render " + scene + " -o " + (test::tempDir() / "module-limit.exr").string() +
                          " --width 8 --height 8 --spp 1 --quiet");
  EXPECT_EQ(o.status, 1) << o.output;
  EXPECT_NE(
      o.output.find("out of memory: loading the image module (OpenImageIO) needs about 480 MB "
                    "of address space, the limit (ulimit -v) leaves "),
      std::string::npos)
      << o.output;
}

TEST(MemoryLimits, AJsonSceneIsCheckedAgainstTheLimitBeforeParsing) {
  SKIP_UNDER_ASAN();
  // A 10 MB inline mesh of 1.9 million JSON values is counted at about 210 MB to parse (its
  // tree, and 48 bytes a value beside it: core/json_memory.h); under a 150 MB limit about 75 MB
  // are left once Glint is loaded. nlohmann-json, failing there, threw from its destructor:
  // std::terminate and SIGABRT. Now it is exit 1 before parsing, naming the scene.
  std::string positions, indices;
  for (int i = 0; i < 240000; ++i) {
    positions += (i ? ",[" : "[") + std::to_string(i % 1000) + ".25," + std::to_string(i / 1000) +
                 ".5,0.125]";
    if (i + 2 < 240000)
      indices += (i ? ",[" : "[") + std::to_string(i) + "," + std::to_string(i + 1) + "," +
                 std::to_string(i + 2) + "]";
  }
  const std::string scene =
      test::writeTemp("big-inline.json",
                      R"({"camera": {"eye": [500,120,900], "look_at": [500,120,0]},
          "materials": {"m": {"type": "phong"}},
          "objects": [{"type": "mesh", "material": "m", "positions": [)" +
                          positions + "], \"indices\": [" + indices + "]}]}");
  const Outcome o =
      underLimit(150, "render " + scene + " -o " + (test::tempDir() / "big-inline.exr").string() +
                          " --width 8 --height 8 --spp 1 --quiet");
  EXPECT_EQ(o.status, 1) << o.output;
  EXPECT_NE(o.output.find("out of memory: parsing scene " + scene), std::string::npos) << o.output;
}

TEST(MemoryLimits, JsonIsCheckedByItsValuesNotItsBytes) {
  SKIP_UNDER_ASAN();
  // Two million empty objects: 6 MB of text whose tree takes about 166 MB in nlohmann-json (83
  // bytes each), where 11 bytes per byte of text counted 66 MB. Under a 150 MB limit (about 75
  // MB left once Glint is loaded) such a scene passed that check and parsing failed inside
  // nlohmann-json (std::terminate, SIGABRT); in a glTF it was not checked at all. Counted by
  // their values, both are exit 1 before parsing, naming the file.
  std::string objects = "[{}";
  for (int i = 1; i < 2'000'000; ++i) objects += ",{}";
  objects += "]";
  const std::string scene = test::writeTemp(
      "many-objects.json",
      R"({"camera": {"eye": [0,0,4], "look_at": [0,0,0]}, "comment": )" + objects + "}");
  const std::string gltf = test::writeTemp(
      "many-objects.gltf", R"({"asset": {"version": "2.0"}, "extras": )" + objects + "}");
  for (const auto& [file, what] : {std::pair{scene, "scene"}, std::pair{gltf, "glTF"}}) {
    const Outcome o = underLimit(150, "render " + file + " -o " +
                                          (test::tempDir() / "many-objects.exr").string() +
                                          " --width 8 --height 8 --spp 1 --quiet");
    EXPECT_EQ(o.status, 1) << o.output;
    EXPECT_NE(o.output.find("out of memory: parsing " + std::string(what) + " " + file + " (" +
                            std::to_string(std::filesystem::file_size(file)) + " bytes) needs "),
              std::string::npos)
        << o.output;
  }
}

TEST(MemoryLimits, AMeshThatOutgrowsTheLimitInAssimpsProcessingIsOutOfMemory) {
  SKIP_UNDER_ASAN();
  // 19 glTF nodes, each listing the next twice: 2^19 copies of 31 triangles, 16.25 M, within
  // the triangle budget (io/expansion_limits.h), which Assimp's pre-transformation fails to
  // allocate under 1.5 GB. Assimp keeps only the text of what it catches: once "cannot process
  // mesh ...: std::bad_alloc", exit 2, as if the file were at fault.
  std::string nodes;
  for (int i = 0; i < 19; ++i)
    nodes += "{\"children\": [" + std::to_string(i + 1) + ", " + std::to_string(i + 1) + "]}, ";
  std::string positions;  // 31 triangles side by side, each (k, 0, 0) (k + 1, 0, 0) (k, 1, 0)
  for (int k = 0; k < 31; ++k)
    for (const float v : {float(k), 0.0f, 0.0f, float(k + 1), 0.0f, 0.0f, float(k), 1.0f, 0.0f})
      positions.append(reinterpret_cast<const char*>(&v), sizeof v);
  const std::string gltf = test::writeTemp(
      "doubling-nodes.gltf",
      R"({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [)" +
          nodes + R"({"mesh": 0}], "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
      "accessors": [{"bufferView": 0, "componentType": 5126, "count": 93, "type": "VEC3",
                     "min": [0, 0, 0], "max": [31, 1, 0]}],
      "bufferViews": [{"buffer": 0, "byteLength": 1116}],
      "buffers": [{"byteLength": 1116, "uri": "data:application/octet-stream;base64,)" +
          test::base64(positions) + R"("}]})");
  const Outcome o = underLimit(1500, "validate " + gltf);
  EXPECT_EQ(o.status, 1) << o.output;
  EXPECT_NE(o.output.find("out of memory while reading mesh " + gltf), std::string::npos)
      << o.output;
}

TEST(MemoryLimits, AFrameIsCheckedWithTheCopiesWrittenWithItsStateAndPreviews) {
  SKIP_UNDER_ASAN();
  // A 2000² frame holds 137 bytes a pixel (0.55 GB) and renders under 1.5 GB on 2 threads
  // (each thread's stack counts against the limit). Written with its state (--resumable) it
  // needs 292 more (the state's 23 channels in the film and packed, a copy of the film: 1.7 GB
  // in all), and with previews 404 more (a copy of the states and the film, written with their
  // state: 2.2 GB): both are refused before any work, naming the part, where they used to
  // render and then fail to write the frame, out of memory.
  const std::string scene = test::writeTemp("big-frame.json", R"({
    "render": {"width": 2000, "height": 2000, "spp": 1},
    "camera": {"eye": [0,0,4], "look_at": [0,0,0]},
    "materials": {"m": {"type": "phong", "kd": [0.5,0.5,0.5]}},
    "lights": [{"type": "point", "position": [0,3,4], "intensity": [5,5,5]}],
    "objects": [{"type": "sphere", "center": [0,0,0], "radius": 1, "material": "m"}]})");
  const std::string render =
      "render " + scene + " --threads 2 --quiet -o " + (test::tempDir() / "big-frame.exr").string();
  const Outcome plain = underLimit(1500, render);
  EXPECT_EQ(plain.status, 0) << plain.output;
  const std::pair<std::string, std::string> copies[] = {
      {" --resumable", "the state kept for --resumable 292"},
      {" --spp 2 --min-spp 1 --preview-every 0.001", "previews 404"}};
  for (const auto& [extra, part] : copies) {
    const Outcome o = underLimit(1500, render + extra);
    EXPECT_EQ(o.status, 2) << extra << "\n" << o.output;
    EXPECT_NE(o.output.find("a frame of 4000000 pixels needs about"), std::string::npos)
        << extra << "\n"
        << o.output;
    EXPECT_NE(o.output.find("colour and sampling state 137 and " + part), std::string::npos)
        << extra << "\n"
        << o.output;
  }
}

TEST(MemoryLimits, EveryLimitGivesAnImageOrOutOfMemory) {
  SKIP_UNDER_ASAN();
  // A textured scene from a limit Glint just starts under (below about 80 MB the dynamic loader
  // cannot map its libraries: exit 127 before main) to one that renders it, through the image
  // module's range (once SIGABRT, SIGSEGV or EAGAIN at 460-500 MB).
  const std::string scene = texturedScene("limits.json", test::writeHalfMatte());
  for (int mb : {100, 120, 200, 300, 460, 480, 500, 540, 600, 800}) {
    const Outcome o =
        underLimit(mb, "render " + scene + " -o " + (test::tempDir() / "limits.exr").string() +
                           " --width 8 --height 8 --spp 1 --quiet");
    EXPECT_TRUE(o.status == 0 || o.status == 1) << mb << " MB: exit " << o.status << "\n"
                                                << o.output;
    if (o.status == 1) {
      EXPECT_NE(o.output.find("out of memory"), std::string::npos) << mb << " MB: " << o.output;
    }
    EXPECT_EQ(o.output.find("terminate"), std::string::npos) << mb << " MB: " << o.output;
  }
}

}  // namespace
}  // namespace glint
