// The double-precision reference (eq3_reference.h).
#include "forward_texture/eq3_reference.h"

#include <algorithm>
#include <cmath>

namespace tessera::test::forward_texture {

namespace {

constexpr double XY_SCALE = 1048576.0;    // 2^20: q12_20
constexpr double W_SCALE = 1073741824.0;  // 2^30: q2_30

Matrix with_u_and_v_swapped(const Matrix& m) {
  return {m.b, m.a, m.c, m.e, m.d, m.f, m.h, m.g, m.i};
}

std::vector<double> transposed(const std::vector<double>& image, int width, int height) {
  std::vector<double> t(image.size());
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      t[static_cast<std::size_t>(x) * height + y] = image[static_cast<std::size_t>(y) * width + x];
    }
  }
  return t;
}

std::vector<double> rows_first(const std::vector<double>& texture, int texture_width, int texture_height,
                               const Matrix& m, FilterKind kind, int width, int output_width, int output_height) {
  std::vector<double> intermediate(static_cast<std::size_t>(output_width) * texture_height);
  for (int row = 0; row < texture_height; ++row) {
    const std::vector<double> texels(texture.begin() + row * texture_width,
                                     texture.begin() + (row + 1) * texture_width);
    const std::vector<double> pixels =
        resample_line_eq3(texels, row_borders(m, row, texture_width), kind, width, output_width);
    std::copy(pixels.begin(), pixels.end(), intermediate.begin() + row * output_width);
  }
  std::vector<double> output(static_cast<std::size_t>(output_width) * output_height);
  for (int column = 0; column < output_width; ++column) {
    const std::vector<double> borders = column_borders(m, column, texture_height);
    if (borders.empty()) {
      continue;
    }
    std::vector<double> texels(static_cast<std::size_t>(texture_height));
    for (int row = 0; row < texture_height; ++row) {
      texels[static_cast<std::size_t>(row)] = intermediate[static_cast<std::size_t>(row) * output_width + column];
    }
    const std::vector<double> pixels = resample_line_eq3(texels, borders, kind, width, output_height);
    for (int y = 0; y < output_height; ++y) {
      output[static_cast<std::size_t>(y) * output_width + column] = pixels[static_cast<std::size_t>(y)];
    }
  }
  return output;
}

}  // namespace

Matrix to_double(const PerspectiveMatrix& m) {
  return {m.a / XY_SCALE, m.b / XY_SCALE, m.c / XY_SCALE, m.d / XY_SCALE, m.e / XY_SCALE,
          m.f / XY_SCALE, m.g / W_SCALE,  m.h / W_SCALE,  m.i / W_SCALE};
}

double filter_primitive(FilterKind kind, int width, double z) {
  const double w = std::clamp(z / width + 0.5, 0.0, 1.0);  // position across the support
  if (kind == FilterKind::box) {
    return w;
  }
  return w <= 0.5 ? 2.0 * w * w : 1.0 - 2.0 * (1.0 - w) * (1.0 - w);
}

double filter_peak(FilterKind kind, int width) {
  return (kind == FilterKind::box ? 1.0 : 2.0) / width;
}

std::vector<double> row_borders(const Matrix& m, int row, int texture_width) {
  const double v = row + 0.5;
  std::vector<double> borders(static_cast<std::size_t>(texture_width) + 1);
  for (int t = 0; t <= texture_width; ++t) {
    borders[static_cast<std::size_t>(t)] = (m.a * t + m.b * v + m.c) / (m.g * t + m.h * v + m.i);  // Eq. 1
  }
  return borders;
}

std::vector<double> column_borders(const Matrix& m, int column, int texture_height) {
  const double x = column + 0.5;
  const double divisor = m.g * x - m.a;
  if (divisor == 0.0) {
    return {};
  }
  const double slope = (m.b - m.h * x) / divisor;   // the paper's m
  const double offset = (m.c - m.i * x) / divisor;  // the paper's n
  std::vector<double> borders(static_cast<std::size_t>(texture_height) + 1);
  for (int t = 0; t <= texture_height; ++t) {
    borders[static_cast<std::size_t>(t)] =
        ((m.d * slope + m.e) * t + (m.d * offset + m.f)) / ((m.g * slope + m.h) * t + (m.g * offset + m.i));  // Eq. 4
  }
  return borders;
}

std::vector<double> resample_line_eq3(const std::vector<double>& texels, const std::vector<double>& borders,
                                      FilterKind kind, int width, int pixel_count) {
  std::vector<double> pixels(static_cast<std::size_t>(pixel_count), 0.0);
  for (int p = 0; p < pixel_count; ++p) {
    const double centre = p + 0.5;
    double sum = 0.0;
    for (std::size_t t = 0; t < texels.size(); ++t) {
      const double left = std::min(borders[t], borders[t + 1]);
      const double right = std::max(borders[t], borders[t + 1]);
      sum += (filter_primitive(kind, width, right - centre) - filter_primitive(kind, width, left - centre)) *
             texels[t];  // Eq. 3
    }
    pixels[static_cast<std::size_t>(p)] = sum;
  }
  return pixels;
}

std::vector<double> warp_eq3(const tessera::forward_texture::Image& texture, const Matrix& m, FilterKind kind,
                             int width, int output_width, int output_height, PassOrder order) {
  const std::vector<double> texels(texture.texels.begin(), texture.texels.end());
  if (order == PassOrder::rows_first) {
    return rows_first(texels, texture.width, texture.height, m, kind, width, output_width, output_height);
  }
  return rows_first(transposed(texels, texture.width, texture.height), texture.height, texture.width,
                    with_u_and_v_swapped(m), kind, width, output_width, output_height);
}

}  // namespace tessera::test::forward_texture
