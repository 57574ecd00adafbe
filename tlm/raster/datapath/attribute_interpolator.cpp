// See attribute_interpolator.h for formats and rounding.
#include "attribute_interpolator.h"

namespace tessera::raster {

namespace {

constexpr int64_t word40(int64_t v) {
  return sign_extend(static_cast<uint64_t>(v), 40);
}

}  // namespace

AttributePlane attribute_plane_from_raw(AttributeKind kind, int64_t start, int64_t grad_x, int64_t grad_y) {
  return AttributePlane{kind, word40(start), word40(grad_x), word40(grad_y)};
}

attribute_sum attribute_at(const AttributePlane& plane, int dx, int dy) {
  return attribute_sum::from_raw(word40(plane.start) + word40(plane.grad_x) * dx + word40(plane.grad_y) * dy);
}

attribute_sum attribute_step_x(const AttributePlane& plane, attribute_sum value) {
  return attribute_sum::from_raw(value.raw + word40(plane.grad_x));
}

attribute_sum attribute_step_y(const AttributePlane& plane, attribute_sum value) {
  return attribute_sum::from_raw(value.raw + word40(plane.grad_y));
}

unorm8 attribute_to_color(attribute_sum value) {
  return unorm8::from_raw(static_cast<uint32_t>(clamp_i64(round_shift_right(value.raw, 16), 0, 255)));
}

unorm24 attribute_to_depth(attribute_sum value) {
  return unorm24::from_raw(static_cast<uint32_t>(clamp_i64(round_shift_right(value.raw, 8), 0, 0xffffff)));
}

q15_16 attribute_to_texcoord(attribute_sum value) {
  return q15_16{clamp_i64(round_shift_right(value.raw, 8), q15_16::MIN_RAW, q15_16::MAX_RAW)};
}

uint32_t attribute_output(AttributeKind kind, attribute_sum value) {
  switch (kind) {
    case AttributeKind::color: return attribute_to_color(value).raw;
    case AttributeKind::depth: return attribute_to_depth(value).raw;
    case AttributeKind::texcoord: return static_cast<uint32_t>(attribute_to_texcoord(value).raw);
  }
  return 0;
}

AttributeEvaluation evaluate_attribute(const AttributePlane& plane, int dx, int dy) {
  AttributeEvaluation r;
  r.value = attribute_at(plane, dx, dy);
  r.value_next_x = attribute_step_x(plane, r.value);
  r.value_next_y = attribute_step_y(plane, r.value);
  r.output = attribute_output(plane.kind, r.value);
  return r;
}

}  // namespace tessera::raster
