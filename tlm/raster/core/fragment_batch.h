// The fragments of one triangle that the traversal hands to the shader at
// once: runs of pixels of rows in the order the traversal found them (top
// row first, left to right), with each fragment's offset from the setup's
// reference pixel and its coverage. The shading stages run the datapath's
// batch forms (raster/datapath/batch.h) over a batch, so a triangle costs
// a few calls per stage rather than a few calls per fragment (README.md,
// "Batches").
#pragma once

#include <array>
#include <cstdint>
#include <utility>

namespace tessera::raster {

class FragmentBatch {
 public:
  // A tile row of the largest tile (512 pixels) fits in one batch.
  static constexpr unsigned CAPACITY = 512;

  struct Run {
    int px, py;      // first pixel, GL window coordinates
    unsigned first;  // its fragment's index in the batch
    unsigned count;
  };

  // Empties the batch for a triangle whose planes start at pixel (ref_x, ref_y).
  void reset(int ref_x, int ref_y) {
    m_ref_x = ref_x;
    m_ref_y = ref_y;
    m_size = 0;
    m_runs = 0;
  }
  void clear() { reset(m_ref_x, m_ref_y); }

  unsigned size() const { return m_size; }
  unsigned room() const { return CAPACITY - m_size; }
  bool empty() const { return m_size == 0; }

  // Appends pixels px .. px + count - 1 of row py (count <= room()), with
  // coverage[0 .. count - 1], or 255 each when `coverage` is null.
  void add_run(int px, int py, unsigned count, const uint32_t* coverage) {
    m_run[m_runs++] = {px, py, m_size, count};
    for (unsigned k = 0; k < count; ++k) {
      m_dx[m_size + k] = px + static_cast<int>(k) - m_ref_x;
      m_dy[m_size + k] = py - m_ref_y;
      m_coverage[m_size + k] = coverage != nullptr ? coverage[k] : 255;
    }
    m_size += count;
  }

  unsigned run_count() const { return m_runs; }
  const Run& run(unsigned r) const { return m_run[r]; }
  // The pixel (px, py) of fragment i.
  std::pair<int, int> pixel(unsigned i) const { return {m_dx[i] + m_ref_x, m_dy[i] + m_ref_y}; }

  const int32_t* dx() const { return m_dx.data(); }
  const int32_t* dy() const { return m_dy.data(); }
  const uint32_t* coverage() const { return m_coverage.data(); }

 private:
  int m_ref_x = 0, m_ref_y = 0;
  unsigned m_size = 0, m_runs = 0;
  std::array<Run, CAPACITY> m_run;
  std::array<int32_t, CAPACITY> m_dx, m_dy;
  std::array<uint32_t, CAPACITY> m_coverage;
};

}  // namespace tessera::raster
