#pragma once
// An FBX file's axes, which its GlobalSettings give (UpAxis, FrontAxis, CoordAxis: 0 x, 1 y,
// 2 z, each with a sign) and Assimp 5.2 only passes on as scene metadata: a Z-up file of 3ds Max,
// Maya or Blender (axis_up 'Z') rendered lying on its side. Glint's are +y up, +z front (towards
// the viewer of a default camera) and +x right, as a Y-up FBX file's are.
#include <assimp/scene.h>

namespace glint {

// Turns the FBX scene `s` into Glint's axes: its root node's transform is preceded by the
// rotation (a mirror, for a left-handed file) taking the file's right, up and front axes to +x,
// +y and +z. A file whose settings are missing or name no three distinct axes is left as it is.
// Returns whether it turned anything.
bool turnFbxAxesToGlints(aiScene& s);

}  // namespace glint
