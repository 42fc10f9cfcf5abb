// CSG (seed 000 §13.3) against interval arithmetic done here in double, and as optics: a lens
// made as the intersection of two spheres focuses where the thick-lens formula says, and a
// hollow shell made as a difference never lets a ray into its cavity without crossing glass.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>
#include <utility>

#include "accel/accelerator.h"
#include "core/hash.h"
#include "materials/snell.h"
#include "test_util.h"

namespace glint {
namespace {

// One CSG object in a scene whose eye sits at the origin, so render space is world space.
Scene csgScene(const std::string& csg) {
  return test::sceneFromText(R"({"camera": {"eye": [0,0,0], "look_at": [0,0,-1]},
    "materials": {"m": {"type": "phong"}, "n": {"type": "phong"},
                  "glass": {"type": "dielectric", "ior": 1.5}},
    "objects": [)" + csg + "]}");
}

using Interval = std::pair<double, double>;

double dotD(const Vec3d& a, const Vec3d& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
double axis(const Vec3d& v, int a) { return a == 0 ? v.x : a == 1 ? v.y : v.z; }

// The line o + t·d inside a sphere, in double: the roots of |o + t·d − c|² = r².
std::optional<Interval> sphereInterval(const Vec3d& o, const Vec3d& d, const Vec3d& c, double r) {
  const Vec3d f = o - c;
  const double a = dotD(d, d), b = dotD(f, d), cc = dotD(f, f) - r * r;
  const double disc = b * b - a * cc;
  if (disc <= 0) return std::nullopt;
  return Interval{(-b - std::sqrt(disc)) / a, (-b + std::sqrt(disc)) / a};
}

// The line inside the axis-aligned box [lo, hi], in double.
std::optional<Interval> boxInterval(const Vec3d& o, const Vec3d& d, const Vec3d& lo,
                                    const Vec3d& hi) {
  double t0 = -1e300, t1 = 1e300;
  for (int a = 0; a < 3; ++a) {
    const double n = (axis(lo, a) - axis(o, a)) / axis(d, a),
                 f = (axis(hi, a) - axis(o, a)) / axis(d, a);
    t0 = std::max(t0, std::min(n, f));
    t1 = std::min(t1, std::max(n, f));
  }
  if (!(t0 < t1)) return std::nullopt;
  return Interval{t0, t1};
}

// A random ray towards the region around `target`, from 6 units away (fixed seed).
Ray randomRay(int i, const Vec3f& target, float spread) {
  const auto u = [&](int k) { return 2 * toUnitFloat(hashKey(7, uint64_t(i), k)) - 1; };
  Ray r;
  const Vec3f from = normalize(Vec3f{u(0), u(1), u(2)} + Vec3f{0, 0, 0.01f});
  r.o = target + 6 * from;
  r.d = target + spread * Vec3f{u(3), u(4), u(5)} - r.o;
  return r;
}

// Asserts that the solid's spans along `ray` are `expected`, ends within 1e-5 in t (|d| ≈ 6, so
// about 6e-5 in distance: a few hundred float ulps of the coordinates, far above the rounding of
// the roots and crossings, far below any feature of the test solids).
void expectSpans(const CsgSolid& solid, const Ray& ray, const std::vector<Interval>& expected,
                 int i) {
  const std::vector<CsgSpan> spans = solid.spans(ray);
  ASSERT_EQ(spans.size(), expected.size()) << "ray " << i;
  for (size_t k = 0; k < spans.size(); ++k) {
    EXPECT_NEAR(spans[k].in.t, expected[k].first, 1e-5) << "ray " << i << " span " << k;
    EXPECT_NEAR(spans[k].out.t, expected[k].second, 1e-5) << "ray " << i << " span " << k;
  }
}

TEST(Csg, SetOperationsCombineIntervalsAndDropSlivers) {
  // Interval arithmetic by hand: A = [0, 3], B = [1, 2] ∪ [2 + 1e-7, 5] (a gap under `thin`).
  // Span k's ends lie on surfaces firstId + 2k and firstId + 2k + 1.
  const auto spans = [](std::initializer_list<Interval> list, uint32_t firstId = 0) {
    std::vector<CsgSpan> out;
    uint32_t id = firstId;
    for (const Interval& i : list)
      out.push_back({{float(i.first), id, 0, 0}, {float(i.second), id + 1, 0, 0}}), id += 2;
    return out;
  };
  const auto ends = [](const std::vector<CsgSpan>& s) {
    std::vector<Interval> out;
    for (const CsgSpan& span : s) out.push_back({span.in.t, span.out.t});
    return out;
  };
  const std::vector<CsgSpan> a = spans({{0, 3}}), b = spans({{1, 2}, {2 + 1e-7, 5}}, 10);
  std::vector<CsgSpan> out;
  constexpr float kThin = 1e-5f;
  combineSpans(CsgOp::Union, a, b, kThin, out);
  EXPECT_EQ(ends(out), (std::vector<Interval>{{0, 5}}));
  combineSpans(CsgOp::Intersection, a, b, kThin, out);
  EXPECT_EQ(ends(out), (std::vector<Interval>{{1, 3}}));  // [1, 2] and [2+, 3] close the gap
  combineSpans(CsgOp::Difference, a, b, kThin, out);
  EXPECT_EQ(ends(out), (std::vector<Interval>{{0, 1}}));  // [2, 2+1e-7] is a sliver
  combineSpans(CsgOp::Difference, b, a, kThin, out);
  EXPECT_EQ(ends(out), (std::vector<Interval>{{3, 5}}));
  // Each end keeps the surface it lies on: A's entry (0) and B's entry (10) bound A − B's [0, 1].
  combineSpans(CsgOp::Difference, a, b, kThin, out);
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(out[0].in.surface, 0u);
  EXPECT_EQ(out[0].out.surface, 10u);
  // Abutting pieces A = [0, 1], C = [1, 2]: one span in the union, none in the intersection.
  combineSpans(CsgOp::Union, spans({{0, 1}}), spans({{1, 2}}), kThin, out);
  EXPECT_EQ(ends(out), (std::vector<Interval>{{0, 2}}));
  combineSpans(CsgOp::Intersection, spans({{0, 1}}), spans({{1, 2}}), kThin, out);
  EXPECT_TRUE(out.empty());
}

TEST(Csg, IntersectionOfSpheresIsTheOverlapOfTheirIntervals) {
  // Spheres of radius 1 at x = ±0.5 (centre z = −5): inside both = [max of entries, min of exits].
  const Scene s = csgScene(R"({"type": "csg", "op": "intersection", "material": "m",
      "operands": [{"type": "sphere", "center": [-0.5,0,-5], "radius": 1},
                   {"type": "sphere", "center": [0.5,0,-5], "radius": 1}]})");
  int crossed = 0;
  for (int i = 0; i < 2000; ++i) {
    const Ray r = randomRay(i, {0, 0, -5}, 1.2f);
    const Vec3d o = toDouble(r.o), d = toDouble(r.d);
    const auto a = sphereInterval(o, d, {-0.5, 0, -5}, 1),
               b = sphereInterval(o, d, {0.5, 0, -5}, 1);
    std::vector<Interval> want;
    if (a && b && std::max(a->first, b->first) < std::min(a->second, b->second))
      want.push_back({std::max(a->first, b->first), std::min(a->second, b->second)});
    // Rays through the lens's rim within rounding of a sliver are not judged.
    if (!want.empty() && want[0].second - want[0].first < 1e-3) continue;
    crossed += !want.empty();
    expectSpans(s.csgs[0], r, want, i);
  }
  EXPECT_GT(crossed, 400);  // the test must cross the lens often, not only miss it
}

TEST(Csg, DifferenceOfSpheresIsTheFirstIntervalLessTheSecond) {
  // A (radius 1 at x = −0.3) less B (radius 0.6 at x = 0.4, poking out of A's side): along a
  // line, A's interval with B's removed — none, one or two pieces.
  const Scene s = csgScene(R"({"type": "csg", "op": "difference", "material": "m",
      "operands": [{"type": "sphere", "center": [-0.3,0,-5], "radius": 1},
                   {"type": "sphere", "center": [0.4,0,-5], "radius": 0.6}]})");
  int twoPieces = 0, bitten = 0;
  for (int i = 0; i < 2000; ++i) {
    const Ray r = randomRay(i, {0, 0, -5}, 1.2f);
    const Vec3d o = toDouble(r.o), d = toDouble(r.d);
    const auto a = sphereInterval(o, d, {-0.3, 0, -5}, 1),
               b = sphereInterval(o, d, {0.4, 0, -5}, 0.6);
    std::vector<Interval> want;
    if (a) {
      if (!b || b->second <= a->first || b->first >= a->second) {
        want.push_back(*a);
      } else {
        if (a->first < b->first) want.push_back({a->first, b->first});
        if (b->second < a->second) want.push_back({b->second, a->second});
      }
    }
    // Rays within rounding of a sliver (grazing a sphere, or B's and A's surfaces crossing) are
    // not judged.
    const auto sliver = [&](const std::optional<Interval>& x) {
      return x && x->second - x->first < 1e-3;
    };
    bool near = sliver(a) || sliver(b);
    for (const Interval& w : want) near |= w.second - w.first < 1e-3;
    if (a && b)
      for (double ea : {a->first, a->second})
        for (double eb : {b->first, b->second}) near |= std::abs(ea - eb) < 1e-3;
    if (near) continue;
    twoPieces += want.size() == 2;
    bitten += a && b && b->first < a->second && b->second > a->first;  // B removed some of A
    expectSpans(s.csgs[0], r, want, i);
  }
  // The rays must cross the bite often, through it (two pieces) too.
  EXPECT_GT(twoPieces, 50);
  EXPECT_GT(bitten, 200);
}

