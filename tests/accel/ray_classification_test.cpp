// Ray classification (seed 002 §9.2.3, accel/ray_classification.h): its hits against brute
// force, whatever the thread count, the order in which its cells were made and its memory cap;
// rays classified where they enter E, along the direction cube's edges and with zero components.
#include "accel/ray_classification.h"

#include <gtest/gtest.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <cmath>
#include <vector>

#include "accel/triangle_scenes.h"
#include "core/hash.h"
#include "io/scene_loader.h"
#include "render/render_job.h"

namespace glint {
namespace {

// A lattice of 4 x 4 x 4 spheres of radius 0.2, one unit apart (centres at 0, 1, 2, 3 on each
// axis), an instance of a rotated group at (0.5, 2.5, 1.5) and, with `soup`, 400 small
// triangles through it: enough objects that the cells are split many levels down.
Scene lattice(bool soup = true) {
  std::string objects, pos, idx;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j)
      for (int k = 0; k < 4; ++k)
        objects += R"({"type": "sphere", "radius": 0.2, "material": "m", "center": )" +
                   test::vec(float(i), float(j), float(k)) + "},";
  for (int t = 0; t < (soup ? 400 : 1); ++t) {
    // Without the soup, one triangle far below the lattice, out of every ray's way.
    const auto u = [&](int k) {
      return soup ? 3.2f * toUnitFloat(hashKey(5, t, k)) - 0.1f : -5.0f;
    };
    pos += (t ? "," : "") + test::vec(u(0), u(1), u(2)) + "," +
           test::vec(u(0) + 0.15f, u(1), u(2)) + "," + test::vec(u(0), u(1) + 0.15f, u(2) + 0.1f);
    idx += (t ? ",[" : "[") + std::to_string(3 * t) + "," + std::to_string(3 * t + 1) + "," +
           std::to_string(3 * t + 2) + "]";
  }
  // The eye at the origin: render space (world minus the eye) is then world space.
  return test::sceneFromText(R"({"camera": {"eye": [0,0,0], "look_at": [1.5,1.5,1.5]},
    "materials": {"m": {"type": "phong"}},
    "groups": {"g": [{"type": "box", "min": [-0.3,-0.1,-0.1], "max": [0.3,0.1,0.1], "material": "m"},
                     {"type": "sphere", "center": [0.3,0,0], "radius": 0.1, "material": "m"}]},
    "objects": [)" + objects +
                             R"({"type": "mesh", "material": "m", "positions": [)" + pos +
                             "], \"indices\": [" + idx + R"(]},
      {"type": "instance", "group": "g", "transform": {"translate": [0.5,2.5,1.5], "rotate": [1,1,0,30]}}]})");
}

// Rays from around the lattice (some from outside E) towards points inside it: most hit.
std::vector<Ray> raysThrough(int n, uint64_t seed) {
  std::vector<Ray> rays;
  for (int i = 0; i < n; ++i) {
    const auto u = [&](int k) { return toUnitFloat(hashKey(seed, i, k)); };
    Ray r;
    r.o = {7 * u(0) - 2, 7 * u(1) - 2, 7 * u(2) - 2};
    r.d = Vec3f{3 * u(3), 3 * u(4), 3 * u(5)} - r.o;
    r.time = u(6);
    rays.push_back(r);
  }
  return rays;
}

void expectSameHit(const Hit& a, const Hit& b, size_t i) {
  ASSERT_EQ(bool(a), bool(b)) << "ray " << i;
  if (!a) return;
  // Bit for bit: the same object tested by the same routine on the same ray.
  ASSERT_EQ(a.t, b.t) << "ray " << i;
  ASSERT_EQ(a.u, b.u) << "ray " << i;
  ASSERT_EQ(a.v, b.v) << "ray " << i;
  ASSERT_EQ(a.geomId, b.geomId) << "ray " << i;
  ASSERT_EQ(a.primId, b.primId) << "ray " << i;
  ASSERT_EQ(a.instId, b.instId) << "ray " << i;
}

