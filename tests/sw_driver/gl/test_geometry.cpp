// Unit tests of the GL front end's geometry stage: clipping against every
// plane of the view volume, the viewport transform into 9.4 / 0.24 / 0.8,
// non-finite and out-of-range vertices, degeneracy before snapping,
// orientation, and lighting.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "gl/geometry.h"

using namespace tessera::gl;

namespace {

// A vertex whose colour's red channel carries its clip-space x and green its
// y, so that after clipping each vertex must still satisfy r == x, g == y
// (attributes are linear in clip space).
ClipVertex vertex(float x, float y, float z, float w = 1) {
  ClipVertex v;
  v.position = {x, y, z, w};
  v.color = {x, y, z, w};
  v.tex[0] = {x * 2, y * 3};
  v.tex[1] = {y - z, 4 * w};  // every unit's coordinates are clipped
  v.fog = 5 * x + 7 * w;      // the fog coordinate is clipped like the rest
  return v;
}

void expect_attributes_follow_positions(const std::vector<ClipVertex>& polygon) {
  for (const auto& v : polygon) {
    EXPECT_NEAR(v.color.r, v.position.x, 1e-5);
    EXPECT_NEAR(v.color.g, v.position.y, 1e-5);
    EXPECT_NEAR(v.color.b, v.position.z, 1e-5);
    EXPECT_NEAR(v.tex[0].x, 2 * v.position.x, 1e-5);
    EXPECT_NEAR(v.tex[0].y, 3 * v.position.y, 1e-5);
    EXPECT_NEAR(v.tex[1].x, v.position.y - v.position.z, 1e-5);
    EXPECT_NEAR(v.tex[1].y, 4 * v.position.w, 1e-5);
    EXPECT_NEAR(v.fog, 5 * v.position.x + 7 * v.position.w, 1e-4);
  }
}

void expect_inside(const std::vector<ClipVertex>& polygon) {
  for (const auto& v : polygon) {
    const glm::vec4& p = v.position;
    EXPECT_GE(p.w + p.x, -1e-5) << p.x << " " << p.w;
    EXPECT_GE(p.w - p.x, -1e-5);
    EXPECT_GE(p.w + p.y, -1e-5);
    EXPECT_GE(p.w - p.y, -1e-5);
    EXPECT_GE(p.w + p.z, -1e-5);
    EXPECT_GE(p.w - p.z, -1e-5);
  }
}

}  // namespace

TEST(Clipping, TriangleInsideIsUnchanged) {
  const std::vector<ClipVertex> in = {vertex(-0.5f, -0.5f, 0), vertex(0.5f, -0.5f, 0), vertex(0, 0.5f, 0)};
  const auto out = clip_polygon(in);
  ASSERT_EQ(out.size(), 3u);
  for (size_t i = 0; i < 3; ++i) EXPECT_EQ(out[i].position, in[i].position);
  EXPECT_TRUE(inside_view_volume(in[0]));
}

// One vertex beyond each plane in turn: the result is a quadrilateral whose
// two new vertices lie exactly on that plane.
TEST(Clipping, EachPlaneCutsOffOneCorner) {
  struct Case {
    const char* plane;
    ClipVertex outside;
    int axis;    // 0 x, 1 y, 2 z
    float sign;  // the plane is axis == sign * w
  };
  const Case cases[] = {
      {"left", vertex(-3, 0, 0), 0, -1}, {"right", vertex(3, 0, 0), 0, 1},  {"bottom", vertex(0, -3, 0), 1, -1},
      {"top", vertex(0, 3, 0), 1, 1},    {"near", vertex(0, 0, -3), 2, -1}, {"far", vertex(0, 0, 3), 2, 1},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.plane);
    // The other two vertices are inside, offset perpendicular to the axis.
    glm::vec3 a(0), b(0);
    a[(c.axis + 1) % 3] = 0.5f;
    b[(c.axis + 2) % 3] = 0.5f;
    const std::vector<ClipVertex> in = {c.outside, vertex(a.x, a.y, a.z), vertex(b.x, b.y, b.z)};
    EXPECT_FALSE(inside_view_volume(in[0]));
    const auto out = clip_polygon(in);
    ASSERT_EQ(out.size(), 4u);
    expect_inside(out);
    expect_attributes_follow_positions(out);
    int on_plane = 0;
    for (const auto& v : out) on_plane += std::fabs(v.position[c.axis] - c.sign * v.position.w) < 1e-5;
    EXPECT_EQ(on_plane, 2);
  }
}