// The cube [−1, 1]² × [−6, −4] as an inline mesh of 6·2·n² triangles, each face an n × n grid of
// quads wound outward (the faces' edge vertices repeat; CSG matches them by position).
std::string tessellatedCube(int n) {
  std::string positions, indices;
  int base = 0;
  for (int axis = 0; axis < 3; ++axis)
    for (int side : {-1, 1}) {
      for (int i = 0; i <= n; ++i)
        for (int j = 0; j <= n; ++j) {
          double p[3];
          p[axis] = side;
          p[(axis + 1) % 3] = -1 + 2.0 * i / n;
          p[(axis + 2) % 3] = -1 + 2.0 * j / n;
          positions += (positions.empty() ? "[" : ",[") + std::to_string(p[0]) + "," +
                       std::to_string(p[1]) + "," + std::to_string(p[2] - 5) + "]";
        }
      const auto at = [&](int i, int j) { return std::to_string(base + i * (n + 1) + j); };
      for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
          // (i, j) → (i+1, j) → (i+1, j+1) turns about +axis; the face at −1 turns the other way.
          const std::string a = at(i, j), b = at(i + 1, j), c = at(i + 1, j + 1), d = at(i, j + 1);
          indices += std::string(indices.empty() ? "" : ",") +
                     (side > 0 ? "[" + a + "," + b + "," + c + "],[" + a + "," + c + "," + d + "]"
                               : "[" + a + "," + c + "," + b + "],[" + a + "," + d + "," + c + "]");
        }
      base += (n + 1) * (n + 1);
    }
  return R"({"type": "mesh", "positions": [)" + positions + "], \"indices\": [" + indices + "]}";
}

