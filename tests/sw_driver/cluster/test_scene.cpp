// The random scene and the geometry stage: the triangles' shape and
// placement, culling, the paper's mean projected height and its trapezoid
// count (Eq. 2), the transform computed by hand, and the teapot through the
// same path.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "cluster/geometry.h"
#include "cluster/scene.h"
#include "cluster_test_support.h"
#include "scenes/teapot_mesh.h"

namespace tessera::cluster {
namespace {

std::vector<ScreenTriangle> survivors(const RandomScene& scene) {
  const View view = random_scene_view(scene);
  std::vector<ScreenTriangle> out;
  WorkCounters counters;
  for (uint32_t i = 0; i < scene.count; ++i) {
    ScreenTriangle t;
    if (transform_triangle(random_triangle(scene, i), view, &t, counters) == GeometryResult::accepted) out.push_back(t);
  }
  return out;
}

bool same(const WorldTriangle& a, const WorldTriangle& b) {
  for (int k = 0; k < 3; ++k) {
    const WorldVertex &u = a.v[k], &v = b.v[k];
    if (u.x != v.x || u.y != v.y || u.z != v.z || u.r != v.r || u.g != v.g || u.b != v.b) return false;
  }
  return true;
}

TEST(ClusterScene, TrianglesDependOnSeedAndIndexAlone) {
  RandomScene scene;
  const WorldTriangle a = random_triangle(scene, 12345), b = random_triangle(scene, 12345);
  EXPECT_TRUE(same(a, b));
  // A node's share, generated alone, is the same triangles.
  random_triangle(scene, 7);
  const WorldTriangle c = random_triangle(scene, 12345);
  EXPECT_TRUE(same(a, c));
  RandomScene other = scene;
  other.seed = 2;
  const WorldTriangle d = random_triangle(other, 12345);
  EXPECT_FALSE(same(a, d));
}

TEST(ClusterScene, TrianglesAreRightIsoscelesInsideTheViewVolume) {
  RandomScene scene;
  scene.width = 300;
  scene.height = 200;
  scene.size = 20;
  for (uint32_t i = 0; i < 2000; ++i) {
    const WorldTriangle t = random_triangle(scene, i);
    auto edge = [&](int a, int b, int k) {
      const float v[3] = {t.v[b].x - t.v[a].x, t.v[b].y - t.v[a].y, t.v[b].z - t.v[a].z};
      return v[k];
    };
    float leg1 = 0, leg2 = 0, dot = 0;
    for (int k = 0; k < 3; ++k) {
      leg1 += edge(0, 1, k) * edge(0, 1, k);
      leg2 += edge(0, 2, k) * edge(0, 2, k);
      dot += edge(0, 1, k) * edge(0, 2, k);
    }
    ASSERT_NEAR(std::sqrt(leg1), 20.0f, 1e-3f);
    ASSERT_NEAR(std::sqrt(leg2), 20.0f, 1e-3f);
    ASSERT_NEAR(dot, 0.0f, 1e-2f);
    for (const WorldVertex& v : t.v) {
      ASSERT_GE(v.x, 0.0f);
      ASSERT_LE(v.x, 300.0f);
      ASSERT_GE(v.y, 0.0f);
      ASSERT_LE(v.y, 200.0f);
      ASSERT_GE(v.z, -150.0f);
      ASSERT_LE(v.z, 150.0f);
      for (float c : {v.r, v.g, v.b}) {
        ASSERT_GE(c, 0.0f);
        ASSERT_LE(c, 1.0f);
      }
    }
  }
}

// Half the triangles face away (binomial: within 5 standard deviations of
// n/2), and the survivors' mean projected height is a quarter of the
// perimeter (Cauchy: the mean width of a plane convex figure turned
// uniformly in space), (2 + sqrt 2) / 4 size, within 5 standard errors of
// the sample and the snapping's 1/16 pixel.
TEST(ClusterScene, HalfAreCulledAndTheMeanHeightIsCauchys) {
  RandomScene scene;
  scene.count = 40000;
  scene.size = 10;
  const std::vector<ScreenTriangle> kept = survivors(scene);
  const double n = scene.count;
  EXPECT_LE(std::fabs(static_cast<double>(kept.size()) - n / 2), 5 * std::sqrt(n) / 2);
  double sum = 0, sum2 = 0;
  for (const ScreenTriangle& t : kept) {
    const int32_t high = std::max({t.v[0].y, t.v[1].y, t.v[2].y}), low = std::min({t.v[0].y, t.v[1].y, t.v[2].y});
    const double h = (high - low) / 16.0;
    sum += h;
    sum2 += h * h;
  }
  const double m = static_cast<double>(kept.size()), mean = sum / m;
  const double standard_error = std::sqrt((sum2 / m - mean * mean) / m);
  const double cauchy = (2 + std::sqrt(2.0)) / 4 * scene.size;
  EXPECT_LE(std::fabs(mean - cauchy), 5 * standard_error + 1.0 / 16) << mean << " vs " << cauchy;
  const SceneStatistics statistics = measure_random_scene(scene);
  EXPECT_EQ(statistics.survivors, kept.size());
  EXPECT_NEAR(statistics.mean_height(), mean, 1e-4);
  std::printf("random scene of %u triangles of size %g: %u survive, mean height %.3f (Cauchy %.3f; the paper 8.3)\n",
              scene.count, static_cast<double>(scene.size), statistics.survivors, mean, cauchy);
}

class CountingSink : public TrapezoidSink {
 public:
  void put(unsigned, const Trapezoid&) override { ++count; }
  uint64_t count = 0;
};

// The paper's Eq. 2: a triangle of height h crosses a stripe boundary h p /
// y times on average, so the n/2 survivors' 2 halves make r = n (1 + h p /
// (2 y)) trapezoids. Here the same reasoning is followed with the split's
// rows: a half covers the rows whose centres lie in [y_top, y_bottom), so
// it crosses the boundary above row B (B - 1 and B both covered) when the
// triangle is moved down by an s in (B + 1/2 - y_bottom, B - 1/2 - y_top],
// a window of h_half - 1 pixels; the scene moves each triangle uniformly
// over the s that keep its centroid in [0.75 size, y - 0.75 size]. So the
// pieces are the non-empty halves (counted) plus, per half and internal
// boundary, the fraction of the shifts that cross it; the variance of the
// crossings is at most the sum of P (1 - P) (a sum of indicators whose
// windows are disjoint or, for long halves, whose count is within one of
// its mean). The expectation is derived here from the survivors' vertices,
// independently of the split.
TEST(ClusterScene, TheTrapezoidCountFollowsThePapersEquation2) {
  RandomScene scene;
  scene.count = 20000;
  scene.size = 10;
  const std::vector<ScreenTriangle> kept = survivors(scene);
  const float h = measure_random_scene(scene).mean_height();
  const double y = scene.height, margin = 0.75 * scene.size;
  for (unsigned p : {1u, 2u, 3u, 8u, 16u, 64u, 100u, 128u}) {
    CountingSink sink;
    double expected = 0, variance = 0;
    for (const ScreenTriangle& t : kept) {
      split_triangle(t, scene.height, p, sink);
      double ys[3] = {t.v[0].y / 16.0, t.v[1].y / 16.0, t.v[2].y / 16.0};
      std::sort(ys, ys + 3);
      const double centroid = (ys[0] + ys[1] + ys[2]) / 3;
      const double shift_low = margin - centroid, shift_high = y - margin - centroid;
      auto rows = [](double top, double bottom) { return std::ceil(bottom - 0.5) - std::ceil(top - 0.5); };
      const double halves[2][2] = {{ys[0], ys[1]}, {ys[1], ys[2]}};
      for (const auto& half : halves) {
        if (rows(half[0], half[1]) <= 0) continue;
        expected += 1;  // the half itself
        for (unsigned stripe = 1; stripe < p; ++stripe) {
          const double boundary = std::floor(stripe * y / p);
          const double low = std::max(boundary + 0.5 - half[1], shift_low);
          const double high = std::min(boundary - 0.5 - half[0], shift_high);
          const double probability = high > low ? (high - low) / (shift_high - shift_low) : 0.0;
          expected += probability;
          variance += probability * (1 - probability);
        }
      }
    }
    const double got = static_cast<double>(sink.count);
    EXPECT_LE(std::fabs(got - expected), 5 * std::sqrt(variance) + 0.5) << "p " << p;
    const double paper = scene.count * (1 + h * p / (2 * y));
    std::printf("p %3u: %6.0f trapezoids, expected %8.1f +- %5.1f; the paper's n (1 + h p / 2y) = %8.1f\n", p, got,
                expected, std::sqrt(variance), paper);
  }
}

TEST(ClusterScene, BadScenesAreNamed) {
  RandomScene scene;
  EXPECT_EQ(random_scene_error(scene), nullptr);
  scene.width = 0;
  EXPECT_EQ(std::string(random_scene_error(scene)), "width: must be in 1 .. 512");
  scene.width = 512;
  scene.height = 600;
  EXPECT_EQ(std::string(random_scene_error(scene)), "height: must be in 1 .. 512");
  scene.height = 14;
  EXPECT_EQ(std::string(random_scene_error(scene)),
            "size: the triangle must fit the screen (1.5 size <= width, height)");
  scene.height = 512;
  scene.size = 0;
  EXPECT_EQ(std::string(random_scene_error(scene)), "size: must be positive");
}

TEST(ClusterScene, LightingIsAmbientPlusDiffuse) {
  Light light;  // towards +z, ambient 0.2, diffuse 0.8
  const float base[3] = {1.0f, 0.5f, 0.25f};
  WorldVertex v;
  const float facing[3] = {0, 0, 1}, side[3] = {1, 0, 0}, half[3] = {0.6f, 0, 0.8f}, away[3] = {0, 0, -1};
  light_vertex(facing, base, light, &v);
  EXPECT_FLOAT_EQ(v.r, 1.0f);
  EXPECT_FLOAT_EQ(v.g, 0.5f);
  light_vertex(side, base, light, &v);
  EXPECT_FLOAT_EQ(v.r, 0.2f);
  light_vertex(half, base, light, &v);  // 0.2 + 0.8 * 0.8 = 0.84
  EXPECT_FLOAT_EQ(v.b, 0.25f * 0.84f);
  light_vertex(away, base, light, &v);
  EXPECT_FLOAT_EQ(v.g, 0.1f);
}

WorldVertex world(float x, float y, float z) {
  WorldVertex v;
  v.x = x;
  v.y = y;
  v.z = z;
  v.r = 1.0f;
  v.g = 0.5f;
  v.b = 0.0f;
  return v;
}

TEST(ClusterGeometry, TheTransformSnapsTo9_4WithYDown) {
  RandomScene scene;  // 512 x 512, z in [-256, 256]
  const View view = random_scene_view(scene);
  WorkCounters counters;
  ScreenTriangle out;
  // Counter-clockwise with y up: a front face.
  const WorldTriangle front{{world(100.25f, 200, 0), world(140, 200, 128), world(100, 230.5f, -256)}};
  ASSERT_EQ(transform_triangle(front, view, &out, counters), GeometryResult::accepted);
  EXPECT_EQ(out.v[0].x, 1604);                 // 100.25 * 16
  EXPECT_EQ(out.v[0].y, (512 - 200) * 16);     // y down
  EXPECT_EQ(out.v[0].z, 8388608u);             // (0 + 1) / 2 * (2^24 - 1), rounded
  EXPECT_EQ(out.v[1].z, 4194304u);             // z = 128 is nearer: (-0.5 + 1) / 2 * (2^24 - 1) = 4194303.75
  EXPECT_EQ(out.v[2].z, MAX_DEPTH);            // the far plane
  EXPECT_EQ(out.v[2].y, (512 * 2 - 461) * 8);  // (512 - 230.5) * 16
  EXPECT_EQ(out.v[0].r, 255);
  EXPECT_EQ(out.v[0].g, 128);  // 0.5 * 255 = 127.5, rounded
  EXPECT_EQ(out.v[0].b, 0);
  const WorldTriangle back{{front.v[0], front.v[2], front.v[1]}};
  EXPECT_EQ(transform_triangle(back, view, &out, counters), GeometryResult::culled);
  const WorldTriangle line{{world(0, 0, 0), world(10, 10, 0), world(20, 20, 0)}};
  EXPECT_EQ(transform_triangle(line, view, &out, counters), GeometryResult::culled);
  const WorldTriangle beyond_depth{{world(0, 0, 300), world(10, 0, 0), world(0, 10, 0)}};
  EXPECT_EQ(transform_triangle(beyond_depth, view, &out, counters), GeometryResult::rejected);
  const WorldTriangle beyond_guard{{world(-1100, 0, 0), world(10, 0, 0), world(0, 10, 0)}};
  EXPECT_EQ(transform_triangle(beyond_guard, view, &out, counters), GeometryResult::rejected);
  const WorldTriangle partly_off{{world(-20, 0, 0), world(10, 0, 0), world(0, 10, 0)}};
  EXPECT_EQ(transform_triangle(partly_off, view, &out, counters), GeometryResult::accepted);
  EXPECT_EQ(counters.triangles_in, 6u);
  EXPECT_EQ(counters.triangles_accepted, 2u);
  EXPECT_EQ(counters.triangles_culled, 2u);
  EXPECT_EQ(counters.triangles_rejected, 2u);
  // Perspective: a vertex behind the eye (w <= 0) rejects the triangle.
  View perspective;
  perspective.matrix = frustum(-1, 1, -1, 1, 1, 100);
  perspective.width = perspective.height = 64;
  const WorldTriangle behind{{world(0, 0, 1), world(1, 0, -5), world(0, 1, -5)}};
  EXPECT_EQ(transform_triangle(behind, perspective, &out, counters), GeometryResult::rejected);
  // On the axis at z = -2: the centre of the screen.
  const WorldTriangle ahead{{world(0, 0, -2), world(1, 0, -2), world(0, 1, -2)}};
  ASSERT_EQ(transform_triangle(ahead, perspective, &out, counters), GeometryResult::accepted);
  EXPECT_EQ(out.v[0].x, 32 * 16);
  EXPECT_EQ(out.v[0].y, 32 * 16);
  EXPECT_EQ(out.v[1].x, 48 * 16);  // x / -z = 0.5: three quarters across
}

TEST(ClusterGeometry, MatricesComposeAsGl) {
  // A quarter turn about z takes x to y; then a translation.
  const Matrix4 m = multiply(translation(1, 2, 3), rotation(2, 0, 1));
  const float* e = m.m;
  EXPECT_FLOAT_EQ(e[0] * 1 + e[4] * 0 + e[8] * 0 + e[12], 1.0f);  // (1, 0, 0) -> (0, 1, 0) + (1, 2, 3)
  EXPECT_FLOAT_EQ(e[1] * 1 + e[5] * 0 + e[9] * 0 + e[13], 3.0f);
  EXPECT_FLOAT_EQ(e[2] * 1 + e[6] * 0 + e[10] * 0 + e[14], 3.0f);
  const Matrix4 s = scaling(2, 3, 4);
  EXPECT_FLOAT_EQ(s.m[0] * s.m[5] * s.m[10], 24.0f);
  const Matrix4 rx = rotation(0, 0, 1);  // y -> z
  EXPECT_FLOAT_EQ(rx.m[6], 1.0f);        // column 1 (y), row 2 (z)
}

// The teapot through the same path: lit at its vertices, turned so that its
// z-up data stands upright, seen in perspective; the same image whatever the
// number of stripes.
TEST(ClusterGeometry, TheTeapotGoesThroughTheSamePath) {
  const scenes::Mesh mesh = scenes::teapot_mesh(6);
  MeshArrays arrays;
  arrays.positions = mesh.positions.data();
  arrays.normals = mesh.normals.data();
  arrays.indices = mesh.indices.data();
  arrays.triangle_count = static_cast<uint32_t>(mesh.triangle_count());
  const WorldTriangle first = mesh_triangle(arrays, 0, std::array<float, 3>{1, 1, 1}.data(), Light{});
  EXPECT_EQ(first.v[1].x, mesh.positions[3 * mesh.indices[1]]);
  EXPECT_EQ(first.v[2].z, mesh.positions[3 * mesh.indices[2] + 2]);

  View view;
  view.width = 256;
  view.height = 200;
  // Upright (z up -> y up), lowered by half its height, 8 units away.
  const Matrix4 model = multiply(translation(0, -1.5f, -8), rotation(0, 0, -1));
  view.matrix = multiply(frustum(-0.64f, 0.64f, -0.5f, 0.5f, 1, 20), model);
  const float base[3] = {0.9f, 0.6f, 0.2f};
  Light light;
  light.direction[0] = 0.6f;
  light.direction[1] = 0;
  light.direction[2] = 0.8f;
  std::vector<ScreenTriangle> triangles;
  WorkCounters counters;
  for (uint32_t t = 0; t < arrays.triangle_count; ++t) {
    ScreenTriangle screen;
    if (transform_triangle(mesh_triangle(arrays, t, base, light), view, &screen, counters) == GeometryResult::accepted)
      triangles.push_back(screen);
  }
  EXPECT_EQ(counters.triangles_in, arrays.triangle_count);
  EXPECT_EQ(counters.triangles_rejected, 0u);
  EXPECT_GT(counters.triangles_culled, arrays.triangle_count / 4);
  EXPECT_GT(counters.triangles_accepted, arrays.triangle_count / 4);
  testing::Frame one(256, 200, 1);
  one.draw(triangles);
  EXPECT_GT(one.stripes[0].counters().depth_passes, 5000u);
  for (unsigned p : {4u, 7u, 100u}) {
    testing::Frame many(256, 200, p);
    many.draw(triangles);
    EXPECT_TRUE(many.bytes() == one.bytes()) << "p " << p;
  }
}

}  // namespace
}  // namespace tessera::cluster
