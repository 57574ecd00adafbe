// The two-pass warp of a whole texture (README.md): the row pass (Eq. 1)
// into an intermediate image of (output width) x (texture height), then the
// column pass (Eq. 4) into the output; or, when mapping the texture's rows
// would compress more than mapping its columns, the same on the transposed
// texture: its columns onto the intermediate rows first ("Pass order"). One channel of unorm8; a colour texture is one
// warp per channel.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "forward_texture/filter.h"
#include "forward_texture/matrix.h"
#include "forward_texture/resample_line.h"

namespace tessera::forward_texture {

struct Image {
  int width = 0;
  int height = 0;
  std::vector<uint8_t> texels;  // row-major, width * height

  uint8_t at(int x, int y) const { return texels[static_cast<std::size_t>(y) * width + x]; }
};

enum class PassOrder { rows_first, columns_first };

const char* pass_order_name(PassOrder order);

// What each first pass makes of the texture: the shorter of the mapped
// lengths of its first and last line, per texel (q16_16 pixels per texel).
struct PassOrderChoice {
  PassOrder order = PassOrder::rows_first;
  q16_16 rows_first_scale = 0;
  q16_16 columns_first_scale = 0;
};

// Rows first unless columns first keeps more pixels per texel in its first
// pass (a tie runs rows first). Empty, or the message of a set-up error.
std::string choose_pass_order(const PerspectiveMatrix& m, int texture_width, int texture_height,
                              PassOrderChoice& choice);

// One line of a pass: its mapping, its texels and the pixels it makes, and
// (set by the resampler) its first and last border, from which the row
// pass finds the columns it reached.
struct PassLine {
  LineMapping mapping;
  LineView texels;
  LineView pixels;
  q16_16 first_border = 0;
  q16_16 last_border = 0;
};

// Where a pass's lines are resampled: on the host (HostResampler: one line
// at a time by step_borders and resample_line) or elsewhere (the array
// program, array_lines.h) with the same results bit for bit.
class LineResampler {
 public:
  virtual ~LineResampler() = default;
  // Resamples every line of `lines` (all of `lines[0].texels.count`
  // texels) with `table`. Empty, or the message of the first line that
  // step_borders refuses, starting with where(k) for line k.
  virtual std::string resample(std::vector<PassLine>& lines, const FilterTable& table,
                               const std::function<std::string(std::size_t)>& where) = 0;
  // The lines the warp hands over at once, at most (the texels of a row
  // pass's lines are staged that many at a time).
  virtual std::size_t batch_lines() const = 0;
};

class HostResampler : public LineResampler {
 public:
  std::string resample(std::vector<PassLine>& lines, const FilterTable& table,
                       const std::function<std::string(std::size_t)>& where) override;
  std::size_t batch_lines() const override { return 1; }
};

struct WarpResult {
  std::string error;  // empty on success; the image is empty otherwise
  Image image;
  PassOrderChoice pass_order;
};

// The texture mapped onto an output_width x output_height image under `m`
// with `table`'s filter, in the order choose_pass_order picks, each pass's
// lines resampled by `resampler` (nullptr: on the host).
WarpResult warp_texture(const Image& texture, const PerspectiveMatrix& m, const FilterTable& table, int output_width,
                        int output_height, LineResampler* resampler = nullptr);

// The same in a given order (for tests of the rule's reason).
WarpResult warp_texture_in_order(const Image& texture, const PerspectiveMatrix& m, const FilterTable& table,
                                 int output_width, int output_height, PassOrder order,
                                 LineResampler* resampler = nullptr);

}  // namespace tessera::forward_texture