class BoxMinusSphere : public ::testing::TestWithParam<int> {};

TEST_P(BoxMinusSphere, LeavesTheCornersAndTurnsTheDimplesOver) {
  // A cube [−1, 1]³ (a mesh operand: the 12-triangle box, or the cube tessellated into 20 × 20
  // quads a face, which the operand's hierarchy must search without losing a crossing at any of
  // its shared edges) minus a sphere of radius 1.2 at its centre: the line is inside the box but
  // outside the sphere over at most two pieces.
  const std::string cube = GetParam() == 1
                               ? R"({"type": "box", "min": [-1,-1,-6], "max": [1,1,-4]})"
                               : tessellatedCube(GetParam());
  const Scene s = csgScene(R"({"type": "csg", "op": "difference", "material": "m",
      "operands": [)" + cube +
                           R"(, {"type": "sphere", "center": [0,0,-5], "radius": 1.2}]})");
  const CsgSolid& solid = s.csgs[0];
  EXPECT_EQ(solid.triangles.size(), size_t(12 * GetParam() * GetParam()));
  int twoPieces = 0;
  for (int i = 0; i < 2000; ++i) {
    const Ray r = randomRay(i, {0, 0, -5}, 1.5f);
    const Vec3d o = toDouble(r.o), d = toDouble(r.d);
    const auto box = boxInterval(o, d, {-1, -1, -6}, {1, 1, -4});
    const auto ball = sphereInterval(o, d, {0, 0, -5}, 1.2);
    std::vector<Interval> want;
    if (box && !ball) want.push_back(*box);
    if (box && ball) {
      if (box->first < ball->first)
        want.push_back({box->first, std::min(box->second, ball->first)});
      if (ball->second < box->second)
        want.push_back({std::max(box->first, ball->second), box->second});
    }
    // Corner pieces thinner than 1e-3 sit within rounding of the tolerance: not judged.
    if (std::any_of(want.begin(), want.end(), [](auto& w) { return w.second - w.first < 1e-3; }))
      continue;
    twoPieces += want.size() == 2;
    expectSpans(solid, r, want, i);
    // Where a piece ends on the sphere the solid's outward normal points into the sphere's
    // centre: the subtracted surface is turned over.
    for (const CsgSpan& span : solid.spans(r))
      for (const CsgBoundary& end : {span.in, span.out}) {
        const CsgSurface on = solid.surface(end.surface);
        if (on.triangle != kInvalidId) continue;
        const Vec3f p = r.o + end.t * r.d;
        EXPECT_LT(dot(solid.normal(on, p), p - Vec3f{0, 0, -5}), 0) << "ray " << i;
      }
  }
  EXPECT_GT(twoPieces, 50);
}

