#pragma once
// A Photoshop file's sections, checked against the file's size before OpenImageIO reads it:
// its PSD reader allocates what a section's length field claims, so 66 bytes claiming 4 GiB of
// colour mode data took 4.3 GB and 13 s before it failed.
#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>

namespace glint {

// Reads `bytes` bytes at `offset` of a file into `out`; false where they are not all there.
using ReadAt = std::function<bool(uint64_t offset, char* out, size_t bytes)>;

// Where the file of `size` bytes that `read` reads is a PSD or PSB file whose colour mode data,
// image resources or layer and mask sections claim more bytes than the file holds past their
// length fields: why ("its image resources claims N bytes, but M remain"). Empty for a file
// whose sections fit, and for any other format.
std::string psdSectionsPastTheEnd(const ReadAt& read, uint64_t size);

}  // namespace glint
