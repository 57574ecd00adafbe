// The two-pass warp (warp.h). The columns-first order is the rows-first
// order run on the transposed texture under the matrix with u and v
// swapped, so there is one implementation of each pass.
#include "forward_texture/warp.h"

#include "forward_texture/resample_line.h"

namespace tessera::forward_texture {

namespace {

struct Plane {  // a q8_8 image
  int width = 0;
  int height = 0;
  std::vector<q8_8> values;

  LineView row(int y) { return {&values[static_cast<std::size_t>(y) * width], width, 1}; }
  LineView column(int x) { return {&values[static_cast<std::size_t>(x)], height, width}; }
};

Image transposed_image(const Image& image) {
  Image t{image.height, image.width, std::vector<uint8_t>(image.texels.size())};
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) {
      t.texels[static_cast<std::size_t>(x) * t.width + y] = image.at(x, y);
    }
  }
  return t;
}

std::string size_error(const char* what, int width, int height) {
  if (width >= 1 && width <= MAX_IMAGE_SIZE && height >= 1 && height <= MAX_IMAGE_SIZE) {
    return {};
  }
  return std::string(what) + " size " + std::to_string(width) + " x " + std::to_string(height) +
         " is out of range: each side must be 1 .. " + std::to_string(MAX_IMAGE_SIZE);
}

// The shorter mapped length of the first and last row under the row pass,
// per texel.
std::string row_pass_scale(const PerspectiveMatrix& m, int width, int height, q16_16& scale) {
  uint32_t shortest = UINT32_MAX;
  for (const int row : {0, height - 1}) {
    LineMapping line;
    std::string error = row_pass_line(m, row, width, line);
    q16_16 first = 0;
    q16_16 last = 0;
    const int64_t numerator_end = line.numerator + int64_t{line.numerator_step} * width;  // fits: row_pass_line
    const int64_t denominator_end = line.denominator + int64_t{line.denominator_step} * width;
    if (error.empty() &&
        (!divide_border(line.numerator, line.denominator, first) ||
         !divide_border(static_cast<q12_20>(numerator_end), static_cast<q2_30>(denominator_end), last))) {
      error = "row " + std::to_string(row) + ": an end of the row maps beyond 32768 pixels";
    }
    if (!error.empty()) {
      return error;
    }
    const uint32_t length = first < last ? static_cast<uint32_t>(last) - static_cast<uint32_t>(first)
                                         : static_cast<uint32_t>(first) - static_cast<uint32_t>(last);
    shortest = length < shortest ? length : shortest;
  }
  scale = static_cast<q16_16>(shortest / static_cast<uint32_t>(width));  // < 2^31 / 1
  return {};
}

// The row pass of `texture` into `intermediate` (output width x texture
// height); [first, last) are the intermediate columns any row can reach.
std::string row_pass(const Image& texture, const PerspectiveMatrix& m, const FilterTable& table, Plane& intermediate,
                     LineResampler& resampler, int& first_column, int& last_column) {
  const std::size_t batch = resampler.batch_lines();
  std::vector<q8_8> texels(static_cast<std::size_t>(texture.width) * batch);
  std::vector<PassLine> lines;
  first_column = intermediate.width;
  last_column = 0;
  for (int first_row = 0; first_row < texture.height; first_row += static_cast<int>(batch)) {
    lines.clear();
    for (int row = first_row; row < texture.height && lines.size() < batch; ++row) {
      PassLine line;
      std::string error = row_pass_line(m, row, texture.width, line.mapping);
      if (!error.empty()) {
        return error;
      }
      line.texels = {&texels[lines.size() * static_cast<std::size_t>(texture.width)], texture.width, 1};
      for (int u = 0; u < texture.width; ++u) {
        line.texels[u] = texture.at(u, row) << Q8_8_FRACTION_BITS;
      }
      line.pixels = intermediate.row(row);
      lines.push_back(line);
    }
    std::string error = resampler.resample(lines, table, [first_row](std::size_t k) {
      return "row pass, row " + std::to_string(first_row + static_cast<int>(k));
    });
    if (!error.empty()) {
      return error;
    }
    for (const PassLine& line : lines) {
      // The filter reaches F/2 pixels beyond the extreme borders.
      const q16_16 low = line.first_border < line.last_border ? line.first_border : line.last_border;
      const q16_16 high = line.first_border < line.last_border ? line.last_border : line.first_border;
      const int reach = table.width / 2 + 1;
      const int low_column = (low >> Q16_16_FRACTION_BITS) - reach;
      const int high_column = (high >> Q16_16_FRACTION_BITS) + reach + 1;
      first_column = low_column < first_column ? low_column : first_column;
      last_column = high_column > last_column ? high_column : last_column;
    }
  }
  first_column = first_column < 0 ? 0 : first_column;
  last_column = last_column > intermediate.width ? intermediate.width : last_column;
  return {};
}

std::string column_pass(const PerspectiveMatrix& m, const FilterTable& table, Plane& intermediate, int first_column,
                        int last_column, LineResampler& resampler, Plane& output) {
  ColumnPassSetup setup;
  std::string error = column_pass_setup(m, setup);
  if (!error.empty()) {
    return error;
  }
  const std::size_t batch = resampler.batch_lines();
  std::vector<PassLine> lines;
  for (int first = first_column; first < last_column; first += static_cast<int>(batch)) {
    lines.clear();
    for (int column = first; column < last_column && lines.size() < batch; ++column) {
      PassLine line;
      error = column_pass_line(setup, column, intermediate.height, line.mapping);
      if (!error.empty()) {
        return error;
      }
      line.texels = intermediate.column(column);
      line.pixels = output.column(column);
      lines.push_back(line);
    }
    error = resampler.resample(lines, table, [first](std::size_t k) {
      return "column pass, column " + std::to_string(first + static_cast<int>(k));
    });
    if (!error.empty()) {
      return error;
    }
  }
  return {};
}