INSTANTIATE_TEST_SUITE_P(Csg, BoxMinusSphere, ::testing::Values(1, 20),
                         [](const auto& p) { return p.param == 1 ? "Box" : "TessellatedCube"; });

TEST(Csg, AbuttingOperandsLeaveNoSeamAndNoSliver) {
  // Two unit cubes sharing the face x = 0: their union is one interval along x (no surface at
  // the shared face), their intersection nothing (only the face, zero thick).
  const std::string cubes = R"([{"type": "box", "min": [-1,-0.5,-5.5], "max": [0,0.5,-4.5]},
                                {"type": "box", "min": [0,-0.5,-5.5], "max": [1,0.5,-4.5]}])";
  const Scene joined =
      csgScene(R"({"type": "csg", "op": "union", "material": "m", "operands": )" + cubes + "}");
  const Scene touching = csgScene(
      R"({"type": "csg", "op": "intersection", "material": "m", "operands": )" + cubes + "}");
  for (int i = 0; i < 200; ++i) {
    Ray r;
    const auto u = [&](int k) { return toUnitFloat(hashKey(9, uint64_t(i), k)) - 0.5f; };
    r.o = {-3, 0.8f * u(0), -5 + 0.8f * u(1)};
    r.d = {1, 0.05f * u(2), 0.05f * u(3)};
    const std::vector<CsgSpan> spans = joined.csgs[0].spans(r);
    ASSERT_EQ(spans.size(), 1u) << "ray " << i;
    EXPECT_NEAR(spans[0].in.t, 2, 1e-5);   // x = −1
    EXPECT_NEAR(spans[0].out.t, 4, 1e-5);  // x = 1
    EXPECT_TRUE(touching.csgs[0].spans(r).empty()) << "ray " << i;
  }
}

