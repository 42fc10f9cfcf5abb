#pragma once
// What nlohmann-json's tree of a text will take, counted from the text's tokens without parsing
// it: checked against the memory budget before parsing any JSON a user or a file hands Glint
// (JSON scenes, glTF, render records), since nlohmann-json cannot unwind from a failed
// allocation (its destructor allocates: std::terminate). Bytes of text are no measure: an empty
// object `{},` is 3 bytes and about 85 in the tree, a mesh's number `0.125,` 6 bytes and 21.
#include <cstdint>
#include <string>
#include <string_view>

namespace glint {

struct JsonTreeSize {
  uint64_t values = 0;    // scalars, strings, arrays and objects (object keys not counted)
  uint64_t lineEnds = 0;  // '\n' and '\r' bytes, wherever they are
  // The most the parse holds at once: the tree's allocations (glibc's headers and vectors' spare
  // room included) and the parser's copies of the longest string.
  double bytes = 0;
};

// Counts the tokens of `text` outside strings and comments (// and /* */, as the scene reader
// allows). Malformed JSON gives some count; the parser refuses it afterwards.
JsonTreeSize measureJsonTree(std::string_view text);

// Throws OutOfMemoryError ("out of memory: parsing WHAT (N bytes) needs ...") when the parse of
// `text`, plus what the caller keeps beside the tree (`bytesPerValue` for each value,
// `bytesPerLine` for each line end), does not fit the memory budget. Texts under 1 MiB are not
// checked: the budget is read from several files, which would cost the fuzzers more than the
// parse.
void checkJsonTreeFits(std::string_view text, double bytesPerValue, double bytesPerLine,
                       const std::string& what);

}  // namespace glint
