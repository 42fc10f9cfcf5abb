#include "core/log.h"

#include <atomic>
#include <cstdio>
#include <mutex>

namespace glint::log {

namespace {
std::atomic<Level> gLevel{Level::Info};
std::mutex gMutex;

void emit(Level l, const char* prefix, std::string_view msg) {
  if (l > gLevel.load(std::memory_order_relaxed)) return;
  std::lock_guard lock(gMutex);
  std::fprintf(stderr, "glint: %s%.*s\n", prefix, static_cast<int>(msg.size()), msg.data());
}
}  // namespace

void setLevel(Level l) { gLevel = l; }
Level level() { return gLevel; }
void error(std::string_view msg) { emit(Level::Error, "error: ", msg); }
void warning(std::string_view msg) { emit(Level::Warning, "warning: ", msg); }
void info(std::string_view msg) { emit(Level::Info, "", msg); }

}  // namespace glint::log