// Every ray's closest hit and occlusion against brute force's: the same object at the same t
// (the two test the same objects with the same routines; only which objects differs), and at
// least `minHits` hits so that the comparison says something.
void expectAgreesWithBruteForce(const Scene& s, const Accelerator& accel,
                                const std::vector<Ray>& rays, int minHits) {
  const auto brute = makeAccelerator(AccelKind::BruteForce, s);
  int hits = 0;
  for (size_t i = 0; i < rays.size(); ++i) {
    const Hit a = accel.intersect(rays[i]), b = brute->intersect(rays[i]);
    hits += bool(b);
    expectSameHit(a, b, i);
    ASSERT_EQ(accel.occluded(rays[i]), bool(b)) << "ray " << i;
  }
  EXPECT_GE(hits, minHits);
}

TEST(RayClassification, AgreesWithBruteForceAtSeveralThresholds) {
  const Scene s = lattice();
  const std::vector<Ray> rays = raysThrough(20000, 1);
  // The defaults, splitting to single objects in narrow cells, and no splitting at all (w_min 1:
  // every ray tests the whole group, as brute force does).
  for (const RayClassSettings settings :
       {RayClassSettings{}, RayClassSettings{0, 1.0 / 256}, RayClassSettings{8, 1}}) {
    SCOPED_TRACE(settings.wMin);
    const RayClassification rc(s, settings);
    expectAgreesWithBruteForce(s, rc, rays, 10000);
    if (settings.wMin < 1) {
      EXPECT_GT(rc.stats().cells, 1000u);
    } else {
      EXPECT_EQ(rc.stats().cells, 0u);
    }
  }
}

TEST(RayClassification, SameHitsWhateverOrderTheCellsWereMadeIn) {
  // The same rays traced forwards in one structure and backwards in a fresh one: the cells are
  // split in another order. Under a cap they never reach (1 GiB), both end with the same cells;
  // under a cap of 64 KiB the
  // splits that came first took the memory, so different cells stay leaves — and still every
  // hit is the same, bit for bit, since every list a ray can end in holds all it hits.
  const Scene s = lattice();
  const std::vector<Ray> rays = raysThrough(20000, 2);
  constexpr size_t kUnreached = size_t(1) << 30;
  for (const size_t cap : {kUnreached, size_t(64) << 10}) {
    SCOPED_TRACE(cap);
    const RayClassSettings settings{4, 1.0 / 64, cap};
    const RayClassification forwards(s, settings), backwards(s, settings);
    std::vector<Hit> a(rays.size()), b(rays.size());
    for (size_t i = 0; i < rays.size(); ++i) a[i] = forwards.intersect(rays[i]);
    for (size_t i = rays.size(); i-- > 0;) b[i] = backwards.intersect(rays[i]);
    for (size_t i = 0; i < rays.size(); ++i) expectSameHit(a[i], b[i], i);
    if (cap == kUnreached) {
      EXPECT_EQ(forwards.stats().cells, backwards.stats().cells);
      EXPECT_EQ(forwards.stats().references, backwards.stats().references);
    } else {
      // The cap bit: both filled most of it (a list near the roots is most of the 465 objects).
      EXPECT_LE(forwards.stats().lazyBytes, cap);
      EXPECT_LE(backwards.stats().lazyBytes, cap);
      EXPECT_GT(forwards.stats().lazyBytes, cap / 2);
      EXPECT_GT(backwards.stats().lazyBytes, cap / 2);
    }
  }
}

TEST(RayClassification, SameHitsOnOneThreadAndTwo) {
  // Two threads split the cells of one structure while tracing, racing for the same cells; one
  // thread traces the same rays through a fresh structure. Under a cap they never reach (1 GiB)
  // both make the same cells.
  const Scene s = lattice();
  const std::vector<Ray> rays = raysThrough(40000, 3);
  const RayClassSettings settings{8, 1.0 / 32, size_t(1) << 30};
  const RayClassification one(s, settings), two(s, settings);
  std::vector<Hit> a(rays.size()), b(rays.size());
  for (size_t i = 0; i < rays.size(); ++i) a[i] = one.intersect(rays[i]);
  tbb::task_arena arena(2);
  arena.execute([&] {
    tbb::parallel_for(size_t(0), rays.size(), [&](size_t i) { b[i] = two.intersect(rays[i]); });
  });
  for (size_t i = 0; i < rays.size(); ++i) expectSameHit(a[i], b[i], i);
  // The same cells, whichever thread made each (a loser of a race drops its copy).
  EXPECT_EQ(one.stats().cells, two.stats().cells);
  EXPECT_EQ(one.stats().references, two.stats().references);
  EXPECT_EQ(one.stats().lazyBytes, two.stats().lazyBytes);
}

