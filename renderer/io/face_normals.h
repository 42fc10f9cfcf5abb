#pragma once
// Which way the faces of a mesh file point, set right in Assimp's scene before Glint flattens it
// (io/mesh_io.cpp): where a file's meshes give vertex normals, those that give none are shaded
// flat as glTF 2.0 says (3.7.2.1: "client implementations MUST calculate flat normals"), not the
// whole file; and a mesh placed by a mirroring node (a transform of negative determinant) has
// its triangles wound back to counter-clockwise about their outward normal, as glTF says a
// clockwise winding under such a node means and as a scene's mirroring transform does.
#include <assimp/scene.h>

#include <string>

namespace glint {

// Whether some of the scene's triangle meshes give vertex normals and some do not.
bool someMeshesLackNormals(const aiScene& s);

// Gives each triangle mesh without vertex normals its faces' own: every corner a vertex of its
// own, with the normal of its triangle (zero for a triangle of no area, whose shading then
// takes the geometric normal). The mesh's skin and morph targets, which Glint does not render
// and whose vertex numbers would no longer hold, are dropped. A mesh of more than 2^32 corners
// is refused (GlintError naming `path`).
void giveFlatNormalsWhereMissing(aiScene& s, const std::string& path);

// Reverses the winding of every triangle that a node of negative determinant places (the
// transform accumulated from the root), copying a mesh that other nodes place unmirrored.
// Vertex normals and tangents are left as they are: Assimp carries them through the inverse
// transpose, which keeps them outward.
void windMirroredTrianglesOutward(aiScene& s);

}  // namespace glint
