#pragma once
// The files an OCIO config reads pass Glint's input check (core/input_files.h) before OCIO
// opens any of them: OCIO reads a FileTransform's LUT whole when it builds a processor, so a
// look naming a FIFO waited for a writer for ever and /dev/zero as a LUT was read until memory
// ran out.
#include <OpenColorIO/OpenColorIO.h>

#include <cstdint>
#include <string>

namespace glint {

// A config file (YAML, a few hundred kB for a studio config) and a LUT it names (a 65-point
// cube as text is about 8 MB) may have at most these many bytes.
inline constexpr uint64_t kMaxOcioConfigBytes = uint64_t{16} << 20;
inline constexpr uint64_t kMaxOcioFileBytes = uint64_t{256} << 20;

// Checks every file that a FileTransform of `config` names (in its colour spaces, looks, view
// transforms and named transforms, through group transforms), resolved through the config's
// search path and context as OCIO resolves it. Files that do not resolve are left to OCIO,
// which reports them only where a processor needs them. Throws UsageError naming `source` (the
// config), the colour space or look, and the file.
void checkOcioConfigFiles(const OCIO_NAMESPACE::ConstConfigRcPtr& config,
                          const std::string& source);

}  // namespace glint