TEST(RayClassification, MemoryStaysUnderItsCapAndHitsStayRight) {
  // 2000 triangles fanned across the cube, every box spanning it: no beam separates them, so
  // lists barely shrink and the cells would grow without bound. Under a cap of 256 KiB the
  // structure stops splitting there and still finds brute force's hits.
  const Scene s = test::triangles(2000, true);
  const RayClassSettings settings{2, 1.0 / 1024, size_t(256) << 10};
  const RayClassification rc(s, settings);
  std::vector<Ray> rays;
  for (int i = 0; i < 3000; ++i) {
    const auto u = [&](int k) { return toUnitFloat(hashKey(4, i, k)); };
    const Vec3f o{3 * u(0) - 1, 3 * u(1) - 1, 3 * u(2) - 1};
    rays.push_back(Ray{o, Vec3f{u(3), u(4), u(5)} - o});
  }
  expectAgreesWithBruteForce(s, rc, rays, 500);
  EXPECT_LE(rc.stats().lazyBytes, settings.capBytes);
  // The cap was reached: the lists made fill more than half of it (a list of 2000 is 8 KB).
  EXPECT_GT(rc.stats().lazyBytes, settings.capBytes / 2);
  test::expectFindsTheFansClosestHit(s, rc);
}

TEST(RayClassification, BeamTestsStayWithinTheirBudgetAndHitsStayRight) {
  // The same fan: a cell keeps nearly all its parent's 2000 objects, so each new cell costs
  // about 2000 beam tests while costing almost no memory. Unbounded, the 3000 rays make cells
  // for several million tests; under a budget of 10⁵ (fifty cells) the structure stops there,
  // on one thread exactly at or below it, and still finds brute force's hits.
  const Scene s = test::triangles(2000, true);
  std::vector<Ray> rays;
  for (int i = 0; i < 3000; ++i) {
    const auto u = [&](int k) { return toUnitFloat(hashKey(6, i, k)); };
    const Vec3f o{3 * u(0) - 1, 3 * u(1) - 1, 3 * u(2) - 1};
    rays.push_back(Ray{o, Vec3f{u(3), u(4), u(5)} - o});
  }
  RayClassSettings settings{2, 1.0 / 1024};
  const RayClassification unbounded(s, settings);
  for (const Ray& r : rays) unbounded.intersect(r);
  settings.testBudget = 100000;
  EXPECT_GT(unbounded.stats().beamTests, 10 * settings.testBudget);
  const RayClassification bounded(s, settings);
  expectAgreesWithBruteForce(s, bounded, rays, 500);
  EXPECT_LE(bounded.stats().beamTests, settings.testBudget);
  // The budget was reached: a list of 2000 more would have passed it.
  EXPECT_GT(bounded.stats().beamTests + 2000, settings.testBudget);
  test::expectFindsTheFansClosestHit(s, bounded);
}

TEST(RayClassification, ARayFromOutsideEIsClassifiedWhereItEnters) {
  // From z = 20, far outside E (the cube around the lattice and the lone triangle at −5), straight
  // down the column of spheres at x = y = 3: it meets the sphere at (3, 3, 3) first, at
  // t = 20 − 3 − 0.2.
  const Scene s = lattice(false);
  const RayClassification rc(s, {0, 1.0 / 256});
  const Hit h = rc.intersect(Ray{{3, 3, 20}, {0, 0, -1}});
  ASSERT_TRUE(h);
  EXPECT_NEAR(h.t, 16.8f, 1e-4f);
  // The same ray starting beyond the lattice, pointing away, misses E: no hit.
  EXPECT_FALSE(rc.intersect(Ray{{3, 3, 20}, {0, 0, 1}}));
  // A segment ending before E (tMax 16) misses too.
  Ray shortRay{{3, 3, 20}, {0, 0, -1}};
  shortRay.tMax = 16;
  EXPECT_FALSE(rc.occluded(shortRay));
}

