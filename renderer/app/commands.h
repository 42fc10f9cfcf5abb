#pragma once
// The `glint` subcommands (../shared/CLI.md). Each registers its options on the CLI11 app and
// returns the process exit code when run.
#include <CLI/CLI.hpp>

#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <functional>
#include <string>

#include "core/error.h"
#include "core/interrupt.h"
#include "film/display.h"

namespace glint {

// Exit codes of CLI.md.
inline constexpr int kExitOk = 0;
inline constexpr int kExitRuntime = 1;
inline constexpr int kExitUsage = 2;
inline constexpr int kExitInterrupted = interrupt::kExitCode;

using CommandRunner = std::function<int()>;

CommandRunner addRenderCommand(CLI::App& app);
CommandRunner addInfoCommand(CLI::App& app);
CommandRunner addValidateCommand(CLI::App& app);
CommandRunner addBenchCommand(CLI::App& app);
CommandRunner addMergeCommand(CLI::App& app);
CommandRunner addPlanCommand(CLI::App& app);
CommandRunner addCompareCommand(CLI::App& app);
CommandRunner addConvergeCommand(CLI::App& app);

// --view, --ocio-display, --look, --ocio-config: how a display image is made (film/display.h).
// CLI.md's --display names the output image, so the OCIO display is --ocio-display.
void addDisplayOptions(CLI::App& cmd, DisplaySettings& settings);

CommandRunner addConvertCommand(CLI::App& app);

// Refuses NaN, which passes CLI11's range and positivity checks (every comparison is false).
inline CLI::Validator notNaN() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        return std::isnan(std::strtod(text.c_str(), nullptr))
                   ? "must be a number, got " + excerpt(text)
                   : std::string();
      },
      "NUMBER");
}

// Refuses an empty value, which the command would read as the option left out (merge
// --scene-hash '' checked no hash, render --frames '' rendered the first frame).
inline CLI::Validator nonEmpty() {
  return CLI::Validator(
      [](std::string& text) {
        return text.empty() ? std::string("must not be empty; leave the option out instead")
                            : std::string();
      },
      "TEXT");
}

// Accepts a finite number above 0, as a whole text ("0.01abc" is refused, not read as 0.01).
// CLI11's PositiveNumber told "--target-rmse 0" it was "not in range 0 to 1.8e308" and read
// "abc" as out of range.
inline CLI::Validator positiveNumber() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        char* end = nullptr;
        const double v = std::strtod(text.c_str(), &end);
        if (text.empty() || *end != '\0' || std::isnan(v))
          return "must be a number, got " + excerpt(text);
        if (!(v > 0) || !std::isfinite(v))
          return "must be a finite number above 0, got " + excerpt(text);
        return {};
      },
      "NUMBER > 0");
}

// Accepts a whole number that fits `max` and is not negative. CLI11 reads "-1" into an unsigned
// option as 2^64 − 1 and an overflowing one as the largest value: both are refused instead.
inline CLI::Validator wholeNumberUpTo(uint64_t max) {
  return CLI::Validator(
      [max](std::string& text) -> std::string {
        errno = 0;
        char* end = nullptr;
        const unsigned long long v = std::strtoull(text.c_str(), &end, 0);
        if (text.empty() || text.find('-') != std::string::npos || *end != '\0' ||
            errno == ERANGE || v > max)
          return "must be a whole number from 0 to " + std::to_string(max) + ", got " +
                 excerpt(text);
        return {};
      },
      "UINT");
}

// An option's default as its help text states it: the value the option's variable holds before
// parsing, so that the help cannot drift from the code. Numbers in their shortest exact form.
inline std::string defaultText(const std::string& value) { return value; }
inline std::string defaultText(double value) {
  char text[32];
  return std::string(text, std::to_chars(text, text + sizeof text, value).ptr);
}
inline std::string defaultText(int value) { return std::to_string(value); }

// The command line as typed, for EXR metadata.
const std::string& commandLine();

// Runs the whole command line; errors are printed and mapped to exit codes.
int runCli(int argc, char** argv);

}  // namespace glint
