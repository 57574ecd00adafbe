// The warp's lines on the array (README.md, "On the array"): a LineResampler
// that runs resample_lines.s with one line per CU (the factors computed, or
// looked up in the array's shared table: ArrayFactors), the lines brought into
// CMEM and the results taken out by the system/array DMA when the SoC has
// one (dma.enabled), else through the CIU, and the host scattering the
// pixels. Its host time goes to the caller's split: writing (the lines
// staged and sent), waiting (the program) and reading (the results fetched
// and scattered).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "device/app_environment.h"
#include "device/array_driver.h"
#include "device/dma_driver.h"
#include "forward_texture/array_chain.h"
#include "forward_texture/array_lines.h"
#include "forward_texture/warp.h"
#include "renderers/common/array_dma.h"
#include "renderers/common/host_time.h"

namespace tessera::forward_texture {

// Where the program's factors come from: computed (resample_lines, the
// J2210's own instructions, the box filter only) or looked up in the shared
// table (resample_lines_lut, array.features.lut, any tabulated filter).
enum class ArrayFactors { computed, table };

// How the lines meet the CUs: one line per CU, every CU at the same border
// (resample_lines*), or van Sinten's own mapping (resample_chain.s,
// README.md "On the array: the chain"): a line per CU row, a border per CU,
// the window's sums passed down each row's chain; its factors are always
// looked up, and it needs delayed execution, the row ring, the selecting
// adds and the table.
enum class ArrayMapping { lines, chain };

class ArrayResampler : public LineResampler {
 public:
  // `staging` .. `staging_end`: system memory the DMA's rows and chains may
  // use (unused without the DMA). `time` receives the host time of each part.
  ArrayResampler(AppEnvironment& env, renderers::HostTime& time, uint32_t staging, uint32_t staging_end,
                 ArrayFactors factors = ArrayFactors::computed, ArrayMapping mapping = ArrayMapping::lines);

  std::string resample(std::vector<PassLine>& lines, const FilterTable& table,
                       const std::function<std::string(std::size_t)>& where) override;
  std::size_t batch_lines() const override { return m_chain ? m_array.rows() : m_array.cus(); }

  // Empty, or why the array cannot resample lines of `texel_count` texels
  // with `table` (array_line_error: with the table, its size against
  // array.lut.entries; the chain: array_chain_error and the switches it
  // needs), why this array cannot run the program (its registers or CMEM),
  // or why the staging is too small.
  std::string check(const FilterTable& table, int texel_count);

  struct Figures {
    uint64_t runs = 0;    // programs run (batches)
    uint64_t cycles = 0;  // array cycles, all runs
    uint64_t lines = 0, borders = 0;
    // Texel steps, every run's: a step takes every CU one border on (the
    // lines: a run's n + 1; the chain: a run's rounds).
    uint64_t steps = 0;
    renderers::ArrayTraffic traffic;
  };
  const Figures& figures() const { return m_figures; }
  bool through_dma() const { return m_dma_use.enabled; }
  // The longest line the program takes.
  int max_texels() const { return m_layout.max_texels; }
  // System memory the DMA's rows and chains need on an array of `cus` CUs
  // for every line and filter the program takes.
  static uint32_t largest_staging(unsigned cus);
  // Another program used the array since: the next batch loads this one
  // and the filter's constants again.
  void forget_loaded() { m_loaded_texels = m_loaded_width = m_filter_width = -1; }

 private:
  void prepare(int texel_count, const FilterTable& table);
  // The chain's batch: up to `rows` lines, one per CU row.
  std::string resample_chain(std::vector<PassLine>& lines, const std::vector<ArrayLine>& oriented,
                             const FilterTable& table, const std::function<std::string(std::size_t)>& refused);
  ChainGeometry chain_geometry() const;
  void send_rows(const std::vector<CmemRow>& rows);
  std::vector<CmemRow> fetch_rows(const std::vector<uint16_t>& addresses);
  uint32_t staging_bytes(int texel_count, int width) const;
  std::string batch_error(const FilterTable& table, int texel_count) const;

  HostApi& m_host;
  renderers::HostTime& m_time;
  ArrayDriver m_array;
  DmaDriver m_dma;
  renderers::DmaUse m_dma_use;
  const ap::Program& m_program;
  ArrayLineLayout m_layout;  // the lines program's (resample_lines)
  bool m_chain = false;
  ArrayChainLayout m_chain_layout;
  const Config* m_config = nullptr;
  unsigned m_entry = 0;
  uint32_t m_staging = 0, m_staging_end = 0;
  int m_loaded_texels = -1, m_loaded_width = -1, m_filter_width = -1;
  // The table's size (0: the factors are computed), and the filter last
  // written into it.
  unsigned m_lut_entries = 0;
  int m_table_width = -1;
  FilterKind m_table_kind = FilterKind::box;
  Figures m_figures;
};

}  // namespace tessera::forward_texture
