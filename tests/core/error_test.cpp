#include "core/error.h"

#include <gtest/gtest.h>

#include <string>

namespace glint {
namespace {

TEST(Utf8, SequencesMustBeWhole) {
  EXPECT_TRUE(isUtf8("abc é € 𝄞"));
  EXPECT_FALSE(isUtf8("caf\xe9"));               // Latin-1 é: a lead byte without its continuation
  EXPECT_FALSE(isUtf8("\xa9"));                  // a continuation byte alone
  EXPECT_FALSE(isUtf8("\xe2\x82"));              // € cut short
  EXPECT_FALSE(isUtf8("\xf8\x88\x80\x80\x80"));  // no lead byte announces five
}

TEST(Excerpt, ShortTextIsKeptWhole) {
  // 200 bytes is the bound: up to it nothing is cut.
  const std::string text(200, 'a');
  EXPECT_EQ(excerpt(text), text);
  EXPECT_EQ(inQuotes("abc"), "\"abc\"");
}

TEST(Excerpt, ALongLibraryMessageKeepsItsReason) {
  // OpenColorIO names the file first and says what was wrong last; a long path used to push
  // the reason past the cut.
  const std::string path = "/luts/" + std::string(300, 'p') + ".spi1d";
  const std::string message =
      "Error parsing .spi1d file (" + path + "). Invalid 'Length' tag: Length 2000000000";
  const std::string shown = excerpt(message);
  EXPECT_EQ(shown.rfind("Error parsing .spi1d file (/luts/ppp", 0), 0u) << shown;
  const std::string reason = "Length 2000000000";
  ASSERT_GE(shown.size(), reason.size());
  EXPECT_EQ(shown.substr(shown.size() - reason.size()), reason) << shown;
  EXPECT_NE(shown.find("… (" + std::to_string(message.size()) + " characters) …"),
            std::string::npos)
      << shown;
  // 150 + 50 bytes of the text, and the marker.
  EXPECT_LT(shown.size(), 250u);
}

TEST(Excerpt, CutsFallBetweenCharacters) {
  // 'é' is two bytes: after one ASCII byte, byte 150 and byte size − 50 are each the second byte
  // of an 'é'.
  std::string text = "x";
  for (int i = 0; i < 400; ++i) text += "é";
  text += "y";
  ASSERT_TRUE(isUtf8(text));
  const std::string shown = excerpt(text);
  EXPECT_TRUE(isUtf8(shown)) << shown;
  EXPECT_LT(shown.size(), text.size());
}

}  // namespace
}  // namespace glint
