// Materials of mesh files mapped onto Glint's surface model (io/mesh_materials.h; the table in
// docs/scene-format.md): each material group of a file becomes its own part with its own
// material, and a scene's "material" overrides them all.
#include <assimp/material.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "io/mesh_io.h"
#include "io/mesh_materials.h"
#include "io/texture_file.h"
#include "test_util.h"

namespace glint {
namespace {

const Material& named(const MeshFile& f, const std::string& name) {
  for (const Material& m : f.materials)
    if (m.name == name) return m;
  ADD_FAILURE() << "no material " << name;
  static const Material none;
  return none;
}

Rgb uniform(const ColorTexture& t) { return t.constant; }

// Two triangles in each of four groups: a diffuse red, a green with a highlight, a mirror
// (illum 3: Ks is the reflection colour) and a glass (illum 7, Ni 1.33).
const char* kMtl = R"(newmtl red
Kd 0.8 0.1 0.1
Ka 0.2 0 0
Ks 0 0 0
newmtl green
Kd 0.1 0.7 0.2
Ks 0.5 0.5 0.5
Ns 64
Ke 0.1 0.2 0.3
newmtl chrome
Kd 0 0 0
Ks 0.9 0.8 0.7
illum 3
newmtl water
Kd 0.5 0.5 0.5
Ks 1 1 1
Ni 1.33
illum 7
)";

std::string objWithGroups() {
  std::string obj = "mtllib groups.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\n";
  for (const char* m : {"red", "green", "chrome", "water"})
    obj += std::string("usemtl ") + m + "\nf 1 2 3\nf 2 4 3\n";
  return obj;
}

TEST(MeshMaterials, AnObjKeepsOnePartAndOneMaterialPerUsemtlGroup) {
  test::writeTemp("groups.mtl", kMtl);
  const MeshFile f = loadMeshFile(test::writeTemp("groups.obj", objWithGroups()));
  ASSERT_EQ(f.parts.size(), 4u);
  ASSERT_EQ(f.materials.size(), 4u);
  for (const TriangleMesh& part : f.parts) EXPECT_EQ(part.triangleCount(), 2u);

  const Material& red = named(f, "groups.obj:red");
  EXPECT_EQ(red.kind, MaterialKind::Phong);
  EXPECT_FLOAT_EQ(uniform(red.surface.kd).r, 0.8f);  // Kd
  EXPECT_FLOAT_EQ(uniform(red.surface.ka).r, 0.2f);  // Ka, not the diffuse colour
  EXPECT_FALSE(red.surface.ambientFollowsDiffuse);
  EXPECT_TRUE(red.surface.km.isBlack());

  const Material& green = named(f, "groups.obj:green");
  EXPECT_FLOAT_EQ(uniform(green.surface.ks).g, 0.5f);  // Ks
  EXPECT_FLOAT_EQ(green.surface.exponent, 64.0f);      // Ns
  EXPECT_FLOAT_EQ(uniform(green.surface.ke).b, 0.3f);  // Ke

  const Material& chrome = named(f, "groups.obj:chrome");
  EXPECT_EQ(chrome.kind, MaterialKind::Phong);
  EXPECT_FLOAT_EQ(uniform(chrome.surface.km).r, 0.9f);  // illum 3: reflection colour Ks
  EXPECT_FLOAT_EQ(uniform(chrome.surface.km).b, 0.7f);

  const Material& water = named(f, "groups.obj:water");
  EXPECT_EQ(water.kind, MaterialKind::Dielectric);  // illum 7: refraction with Fresnel
  EXPECT_FLOAT_EQ(water.dielectric.ior, 1.33f);     // Ni
  EXPECT_TRUE(water.surface.kd.isBlack());          // glass has no diffuse colour
}

TEST(MeshMaterials, AnMtllibLineNamingSeveralLibrariesReadsEachOfThem) {
  // The OBJ format lets one mtllib line list several libraries; Assimp opened "a.mtl b.mtl" as
  // one file name and every face took its default grey. A library whose own name holds a space
  // is still read by that name.
  test::writeTemp("first.mtl", "newmtl red\nKd 1 0 0\n");
  test::writeTemp("second.mtl", "newmtl blue\nKd 0 0 1\n");
  test::writeTemp("third lib.mtl", "newmtl green\nKd 0 1 0\n");
  const std::string obj = test::writeTemp(
      "libraries.obj",
      "mtllib first.mtl second.mtl\nmtllib third lib.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\n"
      "usemtl red\nf 1 2 3\nusemtl blue\nf 1 3 2\nusemtl green\nf 2 1 3\n");
  testing::internal::CaptureStderr();
  const MeshFile f = loadMeshFile(obj);
  const std::string warnings = testing::internal::GetCapturedStderr();
  EXPECT_EQ(warnings, "");
  EXPECT_FLOAT_EQ(uniform(named(f, "libraries.obj:red").surface.kd).r, 1.0f);
  EXPECT_FLOAT_EQ(uniform(named(f, "libraries.obj:blue").surface.kd).b, 1.0f);
  EXPECT_FLOAT_EQ(uniform(named(f, "libraries.obj:blue").surface.kd).r, 0.0f);
  EXPECT_FLOAT_EQ(uniform(named(f, "libraries.obj:green").surface.kd).g, 1.0f);
}

TEST(MeshMaterials, ARealObjWithUsemtlKeepsItsMaterials) {
  // assimp-testmodels' cube_usemtl.obj: 12 triangles in groups of mtl (Ns 200, Ks 0.05),
  // mtl2 (Ns 16, Ks 0.375) and mtl3, which its MTL does not define.
  const std::string path = "/usr/share/assimp/models/OBJ/cube_usemtl.obj";
  if (!std::filesystem::exists(path)) GTEST_SKIP() << "assimp-testmodels is not installed";
  const MeshFile f = loadMeshFile(path);
  size_t triangles = 0;
  for (const TriangleMesh& part : f.parts) triangles += part.triangleCount();
  EXPECT_EQ(triangles, 12u);
  EXPECT_GE(f.parts.size(), 2u);
  EXPECT_FLOAT_EQ(named(f, "cube_usemtl.obj:mtl").surface.exponent, 200.0f);
  EXPECT_FLOAT_EQ(uniform(named(f, "cube_usemtl.obj:mtl").surface.ks).r, 0.05f);
  EXPECT_FLOAT_EQ(named(f, "cube_usemtl.obj:mtl2").surface.exponent, 16.0f);
  EXPECT_FLOAT_EQ(uniform(named(f, "cube_usemtl.obj:mtl2").surface.ks).r, 0.375f);
}

// A glTF of one triangle per material, its buffer embedded (3 positions, 3 indices).
std::string gltfWithMaterials(const std::string& materials, int count) {
  // Positions (0,0,0) (1,0,0) (0,1,0) as float32, then indices 0 1 2 as uint16 + 2 bytes pad.
  const std::string buffer = "AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAAAAABAAIAAAA=";
  std::string meshes, nodes;
  for (int i = 0; i < count; ++i) {
    meshes += std::string(i ? "," : "") + R"({"primitives": [{"attributes": {"POSITION": 0},
      "indices": 1, "material": )" +
              std::to_string(i) + "}]}";
    nodes += std::string(i ? "," : "") + R"({"mesh": )" + std::to_string(i) +
             R"(, "translation": [)" + std::to_string(2 * i) + ", 0, 0]}";
  }
  std::string sceneNodes;
  for (int i = 0; i < count; ++i) sceneNodes += std::string(i ? "," : "") + std::to_string(i);
  return R"({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [)" + sceneNodes +
         R"(]}], "nodes": [)" + nodes + R"(], "meshes": [)" + meshes + R"(],
    "materials": [)" +
         materials + R"(],
    "extensionsUsed": ["KHR_materials_transmission", "KHR_materials_ior", "KHR_materials_volume"],
    "accessors": [
      {"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
       "min": [0,0,0], "max": [1,1,0]},
      {"bufferView": 1, "componentType": 5123, "count": 3, "type": "SCALAR"}],
    "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 36},
                    {"buffer": 0, "byteOffset": 36, "byteLength": 6}],
    "buffers": [{"byteLength": 44, "uri": "data:application/octet-stream;base64,)" +
         buffer + R"("}]})";
}