TEST(Clipping, TriangleCrossingSeveralPlanes) {
  // A large triangle covering the whole volume's cross-section: every side
  // plane cuts it, leaving the square [-1,1]^2 at z = 0.
  const std::vector<ClipVertex> in = {vertex(-10, -10, 0), vertex(10, -10, 0), vertex(0, 10, 0)};
  const auto out = clip_polygon(in);
  ASSERT_GE(out.size(), 4u);
  expect_inside(out);
  expect_attributes_follow_positions(out);
  // The result's area is the area of the triangle inside the unit square.
  double area = 0;
  for (size_t i = 0; i < out.size(); ++i) {
    const auto& p = out[i].position;
    const auto& q = out[(i + 1) % out.size()].position;
    area += p.x * q.y - q.x * p.y;
  }
  // Inside [-1,1]^2 the triangle's edges are x = +-(10 - y)/2, i.e. |x| <= 5.5 - y/2 >= 1 for y <= 1:
  // the whole square is covered.
  EXPECT_NEAR(std::fabs(area) / 2, 4.0, 1e-4);
}

TEST(Clipping, CornerCrossingTwoPlanesAtOnce) {
  const std::vector<ClipVertex> in = {vertex(3, 3, 0), vertex(0, 0, 0), vertex(0.5f, -0.5f, 0)};
  const auto out = clip_polygon(in);
  ASSERT_GE(out.size(), 4u);
  expect_inside(out);
  expect_attributes_follow_positions(out);
}

TEST(Clipping, TriangleOutsideOrBehindTheEyeVanishes) {
  EXPECT_TRUE(clip_polygon({vertex(2, 2, 0), vertex(3, 2, 0), vertex(2, 3, 0)}).empty());
  // w <= 0 everywhere: behind the eye.
  EXPECT_TRUE(clip_polygon({vertex(0, 0, 0, -1), vertex(0.1f, 0, 0, -1), vertex(0, 0.1f, 0, -1)}).empty());
  // One vertex behind the eye: the rest is kept, with w > 0 everywhere.
  const auto out = clip_polygon({vertex(0, 0, 0, -1), vertex(0.5f, 0, 0, 1), vertex(0, 0.5f, 0, 1)});
  for (const auto& v : out) EXPECT_GT(v.position.w, 0);
}

TEST(Viewport, CentreOfTheViewportAndDepthMidpoint) {
  Viewport viewport;
  viewport.width = 320;
  viewport.height = 240;
  ScreenVertex s;
  ClipVertex v = vertex(0, 0, 0);
  v.color = {0.5f, 1.0f, 0.0f, 0.25f};
  ASSERT_TRUE(to_screen(v, viewport, &s));
  EXPECT_EQ(s.x, 160 * 16);  // 9.4: 160.0
  EXPECT_EQ(s.y, 120 * 16);
  // z_ndc 0 lies half way between near 0 and far 1: 0.5 * (2^24 - 1), rounded.
  EXPECT_EQ(s.z, 8388608u);
  EXPECT_EQ(s.r, 128);  // 127.5 rounds to nearest (half away from zero)
  EXPECT_EQ(s.g, 255);
  EXPECT_EQ(s.b, 0);
  EXPECT_EQ(s.a, 64);  // 63.75
  EXPECT_FLOAT_EQ(s.inv_w, 1.0f);
  EXPECT_FLOAT_EQ(s.fog, 7.0f);  // passed on as it is
}

TEST(Viewport, CornersAndSubpixelRounding) {
  Viewport viewport;
  viewport.x = 10;
  viewport.y = 20;
  viewport.width = 100;
  viewport.height = 50;
  viewport.near_depth = 0.25f;
  viewport.far_depth = 0.75f;
  ScreenVertex s;
  ASSERT_TRUE(to_screen(vertex(-1, -1, -1), viewport, &s));
  EXPECT_EQ(s.x, 10 * 16);
  EXPECT_EQ(s.y, 20 * 16);
  EXPECT_EQ(s.z, static_cast<uint32_t>(std::llround(0.25 * 16777215)));
  ASSERT_TRUE(to_screen(vertex(1, 1, 1), viewport, &s));
  EXPECT_EQ(s.x, 110 * 16);
  EXPECT_EQ(s.y, 70 * 16);
  EXPECT_EQ(s.z, static_cast<uint32_t>(std::llround(0.75 * 16777215)));
  // x_ndc = 0.00125 -> 60.0625 pixels = 961 sixteenths exactly; w = 2 halves it first.
  ASSERT_TRUE(to_screen(vertex(0.0025f, 0, 0, 2), viewport, &s));
  EXPECT_EQ(s.x, 961);
  EXPECT_FLOAT_EQ(s.inv_w, 0.5f);
}

TEST(Viewport, NonFiniteHugeAndOffRangeVerticesAreRejected) {
  Viewport viewport;
  viewport.width = 320;
  viewport.height = 240;
  ScreenVertex s;
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  EXPECT_FALSE(to_screen(vertex(nan, 0, 0), viewport, &s));
  EXPECT_FALSE(to_screen(vertex(0, inf, 0), viewport, &s));
  EXPECT_FALSE(to_screen(vertex(0, 0, 0, 0), viewport, &s));
  EXPECT_FALSE(to_screen(vertex(0, 0, 0, -1), viewport, &s));
  EXPECT_FALSE(to_screen(vertex(1e30f, 0, 0, 1), viewport, &s));
  // Beyond the 9.4 range (511.9375) or below 0 after the viewport transform.
  viewport.width = 2048;
  EXPECT_FALSE(to_screen(vertex(1, 0, 0), viewport, &s));
  viewport.x = -100;
  viewport.width = 100;
  EXPECT_FALSE(to_screen(vertex(-1, 0, 0), viewport, &s));
  ClipVertex bad_tex = vertex(0, 0, 0);
  bad_tex.tex[0].x = nan;
  viewport = Viewport{};
  viewport.width = viewport.height = 100;
  EXPECT_FALSE(to_screen(bad_tex, viewport, &s));
}

