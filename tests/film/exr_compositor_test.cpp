// A frame with every AOV, single-part and multipart, read whole the way compositors read it:
// OpenEXR's multipart reader with a frame buffer for every part (what Blender 3.4 does: a part
// whose channels it cannot name gets an empty frame buffer, its read throws "No frame buffer
// specified", and the parts after it load black), and Blender itself, through its EXR reader and
// compositor, when it is installed (tests/film/blender_read_exr.py).
#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfInputPart.h>
#include <OpenEXR/ImfMultiPartInputFile.h>
#include <OpenEXR/ImfStringAttribute.h>
#include <gtest/gtest.h>

#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "film/cryptomatte.h"
#include "test_util.h"

namespace glint {
namespace {

using Channels = std::map<std::string, std::vector<float>>;

constexpr int kSize = 4;  // Blender renders at least 4 x 4 pixels
const char* kAllAovs =
    "depth,normal,albedo,position,objectid,direct,indirect,lights,variance,cryptomatte";

// Looking straight down from y = 5 (orthographic, 4 x 4 units, one sample at each pixel's
// centre): pixel (x, y) sees the point (x − 1.5, 0, y − 1.5). A Lambert quad at y = 0 covers
// x ≤ 1, so columns 0–2 hit it and column 3 sees nothing (transparent film). Light 0 is
// directional along (0,−1,−1)/√2 (cos θ = 1/√2), light 1 a point light at (0, 2, 0) of
// intensity 2 without falloff (cos θ = 2/√(x² + z² + 4)). The quad is named "Floor" and light 0
// "Sun Lamp", so the readers see names where Glint writes them: Cryptomatte's manifest and the
// light's layer (light_Sun_Lamp).
const char* kScene = R"({
  "render": {"width": 4, "height": 4, "spp": 1, "sampler": "regular",
             "transparent_background": true},
  "camera": {"type": "orthographic", "eye": [0,5,0], "look_at": [0,0,0], "up": [0,0,-1],
             "height": 4},
  "materials": {"m": {"type": "phong", "kd": [0.5,0.4,0.2], "ka": [0,0,0]}},
  "lights": [{"type": "directional", "name": "Sun Lamp", "direction": [0,-1,-1]},
             {"type": "point", "position": [0,2,0], "intensity": [2,2,2]}],
  "objects": [{"type": "quad", "name": "Floor", "corner": [-2,0,-2], "edge1": [0,0,4],
               "edge2": [3,0,0], "material": "m"}]})";

// Every channel's value at pixel (x, y), worked out from the scene above.
std::map<std::string, double> expectedAt(int x, int y) {
  const double px = x - 1.5, pz = y - 1.5;
  const bool hit = px < 1;
  const double kd[3] = {0.5, 0.4, 0.2};
  const char* rgb[3] = {"R", "G", "B"};
  const char* xyz[3] = {"X", "Y", "Z"};
  std::map<std::string, double> v;
  const double cos1 = 2 / std::sqrt(px * px + pz * pz + 4);
  for (int c = 0; c < 3; ++c) {
    const double l0 = hit ? kd[c] * std::sqrt(0.5) : 0, l1 = hit ? kd[c] * 2 * cos1 : 0;
    v[rgb[c]] = l0 + l1;  // the beauty is all direct light
    v[std::string("direct.") + rgb[c]] = l0 + l1;
    v[std::string("indirect.") + rgb[c]] = 0;
    v[std::string("light_Sun_Lamp.") + rgb[c]] = l0;
    v[std::string("light1.") + rgb[c]] = l1;
    v[std::string("Albedo.") + rgb[c]] = hit ? kd[c] : 0;
    v[std::string("Variance.") + rgb[c]] = 0;  // one sample: no estimate
    v[std::string("N.") + xyz[c]] = hit && c == 1 ? 1 : 0;
  }
  v["A"] = hit ? 1 : 0;
  v["P.X"] = hit ? px : 0;
  v["P.Y"] = 0;
  v["P.Z"] = hit ? pz : 0;
  v["Z"] = hit ? 5 : 1e10;       // the far value where nothing was hit
  v["IndexOB.X"] = hit ? 1 : 0;  // Floor, the first object
  // Rank 0 is the one object (or material) with all the coverage; the other ranks are empty.
  for (const auto& [type, name] : {std::pair{"CryptoObject", "Floor"}, {"CryptoMaterial", "m"}})
    for (int layer = 0; layer < 3; ++layer)
      for (const char* c : {"R", "G", "B", "A"}) {
        const std::string channel = type + std::string("0") + std::to_string(layer) + "." + c;
        const bool first = hit && layer == 0;
        v[channel] = first && c == std::string("R")   ? double(cryptomatteId(name))
                     : first && c == std::string("G") ? 1.0
                                                      : 0.0;
      }
  return v;
}

