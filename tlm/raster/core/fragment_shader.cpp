// See fragment_shader.h.
#include "raster/core/fragment_shader.h"

#include "raster/core/fragment_operations.h"
#include "raster/core/interpolation.h"
#include "raster/datapath/fog_unit.h"
#include "raster/datapath/texture_env.h"

namespace tessera::raster {

void FragmentShader::shade(const TriangleSetup& ts, int px, int py, unorm8 coverage) {
  const int dx = px - ts.ref_x, dy = py - ts.ref_y;
  Rgba8 color = interpolated_color(ts, dx, dy, m_run.config().recip_method);
  if (m_state.has(StateFlag::texture)) {
    if (!m_sampler.sample(ts, dx, dy, color, color)) return;
  }
  // Fog after texturing, before coverage and the fragment operations.
  if (m_state.has(StateFlag::fog))
    color =
        fog_unit(m_state.fog_mode, interpolated_fog(ts, dx, dy, m_run.config().recip_method), color, m_state.fog_color)
            .color;
  if (m_state.has(StateFlag::polygon_smooth)) color.a = unorm8::from_raw(div255_round(color.a.raw * coverage.raw));

  const unsigned i = m_tile.index(px, py);
  const unorm24 depth = interpolated_depth(ts, dx, dy);
  const FragmentOperationsResult out =
      fragment_operations(m_state.operations, color, depth, m_tile.color(i), unorm24::from_raw(m_tile.depth(i)),
                          stencil8::from_raw(m_tile.stencil(i)));
  m_tile.stencil(i) = out.stencil;
  if (out.depth_write) m_tile.depth(i) = depth.raw;
  if (!out.pass) return;
  ++m_run.result().fragments_written;
  m_tile.color(i) = m_tile.quantise(out.color);
}

}  // namespace tessera::raster
