#pragma once
// An OBJ file's smoothing groups (`s 1`, `s off`), which Assimp's reader skips: a file that
// gives no vertex normals (`vn`) but puts its faces in smoothing groups asks for them to be
// shaded smooth within each group, and it rendered faceted. Glint writes the normals the groups
// give into the text Assimp reads (io/mesh_io.cpp).
#include <optional>
#include <string>

namespace glint {

// `text` (OBJ file `path`'s) with the normals of its smoothing groups: a `vn` line for each,
// written first, and each face corner naming its own (`v//n`, `v/vt/n`). A corner of a face in
// group g takes the sum of the normals of group g's faces at its vertex (each weighted by the
// face's area: Newell's normal), normalised; faces of different groups meet at a hard edge. A
// face in no group (`s off`, `s 0`, or before any `s`), or at a vertex where its group's normals
// cancel, takes its own normal.
//
// nullopt, the file read as it is, where it gives normals or puts no face in a group, and where
// Assimp 5.2.5 would read the rewritten text otherwise than the file: a line continued with
// '\', a `cstype` block, a byte-order mark, a face with a comment, an index with a leading zero
// or sign that Assimp's face reader splits, a texture index before any `vt` line, or a vertex
// that is not there (Assimp's reader names those errors). Throws OutOfMemoryError where the
// rewriting of a file of 1 MiB or more does not fit the memory budget.
std::optional<std::string> objWithSmoothingGroupNormals(const std::string& text,
                                                        const std::string& path);

}  // namespace glint
