#include "film/oiio_module.h"

#include <dlfcn.h>

#include <filesystem>

#include "core/error.h"
#include "core/memory.h"
#include "core/out_of_memory.h"
#include "film/oiio_module_abi.h"

namespace glint::oiio_module {

namespace {

struct Module {
  GlintOiioWriteImage writeImage = nullptr;
  TextureFunctions texture;
  std::string error;         // why it could not be loaded
  bool outOfMemory = false;  // the reason is memory, not the installation
};

// What loading the module takes (docs/hardening.md, "Memory"): address space for its ~270
// libraries' mappings and log4cplus's threads (their stacks and malloc arenas), and memory for
// the pages it touches. A process that lacks it would fail inside the libraries' constructors:
// a thread that cannot start aborts, or a failed allocation crashes.
constexpr uint64_t kModuleAddressSpaceBytes = 480'000'000;
constexpr uint64_t kModuleMemoryBytes = 160'000'000;

// Why the module cannot be loaded within this process's memory, or empty.
std::string moduleMemoryShortage() {
  const MemoryReadings r = readMemoryReadings();
  if (r.addressSpaceLimit) {
    const uint64_t left =
        *r.addressSpaceLimit > r.addressSpaceUsed ? *r.addressSpaceLimit - r.addressSpaceUsed : 0;
    if (left < kModuleAddressSpaceBytes)
      return "out of memory: loading the image module (OpenImageIO) needs about " +
             memorySize(double(kModuleAddressSpaceBytes)) +
             " of address space, the limit (ulimit -v) leaves " + memorySize(double(left));
  }
  MemoryReadings memoryOnly = r;
  memoryOnly.addressSpaceLimit.reset();
  const MemoryBudget budget = memoryBudget(memoryOnly);
  if (budget.limitedBy != MemoryLimit::Unknown && budget.bytes < kModuleMemoryBytes)
    return "out of memory: loading the image module (OpenImageIO) needs about " +
           memorySize(double(kModuleMemoryBytes)) + " of memory, more than " +
           describeBudget(budget);
  return "";
}

const Module& module() {
  static const Module loaded = [] {
    Module m;
    for (const std::string& path : searchPath()) {
      if (!std::filesystem::exists(path)) continue;
      m.error = moduleMemoryShortage();
      if (!m.error.empty()) {
        m.outOfMemory = true;
        return m;
      }
      void* handle = out_of_memory::whileDoing("loading the image module (OpenImageIO)", [&] {
        return dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
      });
      if (!handle) {
        const char* why = dlerror();
        m.error = why ? why : "dlopen failed";
        // The loader reports a mapping it could not make as ENOMEM's text.
        m.outOfMemory = m.error.find("Cannot allocate memory") != std::string::npos;
        if (m.outOfMemory)
          m.error = "out of memory while loading the image module (OpenImageIO): " + m.error;
        return m;
      }
      const auto symbol = [&]<class F>(F& f, const char* name) {
        f = reinterpret_cast<F>(dlsym(handle, name));
        if (!f && m.error.empty()) m.error = path + " has no " + name;
      };
      symbol(m.writeImage, kGlintOiioWriteImageSymbol);
      symbol(m.texture.open, kGlintOiioTextureOpenSymbol);
      symbol(m.texture.openMemory, kGlintOiioTextureOpenMemorySymbol);
      symbol(m.texture.read, kGlintOiioTextureReadSymbol);
      symbol(m.texture.close, kGlintOiioTextureCloseSymbol);
      if (!m.error.empty()) m.writeImage = nullptr, m.texture = {};
      return m;  // loaded for the rest of the process
    }
    m.error = std::string(kGlintOiioModuleName) + " is not installed (looked in";
    for (const std::string& path : searchPath()) m.error += " " + path;
    m.error += ")";
    return m;
  }();
  return loaded;
}

}  // namespace

std::vector<std::string> searchPath() {
  std::vector<std::string> paths;
  std::error_code ec;
  const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (!ec)
    paths.push_back((exe.parent_path() / "../lib/glint" / kGlintOiioModuleName).lexically_normal());
  paths.push_back(std::string(GLINT_MODULE_BUILD_DIR) + "/" + kGlintOiioModuleName);
  return paths;
}

void writeImage(const std::string& path, const std::string& tmpPath, int width, int height,
                int channels, int bits, const std::vector<uint16_t>& codes) {
  const Module& m = module();
  if (!m.writeImage) {
    if (m.outOfMemory) throw OutOfMemoryError(m.error + " (to write " + path + ")");
    throw GlintError("cannot write " + path + ": OpenImageIO's module: " + m.error);
  }
  std::vector<uint8_t> bytes;
  if (bits == 8) bytes.assign(codes.begin(), codes.end());
  const void* pixels = bits == 8 ? static_cast<const void*>(bytes.data()) : codes.data();
  char error[512] = "";
  if (m.writeImage(path.c_str(), tmpPath.c_str(), width, height, channels, bits, pixels, error,
                   sizeof error) != 0)
    throw GlintError("cannot write " + path + ": " + error);
}

}  // namespace glint::oiio_module

namespace glint::oiio_module {

const TextureFunctions& textureFunctions(const std::string& path) {
  const Module& m = module();
  if (!m.texture.read) {
    if (m.outOfMemory) throw OutOfMemoryError(m.error + " (to read texture " + path + ")");
    throw GlintError("cannot read texture " + path + ": OpenImageIO's module: " + m.error);
  }
  return m.texture;
}

}  // namespace glint::oiio_module