TEST(RayClassification, RaysOnTheDirectionCubesEdgesAndWithZeroComponents) {
  // Directions with |dx| = |dy| (on the edge between the ±x and ±y faces, u = ±1), with all
  // three equal (a corner) and with one or two zero components, from a grid of origins: every
  // answer is brute force's.
  const Scene s = lattice();
  const RayClassification rc(s, {2, 1.0 / 128});
  std::vector<Ray> rays;
  const float dirs[][3] = {{1, 1, 0}, {-1, 1, 0.5f}, {1, -1, -1}, {-1, -1, -1}, {0, 0, -1},
                           {0, 1, 0}, {-1, 0, 0},    {0, 1, 1},   {1, 0, -1},   {0.5f, 1, -1},
                           {1, 1, 1}, {-0.f, 0, 1},  {1, -0.f, 0}};
  for (int i = 0; i < 9; ++i)
    for (int j = 0; j < 9; ++j)
      for (int k = 0; k < 9; ++k)
        for (const auto& d : dirs)
          rays.push_back(
              Ray{{-0.5f + 0.5f * float(i), -0.5f + 0.5f * float(j), -0.5f + 0.5f * float(k)},
                  {d[0], d[1], d[2]}});
  expectAgreesWithBruteForce(s, rc, rays, 1500);  // about a fifth of these rays hit
  // On the edge between the +x and +y faces, from (−1, −1, 1) (inside E, which spans the lone
  // triangle at −5 too): the sphere at (0, 0, 1) first, its centre √2 along the unit direction,
  // so t = √2 − 0.2.
  const Scene lone = lattice(false);
  const RayClassification few(lone, {2, 1.0 / 128});
  const Hit h = few.intersect(Ray{{-1, -1, 1}, {0.70710678f, 0.70710678f, 0}});
  ASSERT_TRUE(h);
  EXPECT_NEAR(h.t, std::sqrt(2.0f) - 0.2f, 1e-4f);
}

TEST(RayClassification, RendersTheSameImageOnOneThreadAndTwoInEitherTileOrder) {
  // The bundled objects scene (every shape kind, instances, the Wuson mesh) at 48 x 36: one
  // thread in Morton order and two in row order, each through a fresh structure whose cells its
  // threads make while rendering, give the same pixels, bit for bit, as brute force (the same
  // intersection routines on every object).
  Scene s = loadSceneFile(std::string(GLINT_SCENES_DIR) + "/objects.json");
  s.render.width = 48;
  s.render.height = 36;
  s.render.spp = 1;
  const auto render = [&](const Accelerator& accel, int threads, TileOrder order) {
    RenderOptions opt;
    opt.progress = false;
    opt.threads = threads;
    opt.tileSize = 8;
    opt.tileOrder = order;
    return renderScene(s, accel, opt);
  };
  const RayClassification one(s), two(s);
  const RenderResult a = render(one, 1, TileOrder::Morton);
  const RenderResult b = render(two, 2, TileOrder::RowMajor);
  const RenderResult c = render(*makeAccelerator(AccelKind::BruteForce, s), 2, TileOrder::Morton);
  int lit = 0;
  for (int y = 0; y < 36; ++y)
    for (int x = 0; x < 48; ++x)
      for (int k = 0; k < 4; ++k) {
        ASSERT_EQ(a.film.pixel(x, y)[k], b.film.pixel(x, y)[k]) << x << " " << y;
        ASSERT_EQ(a.film.pixel(x, y)[k], c.film.pixel(x, y)[k]) << x << " " << y;
        lit += k == 0 && a.film.pixel(x, y)[0] > 0;
      }
  EXPECT_GT(lit, 48 * 36 / 2);  // the image is not black: the comparison says something
  EXPECT_GT(two.stats().cells, 0u);
}

}  // namespace
}  // namespace glint