TEST(MeshMaterials, GltfMetallicRoughnessAndTransmissionWithVolumeMapOntoTheSurface) {
  const MeshFile f = loadMeshFile(test::writeTemp("materials.gltf", gltfWithMaterials(R"(
    {"name": "paint", "pbrMetallicRoughness": {"baseColorFactor": [0.8, 0.2, 0.1, 1],
      "metallicFactor": 0, "roughnessFactor": 0.5}, "emissiveFactor": [0.5, 0.25, 0]},
    {"name": "gold", "pbrMetallicRoughness": {"baseColorFactor": [1, 0.8, 0.3, 1],
      "metallicFactor": 1, "roughnessFactor": 0}},
    {"name": "tinted", "extensions": {
      "KHR_materials_transmission": {"transmissionFactor": 1},
      "KHR_materials_ior": {"ior": 1.45},
      "KHR_materials_volume": {"attenuationColor": [0.25, 0.5, 1], "attenuationDistance": 2}}})",
                                                                                      3)));
  ASSERT_EQ(f.parts.size(), 3u);
  const Material& paint = named(f, "materials.gltf:paint");
  EXPECT_EQ(paint.kind, MaterialKind::Phong);
  EXPECT_FLOAT_EQ(uniform(paint.surface.kd).r, 0.8f);  // base × (1 − metallic)
  EXPECT_TRUE(paint.surface.km.isBlack());
  EXPECT_FLOAT_EQ(uniform(paint.surface.ks).r, 0.04f);  // a dielectric's 4 %
  // α = roughness² = 0.25: Blinn-Phong exponent 2/α² − 2 = 30.
  EXPECT_FLOAT_EQ(paint.surface.exponent, 30.0f);
  EXPECT_FLOAT_EQ(uniform(paint.surface.ke).g, 0.25f);

  const Material& gold = named(f, "materials.gltf:gold");
  EXPECT_TRUE(gold.surface.kd.isBlack());             // a metal has no diffuse part
  EXPECT_FLOAT_EQ(uniform(gold.surface.km).g, 0.8f);  // it mirrors its base colour
  EXPECT_FLOAT_EQ(gold.surface.gloss, 0.0f);          // roughness 0: a sharp mirror

  const Material& tinted = named(f, "materials.gltf:tinted");
  EXPECT_EQ(tinted.kind, MaterialKind::Dielectric);
  EXPECT_FLOAT_EQ(tinted.dielectric.ior, 1.45f);
  // KHR_materials_volume: attenuationColor c after attenuationDistance D leaves c^(1/D) per
  // unit distance (Beer): 0.25^(1/2) = 0.5, 0.5^(1/2) = 0.7071, 1.
  const Rgb perUnit = tinted.dielectric.absorption.transmittance(1.0f);
  EXPECT_NEAR(perUnit.r, 0.5f, 1e-6f);
  EXPECT_NEAR(perUnit.g, 0.70710678f, 1e-6f);
  EXPECT_NEAR(perUnit.b, 1.0f, 1e-6f);
}