// Compares what a reader gave for every channel with expectedAt, at every pixel.
void expectTheScenesValues(const Channels& read, const std::string& what) {
  const std::map<std::string, double> names = expectedAt(0, 0);
  std::set<std::string> expectedNames, readNames;
  for (const auto& [name, value] : names) expectedNames.insert(name);
  for (const auto& [name, values] : read) readNames.insert(name);
  EXPECT_EQ(readNames, expectedNames) << what;
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x)
      for (const auto& [name, value] : expectedAt(x, y)) {
        const auto it = read.find(name);
        if (it == read.end() || it->second.size() != size_t(kSize * kSize)) continue;
        const float got = it->second[size_t(y * kSize + x)];
        // Ids (Cryptomatte's hashes, the object index) and depths are exact: a matte is picked
        // by the ID's bits. Shading values agree to float rounding of their sums (1e-6).
        if (name.rfind("Crypto", 0) == 0 || name == "IndexOB.X" || name == "Z")
          EXPECT_EQ(got, float(value)) << what << ": " << name << " at (" << x << ", " << y << ")";
        else
          EXPECT_NEAR(got, value, 1e-6 * std::max(1.0, std::abs(value)))
              << what << ": " << name << " at (" << x << ", " << y << ")";
      }
}

std::string renderFrame(const std::string& name, const std::string& flags) {
  const std::string scene = test::writeTemp("compositor.json", kScene);
  const std::string out = (test::tempDir() / name).string();
  const auto run =
      test::runGlint("render " + scene + " --quiet --aov " + kAllAovs + " " + flags + " -o " + out);
  EXPECT_EQ(run.exitCode, 0) << run.output;
  return out;
}

// Whether Blender 3.4's EXR reader can split `channel` into pass and component
// (imb_exr_split_channel_name): a one-letter name, or PASS.C where C is one letter, two letters
// ending in X, Y, Z, R, G, B, U, V or A, or red, green, blue, alpha or depth. Blender drops any
// other channel, and a part left with none fails its read and the parts after it.
bool blenderCanName(const std::string& channel) {
  if (channel.size() == 1) return true;
  const size_t dot = channel.rfind('.');
  if (dot == std::string::npos || dot == 0) return false;
  std::string c = channel.substr(dot + 1);
  for (char& ch : c) ch = char(std::toupper(static_cast<unsigned char>(ch)));
  if (c.size() == 1) return true;
  if (c.size() == 2) return std::string("XYZRGBUVA").find(c[1]) != std::string::npos;
  return c == "RED" || c == "GREEN" || c == "BLUE" || c == "ALPHA" || c == "DEPTH";
}