// A 512-pixel screen's far edge, 512.0, is one code past 9.4 (8192): the
// vertex moves to 511 15/16 (8191) instead of dropping its triangle, and
// only that code moves. A 511-pixel screen's far edge, 511.0, is 8176.
TEST(Viewport, FarEdgeOfA512PixelScreenIsKept) {
  Viewport viewport;
  viewport.width = viewport.height = 512;
  ScreenVertex s;
  ASSERT_TRUE(to_screen(vertex(1, 1, 0), viewport, &s));
  EXPECT_EQ(s.x, 8191);
  EXPECT_EQ(s.y, 8191);
  ASSERT_TRUE(to_screen(vertex(-1, -1, 0), viewport, &s));
  EXPECT_EQ(s.x, 0);
  EXPECT_EQ(s.y, 0);
  // 511.9375 is 9.4 already and stays.
  ASSERT_TRUE(to_screen(vertex(511.9375f / 256 - 1, 0, 0), viewport, &s));
  EXPECT_EQ(s.x, 8191);
  // 512.0625 (code 8193) is beyond the screen and still rejected.
  EXPECT_FALSE(to_screen(vertex(512.0625f / 256 - 1, 0, 0), viewport, &s));
  viewport.width = viewport.height = 511;
  ASSERT_TRUE(to_screen(vertex(1, 1, 0), viewport, &s));
  EXPECT_EQ(s.x, 511 * 16);
  EXPECT_EQ(s.y, 511 * 16);
}

// The float viewport transform against the exact one (in double here) on a
// 512x512 screen, the largest, and on viewports reaching past it: within
// 1e-4 pixel everywhere in the view volume (geometry.cpp's bound), so the
// 9.4 code is the exactly rounded one unless the exact coordinate is that
// close to a rounding tie. Rounding ties go to the even code, as nearbyint;
// the screen's limits are -1/32 and 512 + 1/32.
TEST(Viewport, FloatWindowCoordinatesAtTheExtremes) {
  std::mt19937 random(99);
  std::uniform_real_distribution<float> ndc(-1.0f, 1.0f), depth(0.05f, 100.0f);
  const int origins[][2] = {{0, 0}, {-256, 0}, {256, -300}, {1, 1}};
  unsigned compared = 0;
  for (const auto& origin : origins) {
    Viewport viewport;
    viewport.x = origin[0], viewport.y = origin[1];
    viewport.width = viewport.height = 512;
    for (int i = 0; i < 20000; ++i) {
      const float w = depth(random);
      const glm::vec4 clip(ndc(random) * w, ndc(random) * w, 0, w);
      WindowPoint window;
      ASSERT_TRUE(to_window(clip, viewport, &window));
      const double exact_x = (double{clip.x} / clip.w + 1) * 256 + viewport.x;
      const double exact_y = (double{clip.y} / clip.w + 1) * 256 + viewport.y;
      ASSERT_NEAR(window.x, exact_x, 1e-4) << i;
      ASSERT_NEAR(window.y, exact_y, 1e-4) << i;
      ScreenVertex s;
      ClipVertex v;
      v.position = clip;
      const double code = std::min(std::nearbyint(exact_x * 16), double{MAX_SCREEN_COORDINATE});
      const bool on_screen = exact_x >= 0 && exact_x < 512 && exact_y >= 0 && exact_y < 512;
      if (!on_screen || std::fabs(exact_x * 16 - std::floor(exact_x * 16) - 0.5) < 2e-3) continue;
      ASSERT_TRUE(to_screen(v, viewport, &s)) << i;
      EXPECT_EQ(s.x, static_cast<int32_t>(code)) << i;
      ++compared;
    }
  }
  EXPECT_GT(compared, 20000u);
  // Ties and limits on the 512-pixel screen (window = 256 x_ndc + 256, exact here).
  Viewport viewport;
  viewport.width = viewport.height = 512;
  auto code_of = [&viewport](float window, int32_t* code) {
    ScreenVertex s;
    const bool ok = to_screen(vertex((window - 256) / 256, 0, 0), viewport, &s);
    *code = s.x;
    return ok;
  };
  int32_t code = -1;
  ASSERT_TRUE(code_of(100.03125f, &code));  // 1600.5
  EXPECT_EQ(code, 1600);
  ASSERT_TRUE(code_of(100.09375f, &code));  // 1601.5
  EXPECT_EQ(code, 1602);
  ASSERT_TRUE(code_of(511.90625f, &code));  // 8190.5
  EXPECT_EQ(code, 8190);
  ASSERT_TRUE(code_of(511.96875f, &code));  // 8191.5: 8192, the far edge, kept as 8191
  EXPECT_EQ(code, 8191);
  ASSERT_TRUE(code_of(512.03125f, &code));  // 8192.5: the last one kept
  EXPECT_EQ(code, 8191);
  EXPECT_FALSE(code_of(512.0313f, &code));
  ASSERT_TRUE(code_of(0.03125f, &code));  // 0.5
  EXPECT_EQ(code, 0);
  ASSERT_TRUE(code_of(0.09375f, &code));  // 1.5
  EXPECT_EQ(code, 2);
  ASSERT_TRUE(code_of(-0.03125f, &code));  // -0.5: the first one kept
  EXPECT_EQ(code, 0);
  EXPECT_FALSE(code_of(-0.0313f, &code));
}

