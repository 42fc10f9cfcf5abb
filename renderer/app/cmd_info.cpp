#include <OpenColorIO/OpenColorIO.h>
#include <OpenEXR/OpenEXRConfig.h>
#include <OpenImageIO/oiioversion.h>
#include <embree3/rtcore.h>
#include <glint_version.h>
#include <png.h>
#include <tbb/version.h>

#include <cstdio>

#include "accel/embree_accel.h"
#include "accel/reference_bvh.h"
#include "app/commands.h"
#include "app/scene_source.h"
#include "core/cpu_features.h"
#include "render/tile_scheduler.h"

namespace glint {

namespace {

std::string embreeWidths() {
  RTCDevice d = embreeDevice();
  std::string s = "ray4";
  if (rtcGetDeviceProperty(d, RTC_DEVICE_PROPERTY_NATIVE_RAY8_SUPPORTED)) s += ", ray8";
  if (rtcGetDeviceProperty(d, RTC_DEVICE_PROPERTY_NATIVE_RAY16_SUPPORTED)) s += ", ray16";
  return s;
}

}  // namespace

void printSceneStats(const std::string& path) {
  const Scene scene = loadSceneOrDefault(path);
  std::printf("scene        %s\n", scene.sourcePath.c_str());
  std::printf(
      "geometry     %zu triangles, %zu spheres, %zu quads, %zu planes, %zu instances, "
      "%zu groups\n",
      scene.triangleCount(), scene.spheres.size(), scene.quads.size(), scene.planes.size(),
      scene.instances.size(), scene.groups.size() - 1);
  const EmbreeAccel embree(scene);
  std::printf("embree       build %.3f s, %.1f MiB\n", embree.buildSeconds(),
              double(embree.bytes()) / (1 << 20));
  const ReferenceBvh bvh(scene);
  const BvhStats& b = bvh.stats();
  std::printf(
      "bvh          build %.3f s, %zu nodes, %zu leaves, %.2f prims/leaf, depth %zu, "
      "SAH cost %.2f, %.1f MiB\n",
      b.buildSeconds, b.nodes, b.leaves, b.primitivesPerLeaf(), b.maxDepth, b.sahCost,
      double(b.bytes) / (1 << 20));
}

CommandRunner addInfoCommand(CLI::App& app) {
  auto scenePath = std::make_shared<std::string>();
  auto withScene = std::make_shared<bool>(false);
  auto ocio = std::make_shared<bool>(false);
  auto ocioConfig = std::make_shared<std::string>();
  CLI::App* cmd = app.add_subcommand(
      "info", "Version, libraries, ISA and thread count; with SCENE, acceleration statistics");
  cmd->add_option("scene", *scenePath, "Scene file: also print build statistics of both backends")
      ->check(CLI::ExistingFile)
      ->each([withScene](const std::string&) { *withScene = true; });
  CLI::Option* list = cmd->add_flag(
      "--ocio", *ocio, "List the active OCIO config's displays, views and colour spaces");
  // Alone it would be read by nothing: the user meant a listing.
  cmd->add_option("--ocio-config", *ocioConfig,
                  "OCIO config to list (default: $OCIO, else bundled)")
      ->needs(list);
  return [scenePath, withScene, ocio, ocioConfig] {
    std::printf("glint        %s\n", GLINT_VERSION);
    std::printf("Embree       %s (native packets: %s)\n", embreeVersionString().c_str(),
                embreeWidths().c_str());
    std::printf("CPU ISA      %s\n", cpuFeatureNames(cpuFeatures()).c_str());
    std::printf("OpenEXR      %s\n", OPENEXR_VERSION_STRING);
    std::printf("libpng       %s\n", PNG_LIBPNG_VER_STRING);
    std::printf("OpenImageIO  %s (module, loaded only for .jpg and .tif images)\n",
                OIIO_VERSION_STRING);
    std::printf("OpenColorIO  %s\n", OCIO_NAMESPACE::GetVersion());
    std::printf("oneTBB       %s\n", TBB_runtime_version());
    std::printf("threads      %d\n", defaultThreadCount());
    if (*ocio) std::printf("%s", describeOcioConfig(*ocioConfig).c_str());
    if (*withScene) printSceneStats(*scenePath);
    return kExitOk;
  };
}

}  // namespace glint