// Every channel of every part, each part read through its own InputPart with every one of its
// channels in the frame buffer (as float, whatever its type), as Blender reads a multipart file;
// every channel must have a name Blender can read.
Channels readEveryPart(const std::string& path, std::vector<std::string>* partNames = nullptr,
                       std::string* objectManifest = nullptr) {
  Channels out;
  Imf::MultiPartInputFile file(path.c_str());
  for (int p = 0; p < file.parts(); ++p) {
    Imf::InputPart part(file, p);
    const Imf::Header& h = part.header();
    if (partNames) partNames->push_back(h.hasName() ? h.name() : "");
    const auto* manifest =
        h.findTypedAttribute<Imf::StringAttribute>("cryptomatte/3ae39a5/manifest");
    if (objectManifest && manifest) *objectManifest = manifest->value();
    const Imath::Box2i dw = h.dataWindow();
    const int width = dw.max.x - dw.min.x + 1, height = dw.max.y - dw.min.y + 1;
    EXPECT_EQ(width, kSize);
    EXPECT_EQ(height, kSize);
    Imf::FrameBuffer frameBuffer;
    for (auto c = h.channels().begin(); c != h.channels().end(); ++c) {
      EXPECT_EQ(out.count(c.name()), 0u) << c.name() << " in two parts of " << path;
      EXPECT_TRUE(blenderCanName(c.name())) << c.name() << " of part " << p << " of " << path;
      std::vector<float>& values = out[c.name()];
      values.assign(size_t(width) * size_t(height), -1.0f);
      frameBuffer.insert(c.name(), Imf::Slice::Make(Imf::FLOAT, values.data(), dw));
    }
    EXPECT_NE(frameBuffer.begin(), frameBuffer.end()) << "part " << p << " has no channels";
    part.setFrameBuffer(frameBuffer);
    EXPECT_NO_THROW(part.readPixels(dw.min.y, dw.max.y)) << "part " << p << " of " << path;
  }
  return out;
}

// The property both readers check: every layer of the single-part and the multipart frame
// reads with the scene's values.
void checkWithOpenExr(const std::string& single, const std::string& multipart) {
  std::vector<std::string> parts;
  std::string manifest;
  expectTheScenesValues(readEveryPart(single, &parts, &manifest), single);
  EXPECT_EQ(parts.size(), 1u);
  // The objectid pass and Cryptomatte name an object alike: id 1 is Floor, which the manifest
  // lists with its Cryptomatte ID.
  const nlohmann::json objects = nlohmann::json::parse(manifest);
  EXPECT_EQ(objects.value("Floor", ""), cryptomatteHex(cryptomatteId("Floor")));
  parts.clear();
  expectTheScenesValues(readEveryPart(multipart, &parts), multipart);
  EXPECT_EQ(parts,
            (std::vector<std::string>{"rgba", "depth", "normal", "albedo", "position", "objectid",
                                      "direct", "indirect", "light_Sun_Lamp", "light1", "variance",
                                      "CryptoObject00", "CryptoObject01", "CryptoObject02",
                                      "CryptoMaterial00", "CryptoMaterial01", "CryptoMaterial02"}));
}

TEST(ExrCompositor, EveryPartOfAFrameWithEveryAovReadsWholeThroughOpenExr) {
  checkWithOpenExr(renderFrame("all-aovs.exr", ""),
                   renderFrame("all-aovs-multipart.exr", "--multipart"));
}

// The channels each of Blender's compositor outputs carries, in the order its RGBA holds them
// (one channel: R = G = B).
std::vector<std::string> channelsOfBlenderOutput(const std::string& output) {
  if (output == "Combined") return {"R", "G", "B", "A"};
  if (output == "Alpha") return {"A"};
  if (output == "Depth") return {"Z"};
  if (output == "IndexOB") return {"IndexOB.X"};
  if (output == "N" || output == "P") return {output + ".X", output + ".Y", output + ".Z"};
  if (output.rfind("Crypto", 0) == 0)
    return {output + ".R", output + ".G", output + ".B", output + ".A"};
  return {output + ".R", output + ".G", output + ".B"};
}

// Blender's compositor output, one RGBA EXR it wrote, as this test's channels ("Alpha" under its
// own name, to compare with Combined's A).
void readBlenderOutput(const std::string& path, const std::string& output, Channels& out) {
  Imf::InputFile in(path.c_str());
  const Imath::Box2i dw = in.header().dataWindow();
  ASSERT_EQ(dw.max.x - dw.min.x + 1, kSize) << path;
  ASSERT_EQ(dw.max.y - dw.min.y + 1, kSize) << path;
  std::vector<float> rgba[4];
  Imf::FrameBuffer frameBuffer;
  const char* names[4] = {"R", "G", "B", "A"};
  for (int c = 0; c < 4; ++c) {
    rgba[c].assign(size_t(kSize * kSize), -1.0f);
    frameBuffer.insert(names[c], Imf::Slice::Make(Imf::FLOAT, rgba[c].data(), dw));
  }
  in.setFrameBuffer(frameBuffer);
  in.readPixels(dw.min.y, dw.max.y);
  const std::vector<std::string> channels = channelsOfBlenderOutput(output);
  if (channels.size() == 1) {  // a one-channel pass comes out grey
    EXPECT_EQ(rgba[1], rgba[0]) << path;
    EXPECT_EQ(rgba[2], rgba[0]) << path;
  }
  for (size_t c = 0; c < channels.size(); ++c)
    out[output == "Alpha" ? output : channels[c]] = rgba[c];
}

