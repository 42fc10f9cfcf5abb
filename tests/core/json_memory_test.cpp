#include "core/json_memory.h"

#include <gtest/gtest.h>
#include <malloc.h>

#include <nlohmann/json.hpp>
#include <string>

#include "test_util.h"

namespace glint {
namespace {

TEST(JsonMemory, CountsValuesOutsideStringsAndComments) {
  EXPECT_EQ(measureJsonTree("[{}, {}, []]").values, 4u);
  // Keys are not values; brackets, quotes and digits inside strings are not tokens.
  EXPECT_EQ(
      measureJsonTree(R"({"a [1, 2]": 1, "b": "{\"[3]\"", "c": [true, null, -1.5e3]})").values, 7u);
  // Comments (the scene reader allows them) hold no values.
  EXPECT_EQ(measureJsonTree("// [[[ \"\n[1, /* {{ \" 2 */ 3]").values, 3u);
  // A text cut inside a string still ends.
  EXPECT_EQ(measureJsonTree("[\"abc\\").values, 2u);
  // Line ends, for the scene's line map: CR and LF each, in comments too.
  EXPECT_EQ(measureJsonTree("[1,\r\n2 /* a\nb */]\n").lineEnds, 4u);
}

// The bytes glibc's allocator holds: in use on its heap, and mapped for large blocks (a long
// array's buffer).
size_t allocatedBytes() {
  const struct mallinfo2 info = mallinfo2();
  return info.uordblks + info.hblkhd;
}

// The bytes nlohmann-json's tree of `text` holds once parsed.
double treeBytes(const std::string& text) {
  const size_t before = allocatedBytes();
  const nlohmann::json tree = nlohmann::json::parse(text);
  return double(allocatedBytes() - before);
}

TEST(JsonMemory, TheCountBoundsWhatNlohmannJsonTakes) {
  if (test::kAddressSanitizer)
    GTEST_SKIP() << "AddressSanitizer's allocator does not report through mallinfo2";
  // Each shape's tree, 100000 values of one kind, measured by the allocator once parsed: the
  // count must not be below it (the check would pass a tree that does not fit), nor more than
  // three times it (it takes each value at 48 bytes, its vector's old and new buffers as it
  // grows, where a parsed vector holds 16 to 32 a value).
  const auto repeated = [](const std::string& element, bool keyed) {
    std::string text = keyed ? "{" : "[";
    for (int i = 0; i < 100000; ++i) {
      if (i) text += ",";
      if (keyed) text += "\"key " + std::to_string(i) + "\": ";
      text += element;
    }
    return text + (keyed ? "}" : "]");
  };
  for (const std::string& text :
       {repeated("0", false), repeated("[]", false), repeated("{}", false), repeated("\"\"", false),
        repeated("\"a string longer than fifteen characters\"", false), repeated("1.5", true),
        repeated("{}", true), repeated("[0.25, 0.5, 0.75]", false)}) {
    const double measured = treeBytes(text), counted = measureJsonTree(text).bytes;
    EXPECT_GE(counted, measured) << text.substr(0, 40);
    EXPECT_LE(counted, 3 * measured) << text.substr(0, 40);
  }
}

}  // namespace
}  // namespace glint
