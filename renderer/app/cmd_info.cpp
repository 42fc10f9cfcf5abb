#include <OpenColorIO/OpenColorIO.h>
#include <OpenImageIO/oiioversion.h>
#include <embree3/rtcore.h>
#include <glint_version.h>
#include <tbb/version.h>

#include <cstdio>

#include "accel/embree_accel.h"
#include "app/commands.h"
#include "render/tile_scheduler.h"

namespace glint {

namespace {

std::string cpuIsa() {
  __builtin_cpu_init();
  if (__builtin_cpu_supports("avx512f")) return "AVX-512";
  if (__builtin_cpu_supports("avx2")) return "AVX2";
  if (__builtin_cpu_supports("avx")) return "AVX";
  if (__builtin_cpu_supports("sse4.2")) return "SSE4.2";
  return "SSE2";
}

std::string embreeWidths() {
  RTCDevice d = embreeDevice();
  std::string s = "ray4";
  if (rtcGetDeviceProperty(d, RTC_DEVICE_PROPERTY_NATIVE_RAY8_SUPPORTED)) s += ", ray8";
  if (rtcGetDeviceProperty(d, RTC_DEVICE_PROPERTY_NATIVE_RAY16_SUPPORTED)) s += ", ray16";
  return s;
}

}  // namespace

CommandRunner addInfoCommand(CLI::App& app) {
  CLI::App* cmd = app.add_subcommand("info", "Version, libraries, ISA and thread count");
  (void)cmd;
  return [] {
    std::printf("glint        %s\n", GLINT_VERSION);
    std::printf("Embree       %s (native packets: %s)\n", embreeVersionString().c_str(),
                embreeWidths().c_str());
    std::printf("CPU ISA      %s\n", cpuIsa().c_str());
    std::printf("OpenImageIO  %s\n", OIIO_VERSION_STRING);
    std::printf("OpenColorIO  %s\n", OCIO_NAMESPACE::GetVersion());
    std::printf("oneTBB       %s\n", TBB_runtime_version());
    std::printf("threads      %d\n", defaultThreadCount());
    return kExitOk;
  };
}

}  // namespace glint
