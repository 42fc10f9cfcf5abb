#pragma once
// Opening an EXR a user named (glint compare, convert, converge --reference, merge): OpenEXR's
// reader only, never another of OpenImageIO's hundred formats, and only after Glint has checked
// the file's headers: every attribute's declared size must fit in the bytes that follow it.
// OpenEXR 3.1 allocates a string attribute's declared size before reading it, so a 1.7 kB file
// declaring two 918 MB strings took 1.8 GB (found by glint_fuzz_exr).
#include <OpenImageIO/imageio.h>

#include <memory>
#include <string>

namespace glint {

// Throws UsageError naming `path` when the checks below fail or OpenEXR cannot open it.
std::unique_ptr<OIIO::ImageInput> openExr(const std::string& path);

// Throws UsageError naming `path` when it does not start with the OpenEXR magic number, or an
// attribute of one of its headers (every part's, for a multi-part file) declares a negative
// size or more bytes than the file has left.
void checkExrHeaders(const std::string& path);

}  // namespace glint
