// Names of objects and lights (docs/scene-format.md, Names): the "name" key and its errors, the
// names mesh files give their triangles (glTF nodes, else meshes; OBJ o and g), what a scene
// makes of them, and the layers of named lights' AOVs.
#include "io/object_names.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>

#include "gltf_util.h"
#include "io/mesh_io.h"
#include "io/scene_loader.h"
#include "render/aov_accumulator.h"
#include "test_util.h"

namespace glint {
namespace {

using json = nlohmann::json;

TEST(ObjectNames, NamesAssimpMakesUpAreNotTheFiles) {
  for (const char* madeUp :
       {"", "<OFFRoot>", "<3DSDummyRoot>", "root_$AssimpFbx$_GeometricScaling",
        "$ColladaAutoName$_3", "nodes[3]", "meshes[0]", "meshes[12]-1", "defaultobject"})
    EXPECT_EQ(fileGivenName(madeUp), "") << madeUp;
  // Names a file gives, including ones that only resemble the made-up ones.
  for (const char* given : {"Wheel", "LOD3sp", "nodes", "nodes[]", "nodes[3]x", "meshes[0]-",
                            "my nodes[3]", "Price <low>x", "Café"})
    EXPECT_EQ(fileGivenName(given), given) << given;
}

// Lines 1 to 3; then "lights" opens line 4, its entries follow, "]," closes it on the next line
// and "objects" opens the line after that.
const char* kHead =
    "{\n\"camera\": {\"eye\": [0,0,5], \"look_at\": [0,0,0]},\n"
    "\"materials\": {\"red\": {\"type\": \"phong\"}},\n";

std::string withObjects(const std::string& lights, const std::string& objects,
                        const std::string& groups = "") {
  return std::string(kHead) + "\"lights\": [\n" + lights + "],\n\"objects\": [\n" + objects + "]" +
         (groups.empty() ? "" : ",\n\"groups\": " + groups) + "}\n";
}

const char* kBall =
    "{\"type\": \"sphere\", \"name\": \"Ball\", \"center\": [0,0,0], \"radius\": 1, "
    "\"material\": \"red\"}";

TEST(ObjectNames, ARepeatedNameNamesWhereItWasFirstGiven) {
  // objects[1] on line 8 repeats the name objects[0] gave on line 7.
  EXPECT_EQ(test::sceneErrorOf(withObjects("", std::string(kBall) + ",\n" + kBall + "\n")),
            "scene.json:8: objects[1].name: \"Ball\" is already the name of objects[0].name "
            "(line 7); names of objects and lights must be unique");
  // Objects and lights share one set of names (a visible light is an object of the frame).
  EXPECT_EQ(test::sceneErrorOf(withObjects(
                "{\"type\": \"point\", \"name\": \"Ball\", \"position\": [0,3,0]}\n", kBall)),
            "scene.json:8: objects[0].name: \"Ball\" is already the name of lights[0].name "
            "(line 5); names of objects and lights must be unique");
}

TEST(ObjectNames, ANameMustBeOneACompositorCanType) {
  const auto errorOf = [](const std::string& name) {
    return test::sceneErrorOf(
        withObjects("", "{\"type\": \"sphere\", \"name\": " + name +
                            ", \"center\": [0,0,0], \"radius\": 1, \"material\": \"red\"}\n"));
  };
  EXPECT_EQ(errorOf("\"\""),
            "scene.json:7: objects[0].name: must not be empty (leave \"name\" "
            "out for the default name)");
  EXPECT_EQ(errorOf("\"a\\tb\""),
            "scene.json:7: objects[0].name: holds a control character; a "
            "name is typed into compositors' matte lists");
  // The default names of unnamed objects and lights: a name like them would take their ids.
  EXPECT_EQ(errorOf("\"objects[1]\""),
            "scene.json:7: objects[0].name: begins with \"objects[\", which names the objects "
            "and lights that have no \"name\"");
  EXPECT_EQ(errorOf("\"lights[0]\""),
            "scene.json:7: objects[0].name: begins with \"lights[\", which names the objects "
            "and lights that have no \"name\"");
  EXPECT_EQ(errorOf("7"), "scene.json:7: objects[0].name: must be a string, got number");
}

TEST(ObjectNames, AGroupsMembersAreNamedByTheirInstance) {
  EXPECT_EQ(test::sceneErrorOf(
                withObjects("", "{\"type\": \"instance\", \"name\": \"Tree\", \"group\": \"g\"}\n",
                            "{\"g\": [\n" + std::string(kBall) + "]}")),
            "scene.json:10: groups.g[0].name: a group's members have no names of their own: each "
            "instance of the group is one object, named by the instance's \"name\"");
  // The instance's name is the object's.
  const Scene s = test::sceneFromText(withObjects(
      "",
      "{\"type\": \"instance\", \"name\": \"Tree\", \"group\": \"g\"},\n"
      "{\"type\": \"instance\", \"group\": \"g\"}\n",
      "{\"g\": [{\"type\": \"sphere\", \"center\": [0,0,0], \"radius\": 1, \"material\": "
      "\"red\"}]}"));
  EXPECT_EQ(s.objectNames, (std::vector<std::string>{"Tree", "objects[1]"}));
}

// Two unit squares named by their nodes, Left at x ∈ [0, 1] and Right at x ∈ [2, 3], of one
// material by default (so the reader merges them into one part); `nodeNames` and `meshNames`
// name nodes and meshes ("" leaves one unnamed).
std::string twoSquaresGltf(const std::vector<std::string>& nodeNames,
                           const std::vector<std::string>& meshNames,
                           const std::vector<int>& materialOf = {0, 0}) {
  json doc =
      json::parse(test::gltfSquares(materialOf, R"([{"name": "paint"}, {"name": "varnish"}])"));
  for (size_t i = 0; i < 2; ++i) {
    if (!nodeNames[i].empty()) doc["nodes"][i]["name"] = nodeNames[i];
    if (!meshNames[i].empty()) doc["meshes"][i]["name"] = meshNames[i];
  }
  doc.erase("textures");
  doc.erase("images");
  return doc.dump();
}

// The name of each triangle of a one-part mesh file, and the smallest x of its corners.
std::vector<std::pair<std::string, float>> triangleNames(const MeshFile& file) {
  std::vector<std::pair<std::string, float>> out;
  EXPECT_EQ(file.parts.size(), 1u);
  const TriangleMesh& m = file.parts[0];
  EXPECT_EQ(m.objectIds.size(), m.triangleCount());
  for (uint32_t t = 0; t < m.triangleCount() && t < m.objectIds.size(); ++t)
    out.emplace_back(file.objectNames.at(m.objectIds[t]),
                     std::min({m.vertex(t, 0).x, m.vertex(t, 1).x, m.vertex(t, 2).x}));
  return out;
}

TEST(ObjectNames, AGltfsTrianglesKeepTheirNodesNames) {
  const std::string named =
      test::writeTemp("named_nodes.gltf", twoSquaresGltf({"Left", "Right"}, {"", ""}));
  // Two triangles per square, each named by the node that placed it: Left's at x = 0, Right's
  // (its node moves it by 2) at x = 2.
  const std::vector<std::pair<std::string, float>> expected = {
      {"Left", 0.f}, {"Left", 0.f}, {"Right", 2.f}, {"Right", 2.f}};
  EXPECT_EQ(triangleNames(loadMeshFile(named, false)), expected);
  // A node without a name takes its mesh's.
  const std::string meshNamed =
      test::writeTemp("named_meshes.gltf", twoSquaresGltf({"Left", ""}, {"", "RightMesh"}));
  EXPECT_EQ(triangleNames(loadMeshFile(meshNamed, false)),
            (std::vector<std::pair<std::string, float>>{
                {"Left", 0.f}, {"Left", 0.f}, {"RightMesh", 2.f}, {"RightMesh", 2.f}}));
  // Neither named: the file names nothing (Assimp's "nodes[0]" and "meshes[0]" are its own).
  const MeshFile unnamed =
      loadMeshFile(test::writeTemp("unnamed.gltf", twoSquaresGltf({"", ""}, {"", ""})), false);
  EXPECT_TRUE(unnamed.objectNames.empty());
  EXPECT_TRUE(unnamed.parts[0].objectIds.empty());
}

TEST(ObjectNames, AnObjsTrianglesKeepTheirObjectAndGroupNames) {
  const std::string obj = test::writeTemp("named.obj",
                                          "o Left\nv 0 0 0\nv 1 0 0\nv 1 1 0\nf 1 2 3\n"
                                          "o Right\nv 2 0 0\nv 3 0 0\nv 3 1 0\nf 4 5 6\n"
                                          "g Back\nf 4 6 5\n");
  EXPECT_EQ(
      triangleNames(loadMeshFile(obj, false)),
      (std::vector<std::pair<std::string, float>>{{"Left", 0.f}, {"Right", 2.f}, {"Back", 2.f}}));
  // Without o or g, Assimp's "defaultobject" is no name of the file's.
  const MeshFile plain =
      loadMeshFile(test::writeTemp("plain.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"), false);
  EXPECT_TRUE(plain.objectNames.empty());
  // A name no scene may give (one of the defaults' shape) is no name either.
  const MeshFile reserved = loadMeshFile(
      test::writeTemp("reserved.obj", "o objects[1]\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"), false);
  EXPECT_TRUE(reserved.objectNames.empty());
}

TEST(ObjectNames, AColladasNodeNamesComeThroughAssimpsNodes) {
  const std::string duck = "/usr/share/assimp/models/Collada/duck.dae";
  if (!std::filesystem::exists(duck)) GTEST_SKIP() << duck << " (assimp-testmodels) is missing";
  // duck.dae's one mesh is placed by the visual scene's node "LOD3sp".
  try {
    const MeshFile file = loadMeshFile(duck, false);
    EXPECT_EQ(file.objectNames, std::vector<std::string>{"LOD3sp"});
  } catch (const GlintError& e) {
    GTEST_SKIP() << "this Glint does not read Collada yet: " << e.what();
  }
}

TEST(ObjectNames, AMeshFilesPartsAreObjectsUnderItsName) {
  test::writeTemp("named_nodes.gltf", twoSquaresGltf({"Left", "Right"}, {"", ""}));
  const std::string text =
      std::string(kHead) +
      "\"objects\": [\n"
      "{\"type\": \"mesh\", \"file\": \"named_nodes.gltf\"},\n"
      "{\"type\": \"mesh\", \"name\": \"Pair\", \"file\": \"named_nodes.gltf\"},\n"
      "{\"type\": \"sphere\", \"center\": [0,5,0], \"radius\": 1, "
      "\"material\": \"red\"}]}";
  const Scene s = loadSceneText(text, "scene.json", test::tempDir().string());
  // An unnamed object's parts keep the file's names; a named one's go under its name. The
  // objects whose every triangle is named show no name of their own, and take no id.
  EXPECT_EQ(s.objectNames,
            (std::vector<std::string>{"Left", "Right", "Pair/Left", "Pair/Right", "objects[2]"}));
  // The second object's triangles, in the file's order.
  const Geometry& second = s.groups[0].geometries[1];
  ASSERT_EQ(second.kind, GeomKind::Mesh);
  EXPECT_EQ(s.meshes[second.index].objectIds, (std::vector<uint32_t>{2, 2, 3, 3}));
  Hit hit;
  hit.geomId = 1;
  hit.primId = 3;
  EXPECT_EQ(s.objectId(hit), 3u);
  hit.geomId = 2;
  hit.primId = 0;
  EXPECT_EQ(s.objectId(hit), 4u);
}

TEST(ObjectNames, AMovingMeshFilesPartsKeepTheirNames) {
  // Of two materials: two parts, each all one node's.
  test::writeTemp("two_parts.gltf", twoSquaresGltf({"Left", "Right"}, {"", ""}, {0, 1}));
  // Moving, the file is placed by an implicit instance of its own; its triangles still say
  // which part they are.
  const std::string text = std::string(kHead) +
                           "\"objects\": [{\"type\": \"mesh\", \"name\": \"Moving\", "
                           "\"file\": \"two_parts.gltf\", \"motion\": {\"transform\": "
                           "[{\"translate\": [0,0,0]}, {\"translate\": [0,1,0]}]}}]}";
  const Scene s = loadSceneText(text, "scene.json", test::tempDir().string());
  EXPECT_EQ(s.objectNames, (std::vector<std::string>{"Moving/Left", "Moving/Right"}));
  ASSERT_EQ(s.groups[0].geometries.size(), 1u);
  ASSERT_EQ(s.groups[0].geometries[0].kind, GeomKind::Instance);
  Hit hit;
  hit.instId = 0;
  hit.geomId = 1;  // the second part: Right's triangles
  hit.primId = 1;
  EXPECT_EQ(s.objectId(hit), 1u);
  hit.geomId = 0;
  EXPECT_EQ(s.objectId(hit), 0u);
}

TEST(ObjectNames, NamedLightsGiveSanitisedUniqueLayers) {
  Scene s;
  s.lights.resize(5, PointLight{});
  s.lightNames = {"Key Light", "Key.Light", "", "Café", std::string(100, 'x')};
  // Every byte but letters, digits, '_' and '-' is '_' (a UTF-8 character once); a layer
  // already taken gets "_K"; an unnamed light is lightK; a long name is cut at 64 bytes.
  EXPECT_EQ(lightLayerNames(s),
            (std::vector<std::string>{"light_Key_Light", "light_Key_Light_1", "light2",
                                      "light_Caf_", "light_" + std::string(58, 'x')}));
  EXPECT_EQ(s.lightName(2), "lights[2]");
  EXPECT_EQ(s.lightName(1), "Key.Light");
}

}  // namespace
}  // namespace glint
