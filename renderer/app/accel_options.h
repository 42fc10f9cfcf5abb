#pragma once
// The options that set a backend's own settings (accel/accelerator.h's AccelOptions), shared by
// render, validate and bench: --rayclass-n-min and --rayclass-w-min.
#include <CLI/CLI.hpp>

#include "accel/accelerator.h"

namespace glint {

void addAccelOptions(CLI::App& cmd, AccelOptions& options);

}  // namespace glint