TEST(Csg, AGlassLensOfTwoSpheresFocusesAtTheThickLensFocus) {
  // Spheres of radius R = 1.6 centred at z = ∓1.4 overlap in a biconvex lens of thickness
  // d = 0.4 between its vertices at z = ±0.2 (centre z = −5 here). Lensmaker's equation for a
  // thick lens, n = 1.5, R1 = R, R2 = −R:
  //   1/f = (n−1)(2/R − (n−1)d/(n R²)) → f = 1.66956; back focal distance
  //   f(1 − (n−1)d/(n R)) = 1.53043, so paraxial rays cross the axis at z = −5.2 − 1.53043.
  // Spherical aberration pulls a ray at height h closer by about k·h² (k ≈ 1.2 here); at
  // h = 0.01 that is 1.2e-4.
  const Scene s = csgScene(R"({"type": "csg", "op": "intersection", "material": "glass",
      "operands": [{"type": "sphere", "center": [0,0,-6.4], "radius": 1.6},
                   {"type": "sphere", "center": [0,0,-3.6], "radius": 1.6}]})");
  const auto accel = makeAccelerator(AccelKind::Embree, s);
  // Where a ray entering parallel to the axis at height h crosses the axis behind the lens:
  // refracted in and out by Snell's law at the solid's own normals.
  const auto focusAt = [&](float h) {
    Ray r;
    r.o = {0, h, 0};
    r.d = {0, 0, -1};
    for (float eta : {1 / 1.5f, 1.5f}) {  // into the glass, then out of it
      const Hit hit = accel->intersect(r);
      if (!hit) {
        ADD_FAILURE() << "the ray at height " << h << " missed the lens";
        return double(kInfinity);
      }
      const ShadingPoint sp = s.shadingPoint(r, hit);
      const Vec3f d = normalize(r.d);
      Vec3f t;
      EXPECT_TRUE(refract(d, dot(d, sp.ng) < 0 ? sp.ng : -sp.ng, eta, t));
      r = spawnRay(sp, t, 0);
    }
    return double(r.o.z - r.o.y / r.d.y * r.d.z);
  };
  const double paraxial = -5.2 - 1.53043;
  EXPECT_NEAR(focusAt(0.01f), paraxial, 3e-4);
  EXPECT_NEAR(focusAt(0.02f), paraxial, 8e-4);
  // Marginal rays focus short of paraxial ones (positive spherical aberration), growing as h².
  const double at1 = focusAt(0.1f) - paraxial, at2 = focusAt(0.2f) - paraxial;
  EXPECT_GT(at1, 0);
  EXPECT_NEAR(at2 / at1, 4, 0.3);
  // The thin-lens focal length (n−1)·2/R = 1.6, measured from the lens's centre, is within half
  // the lens's thickness (0.2) of where paraxial rays focus: the thin lens neglects it.
  EXPECT_NEAR(-5 - focusAt(0.01f), 1.6, 0.2);
}

TEST(Csg, AHollowShellNeverLetsARayIntoItsCavityWithoutCrossingIt) {
  // A sphere of radius 1 minus one of radius 0.8: every boundary a ray meets alternates entering
  // and leaving by the solid's own normal, and every stretch between boundaries is in the glass
  // (0.8 < |p| < 1) exactly when the boundary before it was entered. A leak would show as a
  // stretch in the cavity or outside reached through an "entering" boundary, or the reverse.
  const Scene s = csgScene(R"({"type": "csg", "op": "difference", "material": "glass",
      "operands": [{"type": "sphere", "center": [0,0,-5], "radius": 1},
                   {"type": "sphere", "center": [0,0,-5], "radius": 0.8}]})");
  const auto accel = makeAccelerator(AccelKind::Embree, s);
  int fourCrossings = 0;
  for (int i = 0; i < 5000; ++i) {
    Ray r = randomRay(i, {0, 0, -5}, 1.0f);
    int crossings = 0;
    bool inGlass = false;
    // A sphere minus a sphere meets a line at most four times; a fifth boundary is a fault.
    for (Hit hit = accel->intersect(r); hit && crossings < 5; hit = accel->intersect(r)) {
      const ShadingPoint sp = s.shadingPoint(r, hit);
      const bool entering = dot(r.d, sp.ng) < 0;
      ASSERT_NE(entering, inGlass) << "ray " << i << " crossing " << crossings;
      inGlass = entering;
      ++crossings;
      r = spawnRay(sp, r.d, 0);
      // The next stretch, sampled at its middle (or just past here when it runs to infinity).
      const Hit next = accel->intersect(r);
      const float mid = next ? 0.5f * next.t : 0.01f;
      const float distance = length(r.o + mid * r.d - Vec3f{0, 0, -5});
      if (next && next.t * length(r.d) < 1e-3f) continue;  // a sliver at a grazing rim
      EXPECT_EQ(inGlass, distance > 0.8f && distance < 1.0f) << "ray " << i;
    }
    EXPECT_FALSE(inGlass) << "ray " << i << " ends inside the glass";
    fourCrossings += crossings == 4;
  }
  EXPECT_GT(fourCrossings, 1000);  // many rays cross the cavity, not only the shell's rim
}

}  // namespace
}  // namespace glint
