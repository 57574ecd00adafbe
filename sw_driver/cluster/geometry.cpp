#include "cluster/geometry.h"

namespace tessera::cluster {

Matrix4 multiply(const Matrix4& a, const Matrix4& b) {
  Matrix4 out;
  for (int column = 0; column < 4; ++column) {
    for (int row = 0; row < 4; ++row) {
      float sum = 0;
      for (int k = 0; k < 4; ++k) sum += a.m[k * 4 + row] * b.m[column * 4 + k];
      out.m[column * 4 + row] = sum;
    }
  }
  return out;
}

Matrix4 translation(float x, float y, float z) {
  Matrix4 out;
  out.m[12] = x;
  out.m[13] = y;
  out.m[14] = z;
  return out;
}

Matrix4 scaling(float x, float y, float z) {
  Matrix4 out;
  out.m[0] = x;
  out.m[5] = y;
  out.m[10] = z;
  return out;
}

Matrix4 rotation(int axis, float cosine, float sine) {
  Matrix4 out;
  const int a = (axis + 1) % 3, b = (axis + 2) % 3;  // the plane turned: y z, z x or x y
  out.m[a * 4 + a] = cosine;
  out.m[b * 4 + b] = cosine;
  out.m[a * 4 + b] = sine;  // column a, row b
  out.m[b * 4 + a] = -sine;
  return out;
}

Matrix4 orthographic(float left, float right, float bottom, float top, float near, float far) {
  Matrix4 out;
  out.m[0] = 2 / (right - left);
  out.m[5] = 2 / (top - bottom);
  out.m[10] = -2 / (far - near);
  out.m[12] = -(right + left) / (right - left);
  out.m[13] = -(top + bottom) / (top - bottom);
  out.m[14] = -(far + near) / (far - near);
  return out;
}

Matrix4 frustum(float left, float right, float bottom, float top, float near, float far) {
  Matrix4 out;
  out.m[0] = 2 * near / (right - left);
  out.m[5] = 2 * near / (top - bottom);
  out.m[8] = (right + left) / (right - left);
  out.m[9] = (top + bottom) / (top - bottom);
  out.m[10] = -(far + near) / (far - near);
  out.m[11] = -1;
  out.m[14] = -2 * far * near / (far - near);
  out.m[15] = 0;
  return out;
}

namespace {

constexpr float GUARD_PIXELS = 1023.0f;  // MAX_COORDINATE / 16, rounded down

int32_t round_to_int(float f) {
  return static_cast<int32_t>(f >= 0 ? f + 0.5f : f - 0.5f);
}

uint8_t to_unorm8(float c) {
  if (!(c > 0)) return 0;  // also NaN
  if (c >= 1) return 255;
  return static_cast<uint8_t>(round_to_int(c * 255.0f));
}

// False when the vertex is behind the eye, outside the depth range or the
// guard band (comparisons written so that NaN fails them).
bool project(const WorldVertex& in, const View& view, ScreenVertex* out) {
  const float* m = view.matrix.m;
  const float cx = m[0] * in.x + m[4] * in.y + m[8] * in.z + m[12];
  const float cy = m[1] * in.x + m[5] * in.y + m[9] * in.z + m[13];
  const float cz = m[2] * in.x + m[6] * in.y + m[10] * in.z + m[14];
  const float cw = m[3] * in.x + m[7] * in.y + m[11] * in.z + m[15];
  if (!(cw > 0)) return false;
  const float inverse_w = 1.0f / cw;
  const float sx = (cx * inverse_w + 1.0f) * 0.5f * static_cast<float>(view.width);
  const float sy = (1.0f - cy * inverse_w) * 0.5f * static_cast<float>(view.height);  // y down
  const float depth = (cz * inverse_w + 1.0f) * 0.5f;
  if (!(sx > -GUARD_PIXELS && sx < GUARD_PIXELS && sy > -GUARD_PIXELS && sy < GUARD_PIXELS)) return false;
  if (!(depth >= 0.0f && depth <= 1.0f)) return false;
  out->x = round_to_int(sx * SUBPIXEL_ONE);
  out->y = round_to_int(sy * SUBPIXEL_ONE);
  out->z = static_cast<uint32_t>(round_to_int(depth * static_cast<float>(MAX_DEPTH)));
  if (out->z > MAX_DEPTH) out->z = MAX_DEPTH;
  out->r = to_unorm8(in.r);
  out->g = to_unorm8(in.g);
  out->b = to_unorm8(in.b);
  return true;
}

}  // namespace

GeometryResult transform_triangle(const WorldTriangle& triangle, const View& view, ScreenTriangle* out,
                                  WorkCounters& counters) {
  ++counters.triangles_in;
  ScreenTriangle screen;
  for (int k = 0; k < 3; ++k) {
    if (!project(triangle.v[k], view, &screen.v[k])) {
      ++counters.triangles_rejected;
      return GeometryResult::rejected;
    }
  }
  // With y down, a triangle counter-clockwise as GL sees it (y up) turns
  // clockwise: twice its signed area (x1 - x0)(y2 - y0) - (y1 - y0)(x2 - x0)
  // is negative. |.| < 2^31 within the guard band.
  const ScreenVertex* v = screen.v;
  const int64_t area = int64_t{v[1].x - v[0].x} * (v[2].y - v[0].y) - int64_t{v[1].y - v[0].y} * (v[2].x - v[0].x);
  if (area >= 0) {
    ++counters.triangles_culled;
    return GeometryResult::culled;
  }
  ++counters.triangles_accepted;
  *out = screen;
  return GeometryResult::accepted;
}

}  // namespace tessera::cluster
