// See edge_function.h for formats, rounding and the fill rule.
#include "edge_function.h"

namespace tessera::raster {

namespace {

constexpr int64_t pixel_centre_code(unsigned p) {
  return int64_t{16} * p + 8;
}

}  // namespace

edge_delta edge_dx(const Edge& e) {
  return edge_delta::from_raw(int64_t{e.x1.raw} - e.x0.raw);
}

edge_delta edge_dy(const Edge& e) {
  return edge_delta::from_raw(int64_t{e.y1.raw} - e.y0.raw);
}

q10_4 edge_l1_length(const Edge& e) {
  const int64_t dx = edge_dx(e).raw;
  const int64_t dy = edge_dy(e).raw;
  return q10_4::from_raw(static_cast<uint32_t>((dx < 0 ? -dx : dx) + (dy < 0 ? -dy : dy)));
}

edge_value edge_value_at(const Edge& e, unsigned px, unsigned py) {
  const int64_t rel_x = pixel_centre_code(px) - e.x0.raw;
  const int64_t rel_y = pixel_centre_code(py) - e.y0.raw;
  return edge_value::from_raw(rel_x * edge_dy(e).raw - rel_y * edge_dx(e).raw);
}

edge_value edge_step_x(const Edge& e, edge_value value) {
  return edge_value::from_raw(value.raw + 16 * edge_dy(e).raw);
}

edge_value edge_step_y(const Edge& e, edge_value value) {
  return edge_value::from_raw(value.raw - 16 * edge_dx(e).raw);
}

bool edge_inside(const Edge& e, edge_value value) {
  if (value.raw != 0) {
    return value.raw > 0;
  }
  const int64_t dx = edge_dx(e).raw;
  const int64_t dy = edge_dy(e).raw;
  return dy > 0 || (dy == 0 && dx < 0);
}

edge_distance edge_normalised_distance(edge_value value, q5_16 recip) {
  const int64_t product = value.raw * static_cast<int64_t>(recip.raw);
  const int64_t rounded = round_shift_right(product, 16);
  return edge_distance{clamp_i64(rounded, edge_distance::MIN_RAW, edge_distance::MAX_RAW)};
}

unorm8 edge_coverage(edge_distance distance) {
  const int64_t t = clamp_i64(distance.raw + 128, 0, 256);
  return unorm8::from_raw(static_cast<uint32_t>((255 * t + 128) >> 8));
}

unorm8 triangle_coverage(unorm8 c0, unorm8 c1, unorm8 c2) {
  return unorm8{std::min({c0.raw, c1.raw, c2.raw})};
}

EdgeEvaluation evaluate_edge(const Edge& e, unsigned px, unsigned py, q5_16 recip) {
  EdgeEvaluation r;
  r.value = edge_value_at(e, px, py);
  r.value_next_x = edge_step_x(e, r.value);
  r.value_next_y = edge_step_y(e, r.value);
  r.inside = edge_inside(e, r.value);
  r.l1_length = edge_l1_length(e);
  r.distance = edge_normalised_distance(r.value, recip);
  r.coverage = edge_coverage(r.distance);
  return r;
}

}  // namespace tessera::raster
