#include "geometry/tangents.h"

#include <mikktspace/mikktspace.h>

#include <new>
#include <string>

#include "core/frame.h"
#include "core/memory.h"

namespace glint {

namespace {

struct MeshAccess {
  const TriangleMesh& mesh;
  std::vector<TriangleMesh::Tangent>& out;
};

const MeshAccess& access(const SMikkTSpaceContext* context) {
  return *static_cast<const MeshAccess*>(context->m_pUserData);
}

void copy(const Vec3f& v, float out[]) { out[0] = v.x, out[1] = v.y, out[2] = v.z; }

int faceCount(const SMikkTSpaceContext* context) {
  return static_cast<int>(access(context).mesh.triangleCount());
}
int cornersOfFace(const SMikkTSpaceContext*, const int) { return 3; }

void position(const SMikkTSpaceContext* context, float out[], const int face, const int corner) {
  copy(access(context).mesh.vertex(static_cast<uint32_t>(face), corner), out);
}

void normal(const SMikkTSpaceContext* context, float out[], const int face, const int corner) {
  const TriangleMesh& m = access(context).mesh;
  const auto tri = static_cast<uint32_t>(face);
  if (m.smooth()) return copy(m.normals[m.indices[3 * size_t(tri) + size_t(corner)]], out);
  const Vec3f n = cross(m.vertex(tri, 1) - m.vertex(tri, 0), m.vertex(tri, 2) - m.vertex(tri, 0));
  const float len = length(n);
  copy(len > 0 ? n / len : Vec3f{0, 0, 1}, out);
}

void texCoord(const SMikkTSpaceContext* context, float out[], const int face, const int corner) {
  const TriangleMesh& m = access(context).mesh;
  if (m.hasUvs()) {
    const Vec2f uv = m.uvs[m.indices[3 * size_t(face) + size_t(corner)]];
    out[0] = uv.x, out[1] = uv.y;
    return;
  }
  out[0] = corner == 1 ? 1.0f : 0.0f;
  out[1] = corner == 2 ? 1.0f : 0.0f;
}

void setTangent(const SMikkTSpaceContext* context, const float tangent[], const float sign,
                const int face, const int corner) {
  access(context).out[3 * size_t(face) + size_t(corner)] = {{tangent[0], tangent[1], tangent[2]},
                                                            sign < 0 ? -1.0f : 1.0f};
}

}  // namespace

std::vector<TriangleMesh::Tangent> generateTangents(const TriangleMesh& mesh) {
  // MikkTSpace's working arrays (its triangle records, welding tables, groups and per-corner
  // frames) come to about 400 bytes a triangle, and the result to 48 more: checked before any
  // is allocated, as other loads are (core/memory.h), since under overcommit its malloc would
  // not fail.
  checkMemoryFits(
      512.0 * double(mesh.triangleCount()),
      "generating tangents for a mesh of " + std::to_string(mesh.triangleCount()) + " triangles");
  std::vector<TriangleMesh::Tangent> out(mesh.indices.size());
  MeshAccess data{mesh, out};
  SMikkTSpaceInterface callbacks{};
  callbacks.m_getNumFaces = faceCount;
  callbacks.m_getNumVerticesOfFace = cornersOfFace;
  callbacks.m_getPosition = position;
  callbacks.m_getNormal = normal;
  callbacks.m_getTexCoord = texCoord;
  callbacks.m_setTSpaceBasic = setTangent;
  SMikkTSpaceContext context{&callbacks, &data};
  // It fails only when it cannot allocate its working arrays.
  if (!genTangSpaceDefault(&context)) throw std::bad_alloc();
  // MikkTSpace leaves a zero tangent where it finds none (a corner whose whole group is
  // degenerate): any tangent across the corner's normal, so the frame is defined.
  for (size_t c = 0; c < out.size(); ++c) {
    if (length(out[c].direction) > 0) continue;
    float n[3];
    normal(&context, n, static_cast<int>(c / 3), static_cast<int>(c % 3));
    Vec3f t, b;
    orthonormalBasis({n[0], n[1], n[2]}, t, b);
    out[c] = {t, 1};
  }
  return out;
}

}  // namespace glint