std::string rows_first(const Image& texture, const PerspectiveMatrix& m, const FilterTable& table, int output_width,
                       int output_height, LineResampler& resampler, Image& output) {
  Plane intermediate{output_width, texture.height,
                     std::vector<q8_8>(static_cast<std::size_t>(output_width) * texture.height, 0)};
  Plane result{output_width, output_height,
               std::vector<q8_8>(static_cast<std::size_t>(output_width) * output_height, 0)};
  int first_column = 0;
  int last_column = 0;
  std::string error = row_pass(texture, m, table, intermediate, resampler, first_column, last_column);
  if (error.empty()) {
    error = column_pass(m, table, intermediate, first_column, last_column, resampler, result);
  }
  if (!error.empty()) {
    return error;
  }
  output = Image{output_width, output_height, std::vector<uint8_t>(result.values.size())};
  for (std::size_t k = 0; k < result.values.size(); ++k) {
    // Rounded to unorm8; resample_line clamped to 0 .. 255 << 8.
    output.texels[k] = static_cast<uint8_t>((result.values[k] + (1 << (Q8_8_FRACTION_BITS - 1))) >> Q8_8_FRACTION_BITS);
  }
  return {};
}

std::string input_error(const Image& texture, const PerspectiveMatrix& m, const FilterTable& table, int output_width,
                        int output_height) {
  std::string error = filter_width_error(table.width);
  if (error.empty() && table.values.size() != static_cast<std::size_t>(PHASES) * table.width) {
    error = "the filter table of width " + std::to_string(table.width) + " holds " +
            std::to_string(table.values.size()) + " values, not " + std::to_string(PHASES) + " rows of that many";
  }
  if (error.empty()) {
    error = size_error("texture", texture.width, texture.height);
  }
  if (error.empty() && texture.texels.size() != static_cast<std::size_t>(texture.width) * texture.height) {
    error = "texture holds " + std::to_string(texture.texels.size()) + " texels, not width x height";
  }
  if (error.empty()) {
    error = size_error("output", output_width, output_height);
  }
  if (error.empty()) {
    error = matrix_error(m, texture.width, texture.height);
  }
  return error;
}

}  // namespace

const char* pass_order_name(PassOrder order) {
  return order == PassOrder::rows_first ? "rows first" : "columns first";
}

std::string choose_pass_order(const PerspectiveMatrix& m, int texture_width, int texture_height,
                              PassOrderChoice& choice) {
  std::string error = row_pass_scale(m, texture_width, texture_height, choice.rows_first_scale);
  if (error.empty()) {
    error = row_pass_scale(with_u_and_v_swapped(m), texture_height, texture_width, choice.columns_first_scale);
    if (!error.empty()) {
      error = "columns first, " + error;
    }
  } else {
    error = "rows first, " + error;
  }
  choice.order =
      choice.columns_first_scale > choice.rows_first_scale ? PassOrder::columns_first : PassOrder::rows_first;
  return error;
}

std::string HostResampler::resample(std::vector<PassLine>& lines, const FilterTable& table,
                                    const std::function<std::string(std::size_t)>& where) {
  std::vector<q16_16> borders;
  for (std::size_t k = 0; k < lines.size(); ++k) {
    PassLine& line = lines[k];
    const int n = line.texels.count;
    borders.resize(static_cast<std::size_t>(n) + 1);
    std::string error = step_borders(line.mapping, n, where(k), borders.data());
    if (!error.empty()) {
      return error;
    }
    resample_line(line.texels, borders.data(), table, line.pixels);
    line.first_border = borders.front();
    line.last_border = borders.back();
  }
  return {};
}

WarpResult warp_texture_in_order(const Image& texture, const PerspectiveMatrix& m, const FilterTable& table,
                                 int output_width, int output_height, PassOrder order, LineResampler* resampler) {
  WarpResult result;
  result.pass_order.order = order;
  result.error = input_error(texture, m, table, output_width, output_height);
  if (!result.error.empty()) {
    return result;
  }
  HostResampler on_host;
  LineResampler& lines = resampler != nullptr ? *resampler : on_host;
  if (order == PassOrder::rows_first) {
    result.error = rows_first(texture, m, table, output_width, output_height, lines, result.image);
    return result;
  }
  result.error = rows_first(transposed_image(texture), with_u_and_v_swapped(m), table, output_width, output_height,
                            lines, result.image);
  return result;
}

WarpResult warp_texture(const Image& texture, const PerspectiveMatrix& m, const FilterTable& table, int output_width,
                        int output_height, LineResampler* resampler) {
  WarpResult result;
  result.error = input_error(texture, m, table, output_width, output_height);
  if (result.error.empty()) {
    result.error = choose_pass_order(m, texture.width, texture.height, result.pass_order);
  }
  if (!result.error.empty()) {
    return result;
  }
  const PassOrderChoice choice = result.pass_order;
  result = warp_texture_in_order(texture, m, table, output_width, output_height, choice.order, resampler);
  result.pass_order = choice;
  return result;
}

}  // namespace tessera::forward_texture