TEST(MeshMaterials, AValueGlintCannotUseAsWrittenIsNamedWithWhatIsUsedInstead) {
  // Once Kd inf, Kd -1 and metallicFactor 5 became grey, black and 1 without a word. Each
  // replacement is a warning naming the material, the value and what is used; a value the
  // format's own convention raises (Ns 0 to Glint's least exponent, 1) is not.
  test::writeTemp("odd.mtl", R"(newmtl hot
Kd inf 1 1
Ns 0
newmtl dark
Kd 0.5 -1 0.25
Ns -3
newmtl glass
Ni 0.5
illum 7
)");
  std::string obj = "mtllib odd.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\n";
  for (const char* m : {"hot", "dark", "glass"}) obj += std::string("usemtl ") + m + "\nf 1 2 3\n";
  testing::internal::CaptureStderr();
  const MeshFile f = loadMeshFile(test::writeTemp("odd.obj", obj));
  std::string warnings = testing::internal::GetCapturedStderr();
  EXPECT_EQ(uniform(named(f, "odd.obj:hot").surface.kd), (Rgb{0.5f, 0.5f, 0.5f}));
  EXPECT_EQ(named(f, "odd.obj:hot").surface.exponent, 1.0f);
  EXPECT_EQ(uniform(named(f, "odd.obj:dark").surface.kd), (Rgb{0.5f, 0, 0.25f}));
  EXPECT_EQ(named(f, "odd.obj:dark").surface.exponent, 1.0f);
  EXPECT_EQ(named(f, "odd.obj:glass").dielectric.ior, 1.5f);
  for (const char* expected :
       {"material odd.obj:hot: diffuse colour (Kd) (inf, 1, 1) is not finite: (0.5, 0.5, 0.5) "
        "is used",
        "material odd.obj:dark: diffuse colour (Kd) (0.5, -1, 0.25) has a negative channel: "
        "(0.5, 0, 0.25) is used",
        "material odd.obj:dark: shininess (Ns) -3 is outside [1, 10000]: 1 is used",
        "material odd.obj:glass: index of refraction (Ni) 0.5 is outside [1, 10]: 1.5 is used"})
    EXPECT_NE(warnings.find(expected), std::string::npos) << expected << "\n" << warnings;
  EXPECT_EQ(warnings.find("odd.obj:hot: shininess"), std::string::npos) << warnings;

  testing::internal::CaptureStderr();
  const MeshFile g = loadMeshFile(test::writeTemp("odd.gltf", gltfWithMaterials(R"(
    {"name": "odd", "pbrMetallicRoughness": {"metallicFactor": 5, "roughnessFactor": -3}})",
                                                                                1)));
  warnings = testing::internal::GetCapturedStderr();
  EXPECT_EQ(named(g, "odd.gltf:odd").surface.gloss, 0.0f);  // metallic 1, roughness 0
  EXPECT_NE(warnings.find("material odd.gltf:odd: metallicFactor 5 is outside [0, 1]: 1 is used"),
            std::string::npos)
      << warnings;
  EXPECT_NE(warnings.find("material odd.gltf:odd: roughnessFactor -3 is outside [0, 1]: 0 is used"),
            std::string::npos)
      << warnings;
}

