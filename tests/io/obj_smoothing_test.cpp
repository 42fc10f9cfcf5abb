#include "io/obj_smoothing.h"

#include <gtest/gtest.h>

#include <optional>
#include <string>

namespace glint {
namespace {

// Two triangles folded at a right angle along the edge from (0, 0, 0) to (1, 0, 0): the first
// faces +z, the second +y, each of area 1/2.
const char* kFold = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\n";

std::optional<std::string> smoothed(const std::string& text) {
  return objWithSmoothingGroupNormals(text, "fold.obj");
}

TEST(ObjSmoothing, AFileThatGivesNormalsOrNoGroupsIsLeftAsItIs) {
  EXPECT_FALSE(smoothed(std::string(kFold) + "s 1\nf 1 2 3\nf 2 1 4\n"
                                             "vn 0 0 1\n"));
  EXPECT_FALSE(smoothed(std::string(kFold) + "f 1 2 3\ns off\nf 2 1 4\n"));
  EXPECT_FALSE(smoothed(std::string(kFold) + "s 0\nf 1 2 3\nf 2 1 4\n"));
  // A face naming a vertex that is not there is Assimp's to refuse, naming it.
  EXPECT_FALSE(smoothed(std::string(kFold) + "s 1\nf 1 2 9\n"));
  EXPECT_FALSE(smoothed(std::string(kFold) + "s 1\nf 1 2 -5\n"));
}

TEST(ObjSmoothing, OneGroupAveragesItsFacesAtTheirSharedVertices) {
  // The fold's shared vertices 1 and 2 take (0, 0, 1) + (0, 1, 0), normalised; vertices 3 and
  // 4 their one face's. The groups' normals come first (in the order their corners are met),
  // then the own normals of the faces that take them: here none.
  const auto out = smoothed(std::string(kFold) + "s 1\nf 1 2 3\nf 2 1 4\n");
  ASSERT_TRUE(out);
  EXPECT_EQ(*out,
            "vn 0 0.707106781 0.707106781\nvn 0 0.707106781 0.707106781\nvn 0 0 1\nvn 0 1 0\n" +
                std::string(kFold) + "s 1\nf 1//1 2//2 3//3\nf 2//2 1//1 4//4\n");
}

TEST(ObjSmoothing, DifferentGroupsMeetAtAHardEdgeAndUngroupedFacesAreFlat) {
  // Groups 1 and 2: each face keeps its own normal at the shared vertices too.
  const auto apart = smoothed(std::string(kFold) + "s 1\nf 1 2 3\ns 2\nf 2 1 4\n");
  ASSERT_TRUE(apart);
  EXPECT_NE(apart->find("f 1//1 2//2 3//3\ns 2\nf 2//4 1//5 4//6\n"), std::string::npos) << *apart;
  EXPECT_EQ(apart->rfind("vn 0 0 1\nvn 0 0 1\nvn 0 0 1\nvn 0 1 0\nvn 0 1 0\nvn 0 1 0\n", 0), 0u)
      << *apart;
  // The first face in no group: its own normal (the 4th vn, after group 1's three) at every
  // corner.
  const auto flat = smoothed(std::string(kFold) + "s off\nf 1 2 3\ns 1\nf 2 1 4\n");
  ASSERT_TRUE(flat);
  EXPECT_NE(flat->find("s off\nf 1//4 2//4 3//4\ns 1\nf 2//1 1//2 4//3\n"), std::string::npos)
      << *flat;
}

TEST(ObjSmoothing, TextureCoordinatesAndRelativeIndicesAreKept) {
  // Counting back from its line (-4: vertex 1), with texture coordinates: each corner keeps its
  // vt and gains its normal. A CR LF line end and a line Assimp skips (a blank first) are kept.
  const auto out = smoothed(std::string(kFold) +
                            "vt 0 0\nvt 1 0\nvt 0 1\ns 1\r\nf -4/1 -3/2 -2/3\n f 9 9 9\n"
                            "f 2/2 1/1 4/3\n");
  ASSERT_TRUE(out);
  EXPECT_NE(out->find("s 1\nf -4/1/1 -3/2/2 -2/3/3\n f 9 9 9\nf 2/2/2 1/1/1 4/3/4\n"),
            std::string::npos)
      << *out;
}

TEST(ObjSmoothing, WhatAssimpWouldReadOtherwiseIsLeftAsItIs) {
  // Each of these would read differently once rewritten: a continued line (Assimp joins it
  // without a space), a face with a comment (Assimp 5.2.5 refuses it), an index Assimp splits
  // ("01" is 0 and 1), a texture index before any vt line (with vn lines first, Assimp takes it
  // for the normal's), a cstype block (whose lines Assimp skips), a byte-order mark.
  const std::string fold = kFold;
  for (const std::string& text :
       {fold + "s 1\nf 1 2 \\\n3\n", fold + "s 1\nf 1 2 3 # roof\n", fold + "s 1\nf 01 2 3\n",
        fold + "s 1\nf 1/1 2/2 3/3\nvt 0 0\nvt 1 0\nvt 0 1\n",
        fold + "s 1\nf 1 2 3\ncstype bspline\nend\n", "\xEF\xBB\xBF" + fold + "s 1\nf 1 2 3\n"})
    EXPECT_FALSE(smoothed(text)) << text;
  // The same faces without those are rewritten.
  EXPECT_TRUE(smoothed(fold + "s 1\nf 1 2 3\n"));
}

TEST(ObjSmoothing, WhereAGroupsNormalsCancelItsFacesKeepTheirOwn) {
  // Two faces on one triangle, wound opposite ways, in one group: their normals sum to zero at
  // every vertex, and a zero normal would shade the faces black.
  const auto out = smoothed(std::string(kFold) + "s 1\nf 1 2 3\nf 1 3 2\n");
  ASSERT_TRUE(out);
  EXPECT_NE(out->find("f 1//4 2//4 3//4\nf 1//5 3//5 2//5\n"), std::string::npos) << *out;
  EXPECT_NE(out->find("vn 0 0 1\nvn 0 0 -1\n"), std::string::npos) << *out;
}

}  // namespace
}  // namespace glint
