#pragma once
// A small Collada 1.4.1 document for tests of Glint's reading of Collada (io/mesh_io.h): one
// triangle with a red Lambert material, a perspective camera and a directional light, with the
// asset's unit and up axis and the parts that tests vary given.
#include <string>

namespace glint::test {

struct ColladaParts {
  std::string unitMeters = "1";
  std::string upAxis = "Y_UP";
  std::string positions = "0 0 0  1 0 0  0 1 0";  // the triangle's three vertices
  std::string indices = "0 1 2";                  // its <p>
  std::string triangleCount = "1";
  std::string camera = "<translate>0 0 5</translate>";  // the camera node's transform
  std::string light = "<rotate>1 0 0 -90</rotate>";     // the light node's transform
};

inline std::string colladaDocument(const ColladaParts& p = {}) {
  return R"(<?xml version="1.0" encoding="utf-8"?>
<COLLADA xmlns="http://www.collada.org/2005/11/COLLADASchema" version="1.4.1">
  <asset><unit meter=")" +
         p.unitMeters + R"(" name="u"/><up_axis>)" + p.upAxis + R"(</up_axis></asset>
  <library_cameras><camera id="lens" name="lens"><optics><technique_common><perspective>
    <yfov>30</yfov><aspect_ratio>2</aspect_ratio><znear>0.1</znear><zfar>100</zfar>
  </perspective></technique_common></optics></camera></library_cameras>
  <library_lights><light id="sun" name="sun"><technique_common><directional>
    <color>0.5 0.25 1</color></directional></technique_common></light></library_lights>
  <library_effects><effect id="red-fx"><profile_COMMON><technique sid="common"><lambert>
    <diffuse><color>0.8 0.1 0.1 1</color></diffuse></lambert></technique></profile_COMMON>
  </effect></library_effects>
  <library_materials><material id="red" name="red"><instance_effect url="#red-fx"/></material>
  </library_materials>
  <library_geometries><geometry id="tri" name="tri"><mesh>
    <source id="pos"><float_array id="pos-a" count="9">)" +
         p.positions + R"(</float_array>
      <technique_common><accessor source="#pos-a" count="3" stride="3"><param name="X" type="float"/>
        <param name="Y" type="float"/><param name="Z" type="float"/></accessor></technique_common>
    </source>
    <vertices id="v"><input semantic="POSITION" source="#pos"/></vertices>
    <triangles count=")" +
         p.triangleCount +
         R"(" material="m"><input semantic="VERTEX" source="#v" offset="0"/><p>)" + p.indices +
         R"(</p></triangles>
  </mesh></geometry></library_geometries>
  <library_visual_scenes><visual_scene id="s">
    <node id="shape" name="shape"><instance_geometry url="#tri"><bind_material><technique_common>
      <instance_material symbol="m" target="#red"/></technique_common></bind_material>
    </instance_geometry></node>
    <node id="view" name="view">)" +
         p.camera + R"(<instance_camera url="#lens"/></node>
    <node id="key" name="key">)" +
         p.light + R"(<instance_light url="#sun"/></node>
  </visual_scene></library_visual_scenes>
  <scene><instance_visual_scene url="#s"/></scene>
</COLLADA>
)";
}

}  // namespace glint::test