TEST(ExrCompositor, BlenderReadsEveryLayerOfSingleAndMultipartFrames) {
  const std::string single = renderFrame("blender.exr", "");
  const std::string multipart = renderFrame("blender-multipart.exr", "--multipart");
  if (std::system("command -v blender >/dev/null 2>&1") != 0) {
    std::cerr << "\n*** Blender is NOT installed (no `blender` on PATH): this test checks the\n"
                 "*** frames with OpenEXR's multipart reader instead, a frame buffer for every\n"
                 "*** part and every channel named as Blender 3.4 reads names. Install Blender\n"
                 "*** (apt-get install blender) to check Blender itself.\n\n";
    checkWithOpenExr(single, multipart);
    return;
  }
  const std::string dir = (test::tempDir() / "blender-out").string();
  std::filesystem::remove_all(dir);
  const std::string script = std::string(GLINT_SOURCE_DIR) + "/tests/film/blender_read_exr.py";
  const std::string command =
      "timeout 120 blender -b --factory-startup --python-exit-code 3 "
      "--python " +
      script + " -- " + dir + " " + std::to_string(kSize) + " " + std::to_string(kSize) + " " +
      single + " " + multipart + " 2>&1";
  std::string log;
  FILE* pipe = ::popen(command.c_str(), "r");
  ASSERT_NE(pipe, nullptr);
  char buffer[4096];
  size_t n;
  while ((n = std::fread(buffer, 1, sizeof buffer, pipe)) > 0) log.append(buffer, n);
  ASSERT_EQ(::pclose(pipe), 0) << log;
  // Blender says what it could not read, and goes on: a channel it cannot name, a part left
  // without a frame buffer.
  EXPECT_EQ(log.find("unknown channel token"), std::string::npos) << log;
  EXPECT_EQ(log.find("OpenEXR-readPixels: ERROR"), std::string::npos) << log;
  EXPECT_NE(log.find(single + " is MULTILAYER"), std::string::npos) << log;
  EXPECT_NE(log.find(multipart + " is MULTILAYER"), std::string::npos) << log;
  const std::set<std::string> outputs = {"Combined",
                                         "Alpha",
                                         "Depth",
                                         "N",
                                         "P",
                                         "Albedo",
                                         "IndexOB",
                                         "direct",
                                         "indirect",
                                         "light_Sun_Lamp",  // the light named "Sun Lamp"
                                         "light1",
                                         "Variance",
                                         "CryptoObject00",
                                         "CryptoObject01",
                                         "CryptoObject02",
                                         "CryptoMaterial00",
                                         "CryptoMaterial01",
                                         "CryptoMaterial02"};
  for (const auto& [number, frame] : {std::pair{0, single}, {1, multipart}}) {
    const std::string folder = dir + "/" + std::to_string(number);
    std::set<std::string> listed;
    std::istringstream lines(test::readFile(folder + "/outputs.txt"));
    for (std::string line; std::getline(lines, line);) listed.insert(line);
    EXPECT_EQ(listed, outputs) << frame;
    Channels read;
    for (const std::string& output : listed)
      readBlenderOutput(folder + "/" + output + ".exr", output, read);
    const std::vector<float> alpha = read["Alpha"];
    read.erase("Alpha");
    EXPECT_EQ(alpha, read["A"]) << frame;
    expectTheScenesValues(read, frame + " through Blender");
  }
}

}  // namespace
}  // namespace glint
