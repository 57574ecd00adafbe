// The warp's lines on the array (array_resampler.h).
#include "forward_texture/array_resampler.h"

#include <algorithm>
#include <cstring>

#include "ap_programs/resample_chain.h"
#include "ap_programs/resample_lines.h"
#include "ap_programs/resample_lines_lut.h"
#include "array/isa/ap_isa.h"
#include "config/config.h"
#include "costs/host_cost.h"

namespace tessera::forward_texture {

namespace {

using costs::HostCost;
using renderers::HostSplit;
using renderers::TimedScope;

constexpr unsigned INPUT_CHANNEL = 0;

// Rows a batch sends and fetches at most: the mapping's 16 and the texels'
// 2 (n + 2); the four border planes' 4 (n + 1) and the window's 2 F + 3.
unsigned input_rows(int texel_count) {
  return 16 + 2 * (static_cast<unsigned>(texel_count) + 2);
}
unsigned result_rows(int texel_count, int width) {
  return 4 * (static_cast<unsigned>(texel_count) + 1) + 2 * static_cast<unsigned>(width) + 3;
}

// The larger of the input and result rows, and one descriptor each.
uint32_t staging_for(unsigned cus, int texel_count, int width) {
  const unsigned rows = std::max(input_rows(texel_count), result_rows(texel_count, width));
  return rows * (cus + dma::DESCRIPTOR_BYTES);
}

}  // namespace

namespace {

const ap::Program& program_of(ArrayFactors factors, ArrayMapping mapping) {
  if (mapping == ArrayMapping::chain) return ap::programs::resample_chain();
  return factors == ArrayFactors::table ? ap::programs::resample_lines_lut() : ap::programs::resample_lines();
}

}  // namespace

ArrayResampler::ArrayResampler(AppEnvironment& env, renderers::HostTime& time, uint32_t staging, uint32_t staging_end,
                               ArrayFactors factors, ArrayMapping mapping)
    : m_host(*env.host),
      m_time(time),
      m_array(env),
      m_dma(env),
      m_dma_use(renderers::dma_use(env, m_dma)),
      m_program(program_of(factors, mapping)),
      m_layout(ArrayLineLayout::of(mapping == ArrayMapping::chain ? ap::programs::resample_lines_lut() : m_program)),
      m_chain(mapping == ArrayMapping::chain),
      m_chain_layout(m_chain ? ArrayChainLayout::of(m_program) : ArrayChainLayout{}),
      m_config(env.config),
      m_entry(ap::entry_word(m_program, "resample")),
      m_staging(staging),
      m_staging_end(staging_end),
      // Read only for the table, so that the computed program's runs make
      // the same bus accesses as before it had a twin.
      m_lut_entries(factors == ArrayFactors::table || m_chain ? m_array.lut_entries() : 0) {}

ChainGeometry ArrayResampler::chain_geometry() const {
  return {m_array.columns(), m_array.rows(), m_lut_entries};
}

uint32_t ArrayResampler::staging_bytes(int texel_count, int width) const {
  return staging_for(m_array.cus(), texel_count, width);
}

uint32_t ArrayResampler::largest_staging(unsigned cus) {
  const ArrayLineLayout layout = ArrayLineLayout::of(ap::programs::resample_lines());
  return staging_for(cus, layout.max_texels, layout.max_width);
}

std::string ArrayResampler::batch_error(const FilterTable& table, int texel_count) const {
  std::string error = m_chain ? array_chain_error(m_chain_layout, chain_geometry(), table, texel_count)
                              : array_line_error(m_layout, table, texel_count, m_lut_entries);
  const uint32_t left = m_staging_end > m_staging ? m_staging_end - m_staging : 0;
  if (error.empty() && m_dma_use.enabled && left < staging_bytes(texel_count, table.width)) {
    error = "the DMA's staging for lines of " + std::to_string(texel_count) + " texels needs " +
            std::to_string(staging_bytes(texel_count, table.width)) + " bytes of system memory; " +
            std::to_string(left) + " are left";
  }
  return error;
}

std::string ArrayResampler::check(const FilterTable& table, int texel_count) {
  std::string error;
  if (m_chain && m_config != nullptr) {
    // The chain's sums pass down each row in one instruction only under
    // delayed execution, and cross from round to round by the row ring.
    const std::pair<const char*, bool> needs[] = {
        {"array.issue_skew=lane", m_config->get_string("array.issue_skew") == "lane"},
        {"array.row_ring=true", m_config->get_bool("array.row_ring")},
        {"array.features.neighbour_add=true", m_config->get_bool("array.features.neighbour_add")},
        {"array.features.lut=true", m_config->get_bool("array.features.lut")}};
    for (const auto& [setting, held] : needs)
      if (error.empty() && !held)
        error = std::string("van Sinten's mapping (resample_chain.s) needs ") + setting +
                " (configs/presets/image_blender_like.json sets it)";
  }
  if (error.empty()) error = batch_error(table, texel_count);
  // The program's registers and CMEM addresses against the array's (the
  // assembler checked them against the J2210's).
  const unsigned registers = m_array.registers();
  for (std::size_t w = 0; error.empty() && w < m_program.words.size(); ++w) {
    const std::string beyond =
        ap::check_limits(ap::decode(m_program.words[w]).instruction, registers, m_array.cmem_bytes());
    if (!beyond.empty()) {
      error = "the array program needs more than this array has (array.registers = " + std::to_string(registers) +
              ", array.cmem_bytes = " + std::to_string(m_array.cmem_bytes()) + "): word " + std::to_string(w) + ": " +
              beyond;
    }
  }
  return error;
}

void ArrayResampler::prepare(int texel_count, const FilterTable& table) {
  const int width = table.width;
  if (texel_count != m_loaded_texels || width != m_loaded_width) {
    TimedScope timed(m_host, m_time, HostSplit::array_write);
    m_array.load(m_chain ? program_for_chain(m_program, chain_geometry().rounds(texel_count), width)
                         : program_for_lines(m_program, texel_count, width));
    m_loaded_texels = texel_count;
    m_loaded_width = width;
  }
  if (width != m_filter_width) {
    // The filter's constants, the same in every CU: broadcast when the DMA
    // can, else one row per byte.
    TimedScope timed(m_host, m_time, HostSplit::array_write);
    std::vector<CmemRow> rows;
    for (const CmemBlock& block :
         m_chain ? chain_filter_blocks(m_chain_layout, width) : filter_blocks(m_layout, width)) {
      for (std::size_t k = 0; k < block.bytes.size(); ++k) {
        rows.push_back({static_cast<uint16_t>(block.address + k), std::vector<uint8_t>(m_array.cus(), block.bytes[k])});
      }
    }
    send_rows(rows);
    m_filter_width = width;
  }
  if ((m_chain || m_layout.table_factors) && (width != m_table_width || table.kind != m_table_kind)) {
    // The filter's table, once per filter, through LUT_INDEX and LUT_DATA.
    TimedScope timed(m_host, m_time, HostSplit::array_write);
    m_array.write_lut(0, m_chain ? chain_lut(table) : lut_entries(table));
    m_table_width = width;
    m_table_kind = table.kind;
  }
}

void ArrayResampler::send_rows(const std::vector<CmemRow>& rows) {
  const unsigned cus = m_array.cus();
  if (!m_dma_use.enabled) {
    for (const CmemRow& row : rows) {
      m_array.write_all8(row.address, row.per_cu, HostCost::forward_texture_array_ciu_word_out);
      m_figures.traffic.values_written += cus;
    }
    return;
  }
  // One reshuffle a row (CU k gets byte k), from rows staged one after the
  // other, as one chain.
  const uint32_t chain = m_staging + static_cast<uint32_t>(rows.size()) * cus;
  std::vector<dma::Descriptor> descriptors;
  descriptors.reserve(rows.size());
  for (std::size_t r = 0; r < rows.size(); ++r) {
    const uint32_t source = m_staging + static_cast<uint32_t>(r) * cus;
    std::memcpy(m_host.store_span(source, 1, cus), rows[r].per_cu.data(), cus);
    descriptors.push_back(DmaDriver::to_cmem(source, rows[r].address, cus, 1));
  }
  costs::charge(m_host, HostCost::forward_texture_array_row, rows.size());
  m_dma.write_chain(chain, descriptors);
  m_dma.start_chain(INPUT_CHANNEL, chain);
  m_dma.wait(INPUT_CHANNEL);
  m_figures.traffic.values_written += uint64_t{cus} * rows.size();
  m_figures.traffic.dma_descriptors += rows.size();
}

std::vector<CmemRow> ArrayResampler::fetch_rows(const std::vector<uint16_t>& addresses) {
  const unsigned cus = m_array.cus();
  std::vector<CmemRow> rows;
  rows.reserve(addresses.size());
  if (!m_dma_use.enabled) {
    for (const uint16_t address : addresses)
      rows.push_back({address, m_array.read_all8(address, HostCost::forward_texture_array_ciu_word_in)});
    m_figures.traffic.values_read += uint64_t{cus} * addresses.size();
    return rows;
  }
  const uint32_t chain = m_staging + static_cast<uint32_t>(addresses.size()) * cus;
  std::vector<dma::Descriptor> descriptors;
  descriptors.reserve(addresses.size());
  for (std::size_t r = 0; r < addresses.size(); ++r) {
    descriptors.push_back(DmaDriver::from_cmem(addresses[r], m_staging + static_cast<uint32_t>(r) * cus, cus, 1));
  }
  m_dma.write_chain(chain, descriptors);
  m_dma.start_chain(INPUT_CHANNEL, chain);
  m_dma.wait(INPUT_CHANNEL);
  costs::charge(m_host, HostCost::forward_texture_array_row, addresses.size());
  for (std::size_t r = 0; r < addresses.size(); ++r) {
    const uint8_t* bytes = m_host.load_span(m_staging + static_cast<uint32_t>(r) * cus, 1, cus);
    rows.push_back({addresses[r], std::vector<uint8_t>(bytes, bytes + cus)});
  }
  m_figures.traffic.values_read += uint64_t{cus} * addresses.size();
  m_figures.traffic.dma_descriptors += addresses.size();
  return rows;
}

std::string ArrayResampler::resample(std::vector<PassLine>& lines, const FilterTable& table,
                                     const std::function<std::string(std::size_t)>& where) {
  if (lines.empty()) {
    return {};
  }
  const int n = lines.front().texels.count;
  if (std::string error = batch_error(table, n); !error.empty()) {
    return where(0) + ": " + error;
  }
  // A line the host cannot orient, or that the array flags, is named by
  // step_borders, as on the host.
  const auto refused = [&lines, &where, n](std::size_t k) {
    std::vector<q16_16> borders(static_cast<std::size_t>(n) + 1);
    std::string error = step_borders(lines[k].mapping, n, where(k), borders.data());
    return error.empty() ? where(k) + ": the array flagged the line, but step_borders finds no error" : error;
  };
  prepare(n, table);
  std::vector<ArrayLine> oriented(lines.size());
  {
    TimedScope timed(m_host, m_time, HostSplit::compute);
    costs::charge(m_host, HostCost::forward_texture_array_line, lines.size());
    for (std::size_t k = 0; k < lines.size(); ++k) {
      if (!orient_line(lines[k].mapping, lines[k].texels, oriented[k])) return refused(k);
      lines[k].first_border = oriented[k].first_border;
      lines[k].last_border = oriented[k].last_border;
    }
  }
  if (m_chain) return resample_chain(lines, oriented, table, refused);
  {
    TimedScope timed(m_host, m_time, HostSplit::array_write);
    costs::charge(m_host, HostCost::forward_texture_array_texel, lines.size() * static_cast<uint64_t>(n));
    send_rows(line_rows(m_layout, oriented, m_array.cus()));
  }
  {
    TimedScope timed(m_host, m_time, HostSplit::array_wait);
    m_figures.cycles += m_array.run(m_entry);
    ++m_figures.runs;
    m_figures.steps += static_cast<uint64_t>(n) + 1;
  }
  TimedScope timed(m_host, m_time, HostSplit::array_read);
  const std::vector<CmemRow> results = fetch_rows(result_addresses(m_layout, n, table.width));
  costs::charge(m_host, HostCost::forward_texture_array_border, lines.size() * (static_cast<uint64_t>(n) + 1));
  costs::charge(m_host, HostCost::forward_texture_array_pixel,
                lines.size() * static_cast<uint64_t>(lines.front().pixels.count));
  for (std::size_t k = 0; k < lines.size(); ++k) {
    if (!scatter_line(n, table.width, results, static_cast<unsigned>(k), lines[k].pixels)) return refused(k);
  }
  m_figures.lines += lines.size();
  m_figures.borders += lines.size() * (static_cast<uint64_t>(n) + 1);
  return {};
}

// The chain's batch: line k in CU row k, the program's rounds, the rows it
// leaves read back and each line's pixels gathered from them.
std::string ArrayResampler::resample_chain(std::vector<PassLine>& lines, const std::vector<ArrayLine>& oriented,
                                           const FilterTable& table,
                                           const std::function<std::string(std::size_t)>& refused) {
  const int n = lines.front().texels.count;
  const ChainGeometry geometry = chain_geometry();
  {
    TimedScope timed(m_host, m_time, HostSplit::array_write);
    costs::charge(m_host, HostCost::forward_texture_chain_texel, lines.size() * static_cast<uint64_t>(n));
    send_rows(chain_rows(m_chain_layout, geometry, oriented));
  }
  {
    TimedScope timed(m_host, m_time, HostSplit::array_wait);
    m_figures.cycles += m_array.run(m_entry);
    ++m_figures.runs;
    m_figures.steps += static_cast<uint64_t>(geometry.rounds(n));
  }
  TimedScope timed(m_host, m_time, HostSplit::array_read);
  const ArrayChainLayout& c = m_chain_layout;
  const int rounds = geometry.rounds(n);
  std::vector<uint16_t> addresses;
  for (const uint16_t plane : {c.err, c.idx_hi, c.idx_lo, c.val_hi, c.val_lo})
    for (int v = 0; v < rounds; ++v) addresses.push_back(static_cast<uint16_t>(plane + v));
  for (int j = 0; j < table.width; ++j) {
    addresses.push_back(static_cast<uint16_t>(c.fin_hi + j));
    addresses.push_back(static_cast<uint16_t>(c.fin_lo + j));
  }
  addresses.push_back(c.pixel);
  addresses.push_back(static_cast<uint16_t>(c.pixel + 1));
  const std::vector<CmemRow> results = fetch_rows(addresses);
  std::vector<const CmemRow*> by_address(m_array.cmem_bytes(), nullptr);
  for (const CmemRow& row : results) by_address[row.address] = &row;
  const auto cmem = [&by_address](unsigned cu, uint16_t address) { return by_address[address]->per_cu[cu]; };
  costs::charge(m_host, HostCost::forward_texture_chain_border, lines.size() * (static_cast<uint64_t>(n) + 1));
  costs::charge(m_host, HostCost::forward_texture_array_pixel,
                lines.size() * static_cast<uint64_t>(lines.front().pixels.count));
  for (std::size_t k = 0; k < lines.size(); ++k) {
    if (!gather_chain_line(c, geometry, n, table.width, static_cast<unsigned>(k), cmem, lines[k].pixels))
      return refused(k);
  }
  m_figures.lines += lines.size();
  m_figures.borders += lines.size() * (static_cast<uint64_t>(n) + 1);
  return {};
}

}  // namespace tessera::forward_texture