TEST(Viewport, SignedAreaIsPositiveCounterClockwise) {
  ScreenVertex a{}, b{}, c{};
  a.x = 0, a.y = 0;
  b.x = 160, b.y = 0;
  c.x = 0, c.y = 160;
  EXPECT_EQ(signed_area(a, b, c), 160 * 160);
  EXPECT_EQ(signed_area(a, c, b), -160 * 160);
  EXPECT_EQ(signed_area(a, a, c), 0);
}

// Three vertices on the line y = x / 2 (exact in float: halving only moves
// the exponent) lie on one line in window coordinates too, but snapping
// each to 1/16 pixel moves them off it.
TEST(Degeneracy, CollinearVerticesHaveNoAreaBeforeSnappingButSomeAfter) {
  Viewport viewport;
  viewport.width = 320;
  viewport.height = 240;
  std::vector<WindowPoint> window(3);
  ScreenVertex screen[3];
  const float xs[3] = {-0.9f, 0.13f, 0.77f};
  for (int i = 0; i < 3; ++i) {
    ASSERT_TRUE(to_window(vertex(xs[i], xs[i] * 0.5f, 0).position, viewport, &window[i]));
    ASSERT_TRUE(to_screen(vertex(xs[i], xs[i] * 0.5f, 0), viewport, &screen[i]));
  }
  EXPECT_TRUE(is_degenerate(window));
  EXPECT_NE(signed_area(screen[0], screen[1], screen[2]), 0) << "snapping no longer moves these off their line";
}

TEST(Degeneracy, HeightAcrossTheLongestEdgeAgainstAQuarterOfTheSnappingStep) {
  auto triangle = [](float height) { return std::vector<WindowPoint>{{10, 10}, {110, 10}, {40, 10 + height}}; };
  EXPECT_TRUE(is_degenerate(triangle(0)));
  EXPECT_TRUE(is_degenerate(triangle(DEGENERATE_HEIGHT / 2)));
  EXPECT_FALSE(is_degenerate(triangle(DEGENERATE_HEIGHT * 2)));
  EXPECT_FALSE(is_degenerate(triangle(-0.5f)));  // either winding
  // A needle: long, with its third vertex off the line by less than the limit.
  EXPECT_TRUE(is_degenerate({{0, 0}, {400, 300}, {200, 150.005f}}));
  // Fewer than three vertices, or all in one place.
  EXPECT_TRUE(is_degenerate({{0, 0}, {5, 5}}));
  EXPECT_TRUE(is_degenerate({{3, 3}, {3, 3}, {3, 3}}));
  // A clipped polygon: a unit square is not degenerate, a flattened one is.
  EXPECT_FALSE(is_degenerate({{0, 0}, {1, 0}, {1, 1}, {0, 1}}));
  EXPECT_TRUE(is_degenerate({{0, 0}, {1, 0}, {2, 0.001f}, {0.5f, 0.0005f}}));
}

// The float test at the extremes of a 512x512 screen: slivers whose height
// is 5 % off DEGENERATE_HEIGHT either way across the longest edges there are
// (the full width, the diagonal of 724 pixels), at the screen's far corner
// too, where float's steps are coarsest (geometry.cpp bounds the error by
// 2 % of the limit).
TEST(Degeneracy, SliversAtTheThresholdOnA512PixelScreen) {
  const float below = DEGENERATE_HEIGHT * 0.95f, above = DEGENERATE_HEIGHT * 1.05f;
  for (const float y : {0.0f, 511.0f}) {
    EXPECT_TRUE(is_degenerate({{0, y}, {512, y}, {256, y + below}})) << y;
    EXPECT_FALSE(is_degenerate({{0, y}, {512, y}, {256, y + above}})) << y;
    EXPECT_TRUE(is_degenerate({{0, y}, {512, y}, {511.9375f, y - below}})) << y;
    EXPECT_FALSE(is_degenerate({{0, y}, {512, y}, {511.9375f, y - above}})) << y;
  }
  // The diagonal: the third vertex off its middle by h across it.
  const float step = 1.0f / std::sqrt(2.0f);
  for (const float along : {1.0f, 256.0f, 511.0f}) {
    EXPECT_TRUE(is_degenerate({{0, 0}, {512, 512}, {along - below * step, along + below * step}})) << along;
    EXPECT_FALSE(is_degenerate({{0, 0}, {512, 512}, {along - above * step, along + above * step}})) << along;
  }
  // Collinear vertices of the far corner's lines stay degenerate, and a
  // polygon of the whole screen, clipped to many vertices, is not.
  EXPECT_TRUE(is_degenerate({{511.9375f, 0}, {0, 511.9375f}, {255.96875f, 255.96875f}}));
  EXPECT_TRUE(is_degenerate({{0, 0}, {512, 512}, {511.9375f, 511.9375f}, {0.0625f, 0.0625f}}));
  EXPECT_FALSE(is_degenerate({{0, 0}, {512, 0}, {512, 512}, {0, 512}}));
}

