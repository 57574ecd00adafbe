// See fragment_shader.h.
#include "raster/core/fragment_shader.h"

#include <algorithm>

#include "raster/core/fragment_operations.h"
#include "raster/datapath/fog_unit.h"
#include "raster/datapath/texture_combiner.h"
#include "raster/datapath/texture_env.h"

namespace tessera::raster {

unsigned FragmentShader::shaded_colors(const TriangleSetup& ts, const int32_t* dx, const int32_t* dy,
                                       const uint32_t* coverage, unsigned count, uint32_t* rgba) {
  ShadingWorkspace& w = m_work;
  const RecipMethod method = m_run.config().recip_method;
  interpolated_colors(ts, dx, dy, count, method, w.interpolation, rgba);
  unsigned done = count;
  if (m_state.has(StateFlag::texture_units)) {
    // Every unit's texel of every fragment, fetched fragment by fragment
    // and unit by unit as the hardware issues them; then each unit's
    // environment over the batch, taking the previous unit's result and
    // the interpolated (primary) colour.
    std::copy(rgba, rgba + count, w.primary.data());
    for (unsigned u = 0; u < m_state.unit_count; ++u) m_sampler.prepare_unit(ts, u, dx, dy, count);
    for (unsigned i = 0; i < count && done == count; ++i)
      for (unsigned u = 0; u < m_state.unit_count; ++u) {
        Rgba8 texel;
        if (!m_sampler.unit_texel(u, i, texel)) {
          done = i;
          break;
        }
        w.texel[u][i] = texel.pack();
      }
    for (unsigned u = 0; u < m_state.unit_count; ++u) {
      texture_combiner_batch(m_state.unit[u].env, w.primary.data(), rgba, w.texel[u].data(), done, w.color_out.data());
      std::copy(w.color_out.data(), w.color_out.data() + done, rgba);
    }
  } else if (m_state.has(StateFlag::texture)) {
    done = m_sampler.sample(ts, dx, dy, count, rgba);
  }
  // Fog after texturing, before coverage and the fragment operations.
  if (m_state.has(StateFlag::fog)) {
    interpolated_fogs(ts, dx, dy, done, method, w.interpolation, w.fog.data());
    fog_unit_batch(m_state.fog_mode, m_state.fog_color, w.fog.data(), rgba, done,
                   {w.fog_factor.data(), w.color_out.data()});
    std::copy(w.color_out.data(), w.color_out.data() + done, rgba);
  }
  if (m_state.has(StateFlag::polygon_smooth))
    for (unsigned i = 0; i < done; ++i)
      rgba[i] = (rgba[i] & 0x00ffffffu) | div255_round((rgba[i] >> 24) * coverage[i]) << 24;
  return done;
}

unsigned FragmentShader::shade(const TriangleSetup& ts, const FragmentBatch& batch) {
  ShadingWorkspace& w = m_work;
  unsigned count = batch.size();
  // Without texturing (whose fetches count, and may fail the run) and
  // without the alpha test (which reads the colour), the tests do not
  // depend on the colour: it is computed only for the fragments that pass
  // them. The results are the same as in GL's order.
  const bool color_after_tests = !m_state.textured() && !m_state.operations.alpha_test;
  unsigned failed_at = count;
  if (!color_after_tests) {
    failed_at = shaded_colors(ts, batch.dx(), batch.dy(), batch.coverage(), count, w.color.data());
    count = failed_at;
    for (unsigned i = 0; i < count; ++i) w.alpha[i] = w.color[i] >> 24;
  } else {
    std::fill(w.alpha.data(), w.alpha.data() + count, 0u);  // not read: the alpha test is off
  }

  // The tile's depth and stencil under the fragments, run by run.
  for (unsigned r = 0; r < batch.run_count(); ++r) {
    const FragmentBatch::Run& run = batch.run(r);
    if (run.first >= count) break;
    const unsigned n = std::min(run.count, count - run.first), index = m_tile.index(run.px, run.py);
    for (unsigned k = 0; k < n; ++k) {
      w.tile_index[run.first + k] = index + k;
      w.stored_depth[run.first + k] = m_tile.depth(index + k);
      w.stored_stencil[run.first + k] = m_tile.stencil(index + k);
    }
  }
  interpolated_depths(ts, batch.dx(), batch.dy(), count, w.interpolation, w.depth.data());
  fragment_tests(m_state.operations, w.alpha.data(), w.depth.data(), w.stored_depth.data(), w.stored_stencil.data(),
                 count, w.flags.data(), w.stencil.data());

  // Stencil and depth back into the tile; the fragments that passed, in
  // order (without a branch on the tests' outcome, which is not predictable).
  unsigned passed = 0;
  for (unsigned i = 0; i < count; ++i) {
    const unsigned index = w.tile_index[i];
    m_tile.stencil(index) = uint8_t(w.stencil[i]);
    uint32_t& depth = m_tile.depth(index);
    depth = (w.flags[i] & FRAGMENT_DEPTH_WRITE) != 0 ? w.depth[i] : depth;
    w.passed[passed] = i;
    passed += (w.flags[i] & FRAGMENT_PASS) != 0 ? 1 : 0;
  }
  for (unsigned j = 0; j < passed; ++j) {
    const unsigned i = w.passed[j];
    w.passed_dx[j] = batch.dx()[i];
    w.passed_dy[j] = batch.dy()[i];
    w.passed_coverage[j] = batch.coverage()[i];
    w.stored_color[j] = m_tile.color(w.tile_index[i]);
  }
  if (color_after_tests) {
    shaded_colors(ts, w.passed_dx.data(), w.passed_dy.data(), w.passed_coverage.data(), passed, w.passed_color.data());
  } else {
    for (unsigned j = 0; j < passed; ++j) w.passed_color[j] = w.color[w.passed[j]];
  }
  fragment_color_update(m_state.operations, w.passed_color.data(), w.stored_color.data(), passed, w.written.data());
  m_tile.quantise(w.written.data(), passed);
  for (unsigned j = 0; j < passed; ++j) m_tile.color(w.tile_index[w.passed[j]]) = w.written[j];
  m_run.result().fragments_written += passed;
  return failed_at;
}

}  // namespace tessera::raster
