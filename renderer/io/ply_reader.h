#pragma once
// Glint's own PLY reader (ASCII, binary little and big endian), used for every .ply file.
// Assimp's PLY path welded the file's already shared vertices again (JoinIdenticalVertices),
// slow and several times the memory of the mesh it made. This one streams the
// body through a bounded buffer into vectors sized by the header's counts (checked against the
// file's size first, io/ply_header.h), checking every value as it is read. docs/scene-format.md
// lists what it takes from a file; docs/performance.md ("Loading big meshes") what it costs.
#include <string>

#include "io/mesh_io.h"

namespace glint {

// From the "vertex" element: x, y, z of any scalar type, nx, ny, nz normals when all three are
// there, u, v (or s, t; texture_u, texture_v; texture_s, texture_t) coordinates, and red,
// green, blue (or diffuse_red ...) colours, which become the diffuse colour. From the
// "face" element: the list vertex_indices (or vertex_index) of any count and index types,
// polygons fanned into triangles from their first corner; faces of one or two vertices give
// none. Other elements and properties are skipped; vertices that no triangle uses are dropped.
// One part, with the default material named "FILE:" as for every PLY (io/mesh_materials.h).
// Throws GlintError naming `path`, the element and what is wrong: a value that is not a number
// or not finite, an index outside the vertices, a list longer than the rest of the file, a
// file that ends early, or no triangles. Big files log their progress (io/load_progress.h).
MeshFile readPlyFile(const std::string& path);

}  // namespace glint
