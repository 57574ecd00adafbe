// See fragment_shader.h.
#include "raster/core/fragment_shader.h"

#include "raster/core/fragment_operations.h"
#include "raster/core/interpolation.h"
#include "raster/datapath/fog_unit.h"
#include "raster/datapath/texture_combiner.h"
#include "raster/datapath/texture_env.h"

namespace tessera::raster {

// The fragment's colour: interpolated, textured, its alpha times the
// coverage with polygon_smooth; false when a texel fetch failed.
bool FragmentShader::shaded_color(const TriangleSetup& ts, int dx, int dy, unorm8 coverage, Rgba8& color) {
  color = interpolated_color(ts, dx, dy, m_run.config().recip_method);
  if (m_state.has(StateFlag::texture_units)) {
    // Each enabled unit in order: its texel and its environment, taking the
    // previous unit's result and the interpolated (primary) colour.
    const Rgba8 primary = color;
    for (unsigned u = 0; u < m_state.unit_count; ++u) {
      Rgba8 texel;
      if (!m_sampler.unit_texel(ts, u, dx, dy, texel)) return false;
      color = texture_combiner(m_state.unit[u].env, primary, color, texel);
    }
  } else if (m_state.has(StateFlag::texture)) {
    if (!m_sampler.sample(ts, dx, dy, color, color)) return false;
  }
  // Fog after texturing, before coverage and the fragment operations.
  if (m_state.has(StateFlag::fog))
    color =
        fog_unit(m_state.fog_mode, interpolated_fog(ts, dx, dy, m_run.config().recip_method), color, m_state.fog_color)
            .color;
  if (m_state.has(StateFlag::polygon_smooth)) color.a = unorm8::from_raw(div255_round(color.a.raw * coverage.raw));
  return true;
}

void FragmentShader::shade(const TriangleSetup& ts, int px, int py, unorm8 coverage) {
  const int dx = px - ts.ref_x, dy = py - ts.ref_y;
  // Without texturing (whose fetches count, and may fail the run) and without
  // the alpha test (which reads the colour), the tests do not depend on the
  // colour: it is computed only for the fragments that pass them. The
  // results are the same as in GL's order.
  const bool color_after_tests = !m_state.textured() && !m_state.operations.alpha_test;
  Rgba8 color;
  if (!color_after_tests && !shaded_color(ts, dx, dy, coverage, color)) return;

  const unsigned i = m_tile.index(px, py);
  const unorm24 depth = interpolated_depth(ts, dx, dy);
  const FragmentOperationsResult out = fragment_tests_only(
      m_state.operations, color.a, depth, unorm24::from_raw(m_tile.depth(i)), stencil8::from_raw(m_tile.stencil(i)));
  m_tile.stencil(i) = out.stencil;
  if (out.depth_write) m_tile.depth(i) = depth.raw;
  if (!out.pass) return;
  if (color_after_tests) shaded_color(ts, dx, dy, coverage, color);
  ++m_run.result().fragments_written;
  m_tile.color(i) = m_tile.quantise(fragment_color_update(m_state.operations, color, m_tile.color(i)));
}

}  // namespace tessera::raster
