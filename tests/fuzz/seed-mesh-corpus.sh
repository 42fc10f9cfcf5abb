#!/usr/bin/env bash
# Makes tests/fuzz/corpus-mesh/ from small files of Debian's assimp-testmodels (BSD-3-Clause,
# third_party_notes.md) in glint_fuzz_mesh's input form: a format byte (0 PLY, 1 OBJ, 2 glTF,
# 3 GLB, 4 Collada, 5 FBX, 6 3DS, 7 STL, 8 AC3D, 9 Milkshape 3D, 10 X3D), the file, and for an
# OBJ's material library or a glTF's buffer the separator and that file, renamed m.mtl / m.bin
# (the names the fuzzer writes them under). Run once; the output is checked in.
set -euo pipefail
models=/usr/share/assimp/models
out="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)/corpus-mesh"
sep=$'\n@@glint-part@@\n'
rm -rf "$out"
mkdir -p "$out"

seed() {  # seed FORMAT_BYTE FILE [PART]
  local name
  name="$(echo "${2#"$models"/}" | tr '/ ' '__')"
  {
    printf "\\x$1"
    if [ $# -ge 3 ]; then
      sed -E 's/(mtllib|"uri" *: *")[^"]*\.(mtl|bin)/\1 m.\2/; s/mtllib  m/mtllib m/; s/" m\.bin/"m.bin/' "$2"
      printf '%s' "$sep"
      cat "$3"
    else
      cat "$2"
    fi
  } >"$out/$name"
}

for f in cube.ply cube_binary.ply cube_uv.ply float-color.ply points.ply issue623.ply; do
  seed 00 "$models/PLY/$f"
done
for f in box.obj box_without_lineending.obj box_mat_with_spaces.obj testline.obj testpoints.obj \
  testmixed.obj point_cloud.obj number_formats.obj multiple_spaces.obj box_UTF16BE.obj \
  concave_polygon.obj cube_with_vertexcolors.obj box_longline.obj; do
  seed 01 "$models/OBJ/$f"
done
seed 01 "$models/OBJ/cube_usemtl.obj" "$models/OBJ/cube_usemtl.mtl"
seed 01 "$models/OBJ/cube_mtllib_after_g.obj" "$models/OBJ/cube_mtllib_after_g.mtl"
seed 01 "$models/OBJ/regr_3429812.obj" "$models/OBJ/regr_3429812.mtl"
for d in BoxTextured-glTF/BoxTextured IndexOutOfRange/IndexOutOfRange \
  IndexOutOfRange/AllIndicesOutOfRange BoxTexcoords-glTF/boxTexcoords \
  IncorrectVertexArrays/Cube; do
  bin="$(ls "$models/glTF2/$(dirname "$d")"/*.bin | head -1)"
  seed 02 "$models/glTF2/$d.gltf" "$bin"
done
for f in cameras/Cameras.gltf simple_skin/simple_skin.gltf RecursiveNodes/RecursiveNodes.gltf \
  TestNoRootNode/SceneWithoutNodes.gltf BoxTextured-glTF-Embedded/BoxTextured.gltf \
  wrongTypes/badUint.gltf; do
  seed 02 "$models/glTF2/$f"
done
for f in BoxTextured-glTF-Binary/BoxTextured.glb BoxWithInfinites-glTF-Binary/BoxWithInfinites.glb \
  BoxBadNormals-glTF-Binary/BoxBadNormals.glb; do
  seed 03 "$models/glTF2/$f"
done
seed 04 "$models/Collada/cameras.dae"
seed 04 "$models/Collada/cube_triangulate.dae"
seed 05 "$models/FBX/box.fbx"
seed 06 "$models/3DS/CameraRollAnim.3ds"
seed 06 "$models/3DS/RotatingCube.3DS"
seed 07 "$models/STL/triangle.stl"
seed 07 "$models/STL/triangle_with_two_solids.stl"
seed 08 "$models/AC/closedLine.ac"
seed 08 "$models/AC/SphereWithLight_UTF8BOM.ac"
seed 09 "$models/MS3D/twospheres.ms3d"
seed 0a "$models/X3D/ComputerKeyboard.x3d"
echo "$(ls "$out" | wc -l) seeds, $(du -sb "$out" | cut -f1) bytes in $out"
