// libFuzzer target over the scene loader (docs/hardening.md). Any bytes may come in; the only
// acceptable outcomes are a Scene or a GlintError. A SceneError must name "<fuzz>" and a line,
// since every value the loader can complain about has one. A Scene must be usable: the reference
// BVH (Glint's own code, so instrumented, unlike Embree) builds, keeps its invariants and traces
// the camera's central ray, for an animation at its first, middle and last frame. Crashes,
// sanitizer reports, other exceptions and hangs are bugs.
#include <nlohmann/json.hpp>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "accel/reference_bvh.h"
#include "camera/camera.h"
#include "core/error.h"
#include "core/log.h"
#include "fuzz_temp_dir.h"
#include "io/scene_loader.h"

namespace {

namespace fs = std::filesystem;

// Mesh paths resolve against a private directory, glint-fuzz-PID in the temporary directory,
// holding copies of the small test meshes, so the fuzzer reaches the mesh-file code without
// reading anything else on the machine.
fs::path gBaseDir;

bool escapesBaseDir(const std::string& file) {
  const fs::path p(file);
  if (p.is_absolute() || p.has_root_name() || p.has_root_directory()) return true;
  for (const auto& part : p)
    if (part == "..") return true;
  return false;
}

// True when a "file" value anywhere in the document could name something outside gBaseDir.
// Walks iteratively: fuzz inputs nest deeper than the stack allows recursion.
bool namesOutsideFile(const std::string& text) {
  const auto doc = nlohmann::json::parse(text, nullptr, false, /*ignore_comments=*/true);
  if (doc.is_discarded()) return false;  // the loader reports the syntax error
  std::vector<const nlohmann::json*> todo{&doc};
  while (!todo.empty()) {
    const nlohmann::json* v = todo.back();
    todo.pop_back();
    if (v->is_object()) {
      const auto f = v->find("file");
      if (f != v->end() && f->is_string() && escapesBaseDir(f->get<std::string>())) return true;
    }
    if (v->is_structured())
      for (const auto& child : *v) todo.push_back(&child);
  }
  return false;
}

[[noreturn]] void bug(const std::string& what) {
  std::fprintf(stderr, "glint_fuzz_scene: %s\n", what.c_str());
  std::abort();
}

// What reads a loaded scene next must cope with it: bounds, the camera, the reference BVH.
void checkUsable(const glint::Scene& scene) {
  (void)scene.worldBounds();
  const glint::Camera camera(scene.cameraDesc, scene.render.width, scene.render.height);
  const glint::Ray ray = camera.generateRay(0.5f * static_cast<float>(scene.render.width),
                                            0.5f * static_cast<float>(scene.render.height));
  const glint::ReferenceBvh bvh(scene);
  if (const std::string broken = bvh.checkInvariants(); !broken.empty())
    bug("reference BVH invariant: " + broken);
  if (const glint::Hit hit = bvh.intersect(ray)) (void)scene.shadingPoint(ray, hit);
  (void)bvh.occluded(ray);
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  glint::log::setLevel(glint::log::Level::Error);  // motion-without-shutter warnings are noise
  gBaseDir = glint::fuzz::makePrivateTempDir("glint-fuzz-");
  for (const char* mesh : {"square.ply", "triangle.gltf"})
    fs::copy_file(fs::path(GLINT_TEST_DATA) / mesh, gBaseDir / mesh);
  glint::fuzz::addHostileFiles(gBaseDir);
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  if (namesOutsideFile(text)) return -1;  // -1: keep this input out of the corpus
  try {
    const glint::Scene scene = glint::loadSceneText(text, "<fuzz>", gBaseDir.string());
    checkUsable(scene);
    if (scene.animation) {
      // Loading picks the first frame; a middle and the last one resample the keys between and
      // at the far end of the animation (int64: first and last may be far apart).
      const glint::Animation& a = *scene.animation;
      const int middle = static_cast<int>(a.first + (int64_t{a.last} - a.first) / 2);
      for (const int f : {middle, a.last})
        if (f != a.first) checkUsable(glint::loadSceneText(text, "<fuzz>", gBaseDir.string(), f));
    }
  } catch (const glint::SceneError& e) {
    if (e.loc().file != "<fuzz>" || e.loc().line <= 0)
      bug(std::string("SceneError without file:line: ") + e.what());
  } catch (const glint::GlintError&) {
    // Other user-facing errors (a mesh file Assimp refuses) are acceptable outcomes too.
  }
  return 0;
}