// The integer shortcut may only vouch for triangles the unsnapped test
// keeps: random triangles, many of them thin, in a 320x240 viewport.
TEST(Degeneracy, IntegerShortcutNeverVouchesForADegenerateTriangle) {
  Viewport viewport;
  viewport.width = 320;
  viewport.height = 240;
  std::mt19937 random(1234);
  std::uniform_real_distribution<float> coordinate(-1.0f, 1.0f), thickness(-0.002f, 0.002f);
  unsigned vouched = 0, degenerate = 0;
  for (int i = 0; i < 20000; ++i) {
    // Two free vertices and a third near (or on) the line through them.
    const glm::vec2 p0(coordinate(random), coordinate(random)), p1(coordinate(random), coordinate(random));
    const float along = (coordinate(random) + 1) * 0.5f;
    const glm::vec2 p2 =
        p0 + (p1 - p0) * along + glm::vec2(-(p1 - p0).y, (p1 - p0).x) * (i % 2 ? thickness(random) : 0);
    std::vector<WindowPoint> window(3);
    ScreenVertex screen[3];
    const glm::vec2 points[3] = {p0, p1, p2};
    bool ok = true;
    for (int k = 0; k < 3; ++k) {
      ok = ok && to_window({points[k], 0, 1}, viewport, &window[k]) &&
           to_screen(vertex(points[k].x, points[k].y, 0), viewport, &screen[k]);
    }
    if (!ok) continue;
    const bool is_flat = is_degenerate(window);
    degenerate += is_flat;
    if (surely_has_area(screen[0], screen[1], screen[2])) {
      ++vouched;
      EXPECT_FALSE(is_flat) << "triangle " << i;
    }
  }
  EXPECT_GT(degenerate, 1000u);
  EXPECT_GT(vouched, 2000u);
  // An ordinary triangle takes the shortcut; collinear vertices never do.
  ScreenVertex a{}, b{}, c{};
  a.x = 0, a.y = 0, b.x = 160, b.y = 0, c.x = 0, c.y = 160;
  EXPECT_TRUE(surely_has_area(a, b, c));
  c.x = 320, c.y = 0;
  EXPECT_FALSE(surely_has_area(a, b, c));
}

TEST(FixedPoint, Unorm8AndUnorm24Clamp) {
  EXPECT_EQ(to_unorm8(-1), 0);
  EXPECT_EQ(to_unorm8(std::numeric_limits<float>::quiet_NaN()), 0);
  EXPECT_EQ(to_unorm8(2), 255);
  EXPECT_EQ(to_unorm8(1.0f / 255), 1);
  EXPECT_EQ(to_unorm24(1), 16777215u);
  EXPECT_EQ(to_unorm24(0), 0u);
  EXPECT_EQ(to_unorm24(1.0f / 16777215), 1u);
}

// to_unorm24 rounds value * (2^24 - 1) exactly (in integers): the reference
// is that product in double, which holds it exactly (24 + 24 bits), rounded
// half away from zero. Every float step near 1 and near 1/2, random values,
// and the tiny ones.
TEST(FixedPoint, Unorm24IsTheExactlyRoundedProduct) {
  auto reference = [](float value) { return static_cast<uint32_t>(std::llround(double{value} * 16777215.0)); };
  std::vector<float> values;
  values.reserve(200000);
  float v = 1.0f;
  for (int i = 0; i < 100000; ++i) values.push_back(v = std::nextafter(v, 0.0f));
  v = 0.5f;
  for (int i = 0; i < 100000; ++i) values.push_back(v = std::nextafter(v, 1.0f));
  std::mt19937 random(7);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  for (int i = 0; i < 100000; ++i) values.push_back(unit(random));
  for (const float tiny : {1e-7f, 2.9802322e-8f, 2.9802326e-8f, 1e-12f, 1e-30f, 1e-45f}) values.push_back(tiny);
  for (const float value : values) ASSERT_EQ(to_unorm24(value), reference(value)) << value;
}

