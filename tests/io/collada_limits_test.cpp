// What a Collada file must pass before Assimp's reader sees it (io/collada_limits.h): each case
// is a hostile input that made Assimp's reader loop, or reserve memory the file cannot fill.
#include "io/collada_limits.h"

#include <gtest/gtest.h>

#include "collada_util.h"
#include "core/error.h"

namespace glint {
namespace {

std::string refusal(const std::string& bytes) {
  try {
    checkColladaCounts("m.dae", bytes);
    return "(accepted)";
  } catch (const GlintError& e) {
    return e.what();
  }
}

bool has(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

TEST(ColladaLimits, AWellFormedDocumentPasses) {
  EXPECT_EQ(refusal(test::colladaDocument()), "(accepted)");
  // Negative indices are read (Assimp clamps them to 0), as is white space of every kind.
  test::ColladaParts p;
  p.indices = "\n\t0 -1 +2\r\n";
  EXPECT_EQ(refusal(test::colladaDocument(p)), "(accepted)");
}

TEST(ColladaLimits, AnIndexListWithAnyOtherCharacterIsRefused) {
  // One byte of duck.dae's index list turned into 0x80 made Assimp's reader loop forever,
  // appending a 0 to its list each time round (a fuzzed copy of assimp-testmodels' duck.dae).
  test::ColladaParts p;
  p.indices = "0 1 \x80 2";
  const std::string message = refusal(test::colladaDocument(p));
  EXPECT_TRUE(has(message, "m.dae:20: <p> holds byte 0x80")) << message;
  p.indices = "0 1 2.5";
  EXPECT_TRUE(has(refusal(test::colladaDocument(p)), "<p> holds \".\""))
      << refusal(test::colladaDocument(p));
  // Markup inside the list (a comment) hides text from this check: refused too.
  p.indices = "0 1 <!-- x --> 2";
  EXPECT_TRUE(has(refusal(test::colladaDocument(p)), "<p> holds markup"));
}

TEST(ColladaLimits, CountsPastTheFileAreRefused) {
  // <triangles count="N"> makes Assimp reserve 3N indices before reading one.
  test::ColladaParts p;
  p.triangleCount = "4000000000";
  const std::string message = refusal(test::colladaDocument(p));
  EXPECT_TRUE(has(message, "count=\"4000000000\" is more than the file's")) << message;
  p.triangleCount = "-1";
  EXPECT_TRUE(has(refusal(test::colladaDocument(p)), "count=\"-1\" is not a whole number"));
  // The same words inside a comment are not an attribute.
  std::string commented = test::colladaDocument();
  commented.insert(commented.find("<asset>"), "<!-- <triangles count=\"4000000000\"> -->");
  EXPECT_EQ(refusal(commented), "(accepted)");
}

TEST(ColladaLimits, PolygonSizesPastTheFileAreRefused) {
  // A <vcount> of 10^12 vertices for one polygon: more indices than the file holds bytes.
  std::string doc = test::colladaDocument();
  doc.insert(doc.find("<p>"), "<vcount>3 1000000000000</vcount>");
  EXPECT_TRUE(has(refusal(doc), "<vcount> gives polygons of more vertices")) << refusal(doc);
}

}  // namespace
}  // namespace glint
