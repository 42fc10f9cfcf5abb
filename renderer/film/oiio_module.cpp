#include "film/oiio_module.h"

#include <dlfcn.h>

#include <filesystem>

#include "core/error.h"
#include "film/oiio_module_abi.h"

namespace glint::oiio_module {

namespace {

struct Module {
  GlintOiioWriteImage writeImage = nullptr;
  TextureFunctions texture;
  std::string error;  // why it could not be loaded
};

const Module& module() {
  static const Module loaded = [] {
    Module m;
    for (const std::string& path : searchPath()) {
      if (!std::filesystem::exists(path)) continue;
      void* handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
      if (!handle) {
        m.error = dlerror();
        return m;
      }
      const auto symbol = [&]<class F>(F& f, const char* name) {
        f = reinterpret_cast<F>(dlsym(handle, name));
        if (!f && m.error.empty()) m.error = path + " has no " + name;
      };
      symbol(m.writeImage, kGlintOiioWriteImageSymbol);
      symbol(m.texture.open, kGlintOiioTextureOpenSymbol);
      symbol(m.texture.openMemory, kGlintOiioTextureOpenMemorySymbol);
      symbol(m.texture.lookup, kGlintOiioTextureLookupSymbol);
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
  if (!m.writeImage)
    throw GlintError("cannot write " + path + ": OpenImageIO's module: " + m.error);
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
  if (!m.texture.lookup)
    throw GlintError("cannot read texture " + path + ": OpenImageIO's module: " + m.error);
  return m.texture;
}

}  // namespace glint::oiio_module