TEST(Lighting, DirectionalDiffuseAmbientAndSpecular) {
  LightingModel model;
  model.lights.resize(8);
  Light& light = model.lights[0];
  light.enabled = true;
  light.diffuse = glm::vec4(1);
  light.specular = glm::vec4(1);
  light.position = {0, 0, 1, 0};
  Material material;  // GL defaults: ambient 0.2, diffuse 0.8, no specular
  const glm::vec4 eye(0, 0, -5, 1);
  // Facing the light: emission 0 + 0.2 * 0.2 (scene ambient) + 0.8 * 1 (diffuse).
  glm::vec4 c = light_vertex(model, material, eye, {0, 0, 1});
  EXPECT_NEAR(c.r, 0.84f, 1e-5);
  EXPECT_NEAR(c.a, 1.0f, 1e-6);  // alpha: the material's diffuse alpha, 1 by default
  // At 60 degrees: n.l = 0.5.
  c = light_vertex(model, material, eye, {std::sqrt(3.0f) / 2, 0, 0.5f});
  EXPECT_NEAR(c.g, 0.04f + 0.4f, 1e-5);
  // Facing away: ambient only.
  c = light_vertex(model, material, eye, {0, 0, -1});
  EXPECT_NEAR(c.b, 0.04f, 1e-6);
  // Specular with shininess 8: half vector between l = +z and the viewer
  // (+z) is +z, n.h = 1 for n = +z, so the full specular adds and clamps.
  material.specular = {0.5f, 0.5f, 0.5f, 1};
  material.shininess = 8;
  c = light_vertex(model, material, eye, {0, 0, 1});
  EXPECT_NEAR(c.r, 1.0f, 1e-6);  // 0.84 + 0.5, clamped
  // Off-axis: n.l = cos 30 deg, half vector is +z, n.h = cos 30, power 8.
  const glm::vec3 n(0.5f, 0, std::sqrt(3.0f) / 2);
  c = light_vertex(model, material, eye, n);
  const float expected = 0.04f + 0.8f * n.z + 0.5f * std::pow(n.z, 8.0f);
  EXPECT_NEAR(c.r, expected, 1e-5);
}

TEST(Lighting, PositionalLightAttenuatesAndSpotCutsOff) {
  LightingModel model;
  model.ambient = glm::vec4(0);
  model.lights.resize(8);
  Light& light = model.lights[1];
  light.enabled = true;
  light.diffuse = glm::vec4(1);
  light.position = {0, 0, 0, 1};  // at the eye
  light.constant_attenuation = 1;
  light.linear_attenuation = 0.5f;
  Material material;
  material.ambient = glm::vec4(0);
  material.diffuse = glm::vec4(1);
  // A surface 2 units in front of the light facing it: 1 / (1 + 0.5 * 2) = 0.5.
  glm::vec4 c = light_vertex(model, material, {0, 0, -2, 1}, {0, 0, 1});
  EXPECT_NEAR(c.r, 0.5f, 1e-5);
  // A 10-degree spot pointing down -z: a point off to the side is dark.
  light.spot_direction = {0, 0, -1};
  light.spot_cutoff = 10;
  c = light_vertex(model, material, {2, 0, -2, 1}, glm::normalize(glm::vec3(-1, 0, 1)));
  EXPECT_NEAR(c.r, 0.0f, 1e-6);
  // On the axis it is lit as before (exponent 0).
  c = light_vertex(model, material, {0, 0, -2, 1}, {0, 0, 1});
  EXPECT_NEAR(c.r, 0.5f, 1e-5);
}

TEST(Lighting, DisabledLightsContributeNothing) {
  LightingModel model;
  model.lights.resize(8);
  model.lights[3].diffuse = glm::vec4(1);  // not enabled
  Material material;
  material.emission = {0.1f, 0.2f, 0.3f, 1};
  const glm::vec4 c = light_vertex(model, material, {0, 0, -1, 1}, {0, 0, 1});
  EXPECT_NEAR(c.r, 0.1f + 0.04f, 1e-6);
  EXPECT_NEAR(c.g, 0.2f + 0.04f, 1e-6);
  EXPECT_NEAR(c.b, 0.3f + 0.04f, 1e-6);
}

// User clip planes, polygon offset and lighting of ES 1.1 -------------------

namespace {

// A vertex whose eye coordinates equal its clip coordinates (identity
// projection), with a colour to follow through the clipper.
ClipVertex eye_vertex(float x, float y, glm::vec4 color) {
  ClipVertex v;
  v.position = v.eye = {x, y, 0, 1};
  v.color = v.back_color = color;
  for (glm::vec2& st : v.tex) st = {0, 0};
  return v;
}

}  // namespace