TEST(MeshMaterials, ASceneMaterialOverridesTheFilesAndWithoutOneTheFileKeepsItsOwn) {
  test::writeTemp("groups.mtl", kMtl);
  test::writeTemp("groups.obj", objWithGroups());
  const auto load = [](const std::string& material) {
    return loadSceneText(R"({"render": {"width": 8, "height": 8},
      "camera": {"eye": [0,0,5], "look_at": [0,0,0]},
      "materials": {"grey": {"type": "phong"}}, "lights": [],
      "objects": [{"type": "mesh", "file": "groups.obj")" +
                             material + "}]}",
                         "scene.json", test::tempDir().string());
  };
  const Scene own = load("");
  ASSERT_EQ(own.groups[0].geometries.size(), 4u);  // one geometry per material group
  std::vector<std::string> names;
  for (const Geometry& g : own.groups[0].geometries) {
    names.push_back(own.materials[g.materialId].name);
    EXPECT_EQ(g.objectId, 0u);  // still the one object of the scene file
  }
  EXPECT_EQ(names, (std::vector<std::string>{"groups.obj:red", "groups.obj:green",
                                             "groups.obj:chrome", "groups.obj:water"}));
  // The file's glass makes the scene need refraction.
  const std::vector<std::string> used = own.features.used();
  EXPECT_NE(std::find(used.begin(), used.end(), "refraction"), used.end());

  const Scene overridden = load(R"(, "material": "grey")");
  ASSERT_EQ(overridden.groups[0].geometries.size(), 4u);
  for (const Geometry& g : overridden.groups[0].geometries)
    EXPECT_EQ(overridden.materials[g.materialId].name, "grey");
}

TEST(MeshMaterials, OtherFormatsLetTheDiffuseTextureReplaceTheColour) {
  // An FBX or 3DS material keeps the grey its tool showed beside its texture; an MTL's map_Kd
  // multiplies Kd (the OBJ specification). The same Assimp material, read as each.
  aiMaterial src;
  const aiColor3D grey(0.6f, 0.6f, 0.6f);
  src.AddProperty(&grey, 1, AI_MATKEY_COLOR_DIFFUSE);
  const aiString name("wood"), texture("half_matte.png");
  src.AddProperty(&name, AI_MATKEY_NAME);
  src.AddProperty(&texture, AI_MATKEY_TEXTURE_DIFFUSE(0));
  const std::string png = test::writeHalfMatte();
  const TextureOpener open = [&](const std::string&) { return openImageTexture(png); };
  const Material other = materialFromMeshFile(src, MeshFileFormat::Other, "box.fbx", open);
  EXPECT_EQ(other.name, "box.fbx:wood");
  EXPECT_EQ(other.surface.kd.pattern, TexturePattern::Image);
  EXPECT_EQ(uniform(other.surface.kd).r, 1.0f);
  const Material mtl = materialFromMeshFile(src, MeshFileFormat::Obj, "box.obj", open);
  EXPECT_EQ(mtl.surface.kd.pattern, TexturePattern::Image);
  EXPECT_FLOAT_EQ(uniform(mtl.surface.kd).r, 0.6f);
}

TEST(MeshMaterials, TheSpecularStrengthScalesTheHighlightsColour) {
  // Blender writes a matte material to FBX as SpecularColor 0.8 with SpecularFactor 0 (Assimp's
  // shininess strength): read without the factor, a matte sphere took a white sheen of 0.8.
  const auto ks = [](const float* strength) {
    aiMaterial src;
    const aiColor3D specular(0.8f, 0.8f, 0.8f);
    src.AddProperty(&specular, 1, AI_MATKEY_COLOR_SPECULAR);
    if (strength) src.AddProperty(strength, 1, AI_MATKEY_SHININESS_STRENGTH);
    const TextureOpener none = [](const std::string&) { return nullptr; };
    return uniform(materialFromMeshFile(src, MeshFileFormat::Other, "ball.fbx", none).surface.ks);
  };
  const float zero = 0, half = 0.5f;
  EXPECT_EQ(ks(&zero).r, 0.0f);
  EXPECT_FLOAT_EQ(ks(&half).g, 0.4f);
  EXPECT_FLOAT_EQ(ks(nullptr).b, 0.8f);  // absent (an MTL): the colour as given
}

TEST(MeshMaterials, ATexturePathOfAnotherMachineFindsTheImageBesideTheMesh) {
  // Exporters write the path the texture had where the file was made (assimp-testmodels'
  // spider.fbx: "D:\\projects\\...\\drkwood2.jpg"); the image of that name beside the mesh is used.
  const std::string png = test::writeHalfMatte();
  const std::string dir = std::filesystem::path(png).parent_path().string();
  test::writeTemp("elsewhere.mtl", "newmtl m\nKd 1 1 1\nmap_Kd D:\\art\\half_matte.png\n");
  const MeshFile f = loadMeshFile(test::writeTemp(
      "elsewhere.obj", "mtllib elsewhere.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl m\nf 1 2 3\n"));
  ASSERT_EQ(f.materials.size(), 1u);
  EXPECT_EQ(f.materials[0].surface.kd.pattern, TexturePattern::Image) << dir;
}

TEST(MeshMaterials, AnFbxsEmbeddedImagesAreReadFromTheFile) {
  // FBX files carry their images (a Video's Content) under the name of the file each was; Assimp
  // keeps them as embedded textures named so. Before this, Glint looked for those names on disk
  // and left the textures out ("texture not found"). The file's own image is taken even where a
  // file of that name lies beside the mesh, as Blender takes an FBX's packed images.
  const std::filesystem::path models = "/usr/share/assimp/models/FBX";
  if (!std::filesystem::is_directory(models / "embedded_ascii"))
    GTEST_SKIP() << "assimp-testmodels is not installed (" << models
                 << " is missing); tools/lib.sh installs it";
  const std::string beside = test::writeHalfMatte();
  const std::filesystem::path dir = std::filesystem::path(beside).parent_path();
  std::filesystem::copy_file(models / "embedded_ascii/box_embedded_texture_fragmented.fbx",
                             dir / "fragmented.fbx",
                             std::filesystem::copy_options::overwrite_existing);
  std::filesystem::copy_file(beside, dir / "paper.png",
                             std::filesystem::copy_options::overwrite_existing);
  // Which image each names: an ASCII FBX's PNG in one Content string and in fragments, and a
  // binary FBX's TGA, whose names point at files that are not there ("../../Desktop/...").
  for (const std::filesystem::path& mesh :
       {models / "embedded_ascii/box.FBX", dir / "fragmented.fbx",
        models / "box_orphant_embedded_texture.fbx"}) {
    SCOPED_TRACE(mesh.string());
    const MeshFile f = loadMeshFile(mesh.string());
    const auto textured = std::find_if(f.materials.begin(), f.materials.end(),
                                       [](const Material& m) { return m.surface.kd.image; });
    ASSERT_NE(textured, f.materials.end());
    EXPECT_NE(textured->surface.kd.image->path().find(mesh.string() + "#"), std::string::npos)
        << textured->surface.kd.image->path();
  }
}

}  // namespace
}  // namespace glint
