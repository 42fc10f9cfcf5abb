// What an ASCII FBX file must pass before Assimp's reader sees it (io/fbx_limits.h): embedded
// textures whose base64 Assimp's decoder wrote past its buffer on (a SIGSEGV, or glibc's "double
// free or corruption" abort, from a few changed bytes of assimp-testmodels' embedded_ascii files).
#include "io/fbx_limits.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "core/error.h"
#include "io/mesh_io.h"
#include "test_util.h"

namespace glint {
namespace {

// A Video object of an ASCII FBX file, its Content the given property text.
std::string fbxWithContent(const std::string& content) {
  return "; FBX 7.4.0 project file\nObjects:  {\n\tVideo: 1, \"Video::t\", \"Clip\" {\n"
         "\t\tType: \"Clip\"\n\t\tContent: " +
         content + "\n\t}\n}\n";
}

std::string refusal(const std::string& bytes) {
  try {
    checkFbxEmbeddedContent("m.fbx", bytes);
    return "(accepted)";
  } catch (const GlintError& e) {
    return e.what();
  }
}

TEST(FbxLimits, Base64ContentPassesInOneStringOrSeveral) {
  EXPECT_EQ(refusal(fbxWithContent(",\n \"iVBORw0KGgo=\"")), "(accepted)");
  // Exporters split long content into strings of their own, each padded (Assimp decodes each).
  EXPECT_EQ(refusal(fbxWithContent(",\n \"iVBORw0K\",\n \"R2dvAA==\"")), "(accepted)");
  EXPECT_EQ(refusal(fbxWithContent("\"\"")), "(accepted)");
  // A property named Content inside a string, and a binary file, are not read as one.
  EXPECT_EQ(refusal("; FBX\n\tComment: \"Content: \\\"-\\\"\"\n"), "(accepted)");
  constexpr char kBinary[] = "Kaydara FBX Binary  \0\x1a\0Content: \"-\"";
  EXPECT_EQ(refusal(std::string(kBinary, sizeof kBinary - 1)), "(accepted)");
}

TEST(FbxLimits, ContentThatIsNotBase64IsRefusedNamingTheLineAndTheByte) {
  EXPECT_EQ(refusal(fbxWithContent(",\n \"iVBORw0KGgo-AAAANSUhEUg\"")),
            "mesh m.fbx:6: its embedded texture (Content) is not base64: its string has \"-\" "
            "at character 12, outside base64's alphabet");
  EXPECT_EQ(refusal(fbxWithContent("\"iV==AAAA\"")),
            "mesh m.fbx:5: its embedded texture (Content) is not base64: its string has \"A\" "
            "after its padding '='");
  EXPECT_EQ(refusal(fbxWithContent("\"iVB\x01\"")),
            "mesh m.fbx:5: its embedded texture (Content) is not base64: its string has byte "
            "0x01 at character 4, outside base64's alphabet");
  EXPECT_EQ(refusal(fbxWithContent("\"iVBORw0KGgoA\", \"AAA\"")),
            "mesh m.fbx:5: its embedded texture (Content) is not base64: its string is 3 "
            "characters long, not a multiple of 4");
  EXPECT_EQ(refusal(fbxWithContent("\"A===\"")),
            "mesh m.fbx:5: its embedded texture (Content) is not base64: its string ends in 3 "
            "'=' (base64 pads with 2 at most)");
  EXPECT_EQ(refusal(fbxWithContent("\"iVBO")),
            "mesh m.fbx:5: its embedded texture (Content) has a string that is never closed");
}

TEST(FbxLimits, ContentIsFoundAsAssimpsTokenizerFindsIt) {
  // A review crashed Assimp past an earlier version of the check, which read Content's strings
  // line by line: a comment between the key and its string, the key after other tokens on its
  // line, and a value that is not a quoted string (Assimp strips one byte from each end of it
  // unchecked: one byte long, its length wrapped).
  EXPECT_EQ(refusal(fbxWithContent(",\n; a comment \"\n \"iVBO-w0K\"")),
            "mesh m.fbx:7: its embedded texture (Content) is not base64: its string has \"-\" "
            "at character 5, outside base64's alphabet");
  EXPECT_EQ(refusal("; FBX\nVideo: 1 {\n\tType: \"Clip\" Content: , \"iV*A\"\n}\n"),
            "mesh m.fbx:3: its embedded texture (Content) is not base64: its string has \"*\" "
            "at character 3, outside base64's alphabet");
  EXPECT_EQ(refusal(fbxWithContent("\"iVBORw0K\", x")),
            "mesh m.fbx:5: its embedded texture (Content) is not base64: \"x\" is not a quoted "
            "string");
  // The next key ends the values: a later property's bare values are its own.
  EXPECT_EQ(refusal(fbxWithContent("\"iVBORw0K\"\n\t\tVersion: 202")), "(accepted)");
}

TEST(FbxLimits, TheLoaderRefusesAnEmbeddedTextureAssimpWouldCrashOn) {
  // assimp-testmodels' embedded_ascii/box.FBX with one byte of its texture's base64 changed
  // crashed Glint (SIGSEGV) in render, info and a scene naming it.
  const std::string box = "/usr/share/assimp/models/FBX/embedded_ascii/box.FBX";
  if (!std::filesystem::exists(box))
    GTEST_SKIP() << "assimp-testmodels is not installed (tools/lib.sh installs it)";
  std::string bytes = test::readFile(box);
  const size_t content = bytes.find("\"iVBORw0KGgo", bytes.find("Content:"));
  ASSERT_NE(content, std::string::npos);
  bytes[content + 12] = '-';
  const std::string path = test::writeTemp("damaged-box.fbx", bytes);
  try {
    loadMeshFile(path, /*readTextures=*/false);
    ADD_FAILURE() << "a damaged embedded texture was read";
  } catch (const GlintError& e) {
    EXPECT_NE(std::string(e.what()).find(path + ":445: its embedded texture (Content) is not "
                                                "base64: its string has \"-\" at character 12"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace glint