TEST(UserClipPlanes, CutAPolygonInEyeSpace) {
  // The triangle (-1, 0), (1, 0), (1, 1) against x >= 0: the edge
  // (-1, 0)-(1, 0) crosses at (0, 0) half way, the edge (1, 1)-(-1, 0) at
  // (0, 0.5) half way; what remains is (0, 0), (1, 0), (1, 1), (0, 0.5).
  const std::vector<ClipVertex> triangle = {eye_vertex(-1, 0, {1, 0, 0, 1}), eye_vertex(1, 0, {0, 1, 0, 1}),
                                            eye_vertex(1, 1, {0, 0, 1, 1})};
  const std::vector<ClipVertex> clipped = clip_polygon(triangle, {glm::vec4(1, 0, 0, 0)});
  ASSERT_EQ(clipped.size(), 4u);
  int crossings = 0;
  for (const ClipVertex& v : clipped) {
    EXPECT_GE(v.eye.x, 0);
    EXPECT_EQ(v.eye, v.position);  // eye coordinates are interpolated with the rest
    if (v.eye.x == 0 && v.eye.y == 0) {
      // Half way from red to green.
      EXPECT_NEAR(v.color.r, 0.5f, 1e-6);
      EXPECT_NEAR(v.color.g, 0.5f, 1e-6);
      EXPECT_NEAR(v.back_color.r, 0.5f, 1e-6);
      ++crossings;
    }
    if (v.eye.x == 0 && std::fabs(v.eye.y - 0.5f) < 1e-6f) {
      // Half way from blue to red.
      EXPECT_NEAR(v.color.r, 0.5f, 1e-6);
      EXPECT_NEAR(v.color.b, 0.5f, 1e-6);
      ++crossings;
    }
  }
  EXPECT_EQ(crossings, 2);
  // Two planes that leave nothing between them.
  EXPECT_TRUE(clip_polygon(triangle, {glm::vec4(1, 0, 0, -2), glm::vec4(-1, 0, 0, 0)}).empty());
  // No planes: clip_polygon of the view volume alone.
  EXPECT_EQ(clip_polygon(triangle, {}).size(), 3u);
  EXPECT_TRUE(inside_user_planes(triangle[1], {glm::vec4(1, 0, 0, 0)}));
  EXPECT_FALSE(inside_user_planes(triangle[0], {glm::vec4(1, 0, 0, 0)}));
}

TEST(UserClipPlanes, CutASegment) {
  // Keep z <= -2 ((0, 0, -1, -2)): from z = -1 to z = -5 the value runs
  // from -1 to 3 and crosses 0 a quarter of the way.
  float t0 = -1, t1 = -1;
  ASSERT_TRUE(clip_segment({0, 0, -1, 1}, {0, 0, -5, 1}, {glm::vec4(0, 0, -1, -2)}, &t0, &t1));
  EXPECT_FLOAT_EQ(t0, 0.25f);
  EXPECT_FLOAT_EQ(t1, 1.0f);
  // And x <= 0.5 on a segment from x = 0 to 1 at the same time: ends half way.
  ASSERT_TRUE(
      clip_segment({0, 0, -1, 1}, {1, 0, -5, 1}, {glm::vec4(0, 0, -1, -2), glm::vec4(-1, 0, 0, 0.5f)}, &t0, &t1));
  EXPECT_FLOAT_EQ(t0, 0.25f);
  EXPECT_FLOAT_EQ(t1, 0.5f);
  // Both ends outside, or the inside parts of two planes disjoint: nothing.
  EXPECT_FALSE(clip_segment({0, 0, -1, 1}, {0, 0, -1.5f, 1}, {glm::vec4(0, 0, -1, -2)}, &t0, &t1));
  EXPECT_FALSE(
      clip_segment({0, 0, 0, 1}, {1, 0, 0, 1}, {glm::vec4(1, 0, 0, -0.75f), glm::vec4(-1, 0, 0, 0.25f)}, &t0, &t1));
}

TEST(PolygonOffset, SlopeOfThePlaneInWindowCoordinates) {
  // z = 0.05 x + 0.01 y: at (0, 0) 0, at (10, 0) 0.5, at (0, 20) 0.2.
  // Single precision: within a few float steps of the exact slope.
  EXPECT_NEAR(depth_slope({{0, 0, 0}, {10, 0, 0.5f}, {0, 20, 0.2f}}), 0.05, 1e-8);
  // The same plane as a quadrilateral, and wound the other way.
  EXPECT_NEAR(depth_slope({{0, 0, 0}, {0, 20, 0.2f}, {10, 20, 0.7f}, {10, 0, 0.5f}}), 0.05, 1e-8);
  // Steeper in y: z = -0.3 y.
  EXPECT_NEAR(depth_slope({{0, 0, 0.5f}, {4, 0, 0.5f}, {0, 1, 0.2f}}), 0.3, 1e-7);
  // Constant depth, and a polygon seen edge-on (no area in x, y).
  EXPECT_EQ(depth_slope({{0, 0, 0.5f}, {4, 0, 0.5f}, {0, 1, 0.5f}}), 0);
  EXPECT_EQ(depth_slope({{0, 0, 0.1f}, {4, 0, 0.5f}, {8, 0, 0.9f}}), 0);
  // At the far corner of a 512x512 screen, where float's steps are
  // coarsest, the slope is taken relative to the first vertex: the same
  // plane, z = 0.05 x + 0.01 y shifted, as at the origin.
  EXPECT_NEAR(depth_slope({{500, 490, 0}, {510, 490, 0.5f}, {500, 510, 0.2f}}), 0.05, 1e-7);
  // A sliver across the whole screen, 1/32 pixel high (just above the
  // degeneracy limit): z = x / 1024 along it, dz/dy = 1 across it.
  const float h = 1.0f / 32;
  EXPECT_NEAR(depth_slope({{0, 0, 0}, {512, 0, 0.5f}, {256, h, 0.25f + h}}), 1.0, 1e-3);
}

