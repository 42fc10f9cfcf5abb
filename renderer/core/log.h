#pragma once
// Diagnostics on stderr, serialised across render threads. `--quiet` lowers the level.
#include <string_view>

namespace glint::log {

enum class Level { Error = 0, Warning = 1, Info = 2 };
void setLevel(Level level);
Level level();
void error(std::string_view msg);
void warning(std::string_view msg);
void info(std::string_view msg);

}  // namespace glint::log