TEST(PolygonOffset, UnitsAreTheDepthBuffersSmallestStep) {
  EXPECT_FLOAT_EQ(minimum_resolvable_depth(16), 1.0f / 65535);
  EXPECT_FLOAT_EQ(minimum_resolvable_depth(24), 1.0f / 16777215);
  EXPECT_FLOAT_EQ(minimum_resolvable_depth(0), 1.0f / 16777215);
  EXPECT_FLOAT_EQ(polygon_depth_offset(0.05f, 2, 3, 16), 0.1f + 3.0f / 65535);
  EXPECT_FLOAT_EQ(polygon_depth_offset(0.05f, -1, -1, 24), -0.05f - 1.0f / 16777215);
}

TEST(PolygonOffset, OffsetDepthIsClampedToTheDepthRange) {
  Viewport viewport;
  viewport.width = 64, viewport.height = 48;
  viewport.near_depth = 0.2f, viewport.far_depth = 0.6f;
  const ClipVertex v = vertex(0, 0, 0);  // NDC z 0: window depth 0.4
  EXPECT_NEAR(window_depth(v.position, viewport), 0.4, 1e-7);
  ScreenVertex s{};
  ASSERT_TRUE(to_screen(v, viewport, 0.1f, &s));
  EXPECT_EQ(s.z, to_unorm24(0.5f));
  ASSERT_TRUE(to_screen(v, viewport, 0.5f, &s));
  EXPECT_EQ(s.z, to_unorm24(0.6f));
  ASSERT_TRUE(to_screen(v, viewport, -0.5f, &s));
  EXPECT_EQ(s.z, to_unorm24(0.2f));
}

TEST(Lighting, SpotLightsAndAttenuation) {
  LightingModel model;
  model.ambient = {0, 0, 0, 1};
  model.lights.resize(8);
  Material material;
  material.ambient = {0, 0, 0, 1};  // only the diffuse term: 0.8 per unit of n.l
  Light& light = model.lights[7];   // any of the eight
  light.enabled = true;
  light.diffuse = {1, 1, 1, 1};
  light.position = {0, 0, 0, 1};
  // Attenuation 1 / (1 + 0.5 d) at d = 2: 0.5; n.l = 1: 0.8 * 0.5 = 0.4.
  light.linear_attenuation = 0.5f;
  EXPECT_NEAR(light_vertex(model, material, {0, 0, -2, 1}, {0, 0, 1}).r, 0.4f, 1e-6);
  // Quadratic: 1 / (1 + 0.25 * 4) = 0.5 as well.
  light.linear_attenuation = 0, light.quadratic_attenuation = 0.25f;
  EXPECT_NEAR(light_vertex(model, material, {0, 0, -2, 1}, {0, 0, 1}).r, 0.4f, 1e-6);
  light.quadratic_attenuation = 0;
  // A spot light down -z with a 30-degree cutoff and exponent 2: on the
  // axis the spot factor is 1; at 20 degrees off it cos(20)^2; at 45
  // degrees the vertex is outside the cone and gets nothing.
  light.spot_direction = {0, 0, -1};
  light.spot_cutoff = 30, light.spot_exponent = 2;
  const float pi = std::acos(-1.0f);
  const float angle = 20 * pi / 180;
  const glm::vec4 off_axis{std::sin(angle), 0, -std::cos(angle), 1};
  const glm::vec3 facing_light = -glm::vec3(off_axis);  // n.l = 1
  EXPECT_NEAR(light_vertex(model, material, {0, 0, -2, 1}, {0, 0, 1}).r, 0.8f, 1e-6);
  EXPECT_NEAR(light_vertex(model, material, off_axis, facing_light).r, 0.8f * std::pow(std::cos(angle), 2.0f), 1e-5);
  EXPECT_EQ(light_vertex(model, material, {2, 0, -2, 1}, glm::normalize(glm::vec3(-1, 0, 1))).r, 0);
  // A directional light is not attenuated; its spot factor takes the
  // light's direction, -position: from +x, (-1, 0, 0) against the spot
  // direction (0, 0, -1) is 90 degrees off, outside the 30-degree cone.
  light.position = {1, 0, 0, 0};
  light.linear_attenuation = 3;
  EXPECT_EQ(light_vertex(model, material, {0, 0, -2, 1}, {1, 0, 0}).r, 0);
  light.spot_direction = {-1, 0, 0};  // on the cone's axis: spot factor 1
  EXPECT_NEAR(light_vertex(model, material, {0, 0, -2, 1}, {1, 0, 0}).r, 0.8f, 1e-6);
}
