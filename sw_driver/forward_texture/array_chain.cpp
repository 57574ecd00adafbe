// The host's side of resample_chain.s (array_chain.h).
#include "forward_texture/array_chain.h"

#include "array/isa/ap_isa.h"

namespace tessera::forward_texture {

namespace {

CmemBlock word_block(uint16_t address, uint32_t value) {
  CmemBlock block{address, std::vector<uint8_t>(4)};
  for (unsigned k = 0; k < 4; ++k) {
    block.bytes[k] = static_cast<uint8_t>(value >> (24 - 8 * k));
  }
  return block;
}

int16_t signed16(uint8_t high, uint8_t low) {
  return static_cast<int16_t>(static_cast<uint16_t>((high << 8) | low));
}

}  // namespace

ArrayChainLayout ArrayChainLayout::of(const ap::Program& program) {
  ArrayChainLayout m;
  m.max_rounds = ap::constant_value(program, "MAX_ROUNDS");
  m.max_width = ap::constant_value(program, "MAX_WIDTH");
  const auto rounds = static_cast<unsigned>(m.max_rounds);
  const auto width = static_cast<unsigned>(m.max_width);
  const auto at = [&program](const char* name, unsigned size) { return ap::variable_address(program, name, size); };
  m.num = at("num", 4);
  m.num_step = at("num_step", 4);
  m.den = at("den", 4);
  m.den_step = at("den_step", 4);
  m.prev_hi = at("prev_hi", rounds);
  m.prev_lo = at("prev_lo", rounds);
  m.cur_hi = at("cur_hi", rounds);
  m.cur_lo = at("cur_lo", rounds);
  m.texel_cu = at("texel_cu", 1);
  m.relay = at("relay", 1);
  m.started = at("started", 1);
  m.offset = at("offset", 4);
  m.slots = at("slots", width);
  m.zero = at("zero", 1);
  m.ff = at("ff", 1);
  m.c80 = at("c80", 1);
  m.c7f = at("c7f", 1);
  m.c40 = at("c40", 1);
  m.cc0 = at("cc0", 1);
  m.none = at("none", 1);
  m.limit = at("limit", 4);
  m.clamp = at("clamp", 3);
  m.idx_hi = at("idx_hi", rounds);
  m.idx_lo = at("idx_lo", rounds);
  m.val_hi = at("val_hi", rounds);
  m.val_lo = at("val_lo", rounds);
  m.err = at("err", rounds);
  m.fin_hi = at("fin_hi", width);
  m.fin_lo = at("fin_lo", width);
  m.pixel = at("pixel", 2);
  return m;
}

std::string array_chain_error(const ArrayChainLayout& layout, const ChainGeometry& geometry, const FilterTable& table,
                              int texel_count) {
  if (table.width < 1 || table.width > layout.max_width) {
    return "filter width F = " + std::to_string(table.width) + " is beyond the chain program's window of 1 .. " +
           std::to_string(layout.max_width) + " pixels";
  }
  const auto entries = static_cast<unsigned>(PHASES * table.width);
  if (geometry.lut_entries < entries) {
    return "the filter's table of " + std::to_string(entries) + " entries (256 F) does not fit the lookup table's " +
           std::to_string(geometry.lut_entries) + " (array.lut.entries)";
  }
  if (geometry.columns < 2) {
    return "the chain needs at least 2 columns (a relay and a texel CU per row)";
  }
  if (texel_count < 1 || geometry.rounds(texel_count) > layout.max_rounds) {
    return "a line of " + std::to_string(texel_count) + " texels needs " +
           std::to_string(geometry.rounds(texel_count)) + " rounds of " + std::to_string(geometry.borders_per_round()) +
           " borders; the chain program's CMEM holds " + std::to_string(layout.max_rounds);
  }
  return {};
}

std::vector<uint64_t> program_for_chain(const ap::Program& program, int rounds, int width) {
  const auto last_round = static_cast<uint16_t>(ap::constant_value(program, "MAX_ROUNDS") - 1);
  const auto last_slot = static_cast<uint16_t>(ap::constant_value(program, "MAX_WIDTH") - 1);
  std::vector<uint64_t> words = program.words;
  for (uint64_t& word : words) {
    ap::Decoded decoded = ap::decode(word);
    ap::Instruction& instruction = decoded.instruction;
    if (!decoded.error.empty() || instruction.opcode != ap::Opcode::op_loop) {
      continue;
    }
    // The loop's start is in a (ap_isa.h).
    if (instruction.a.value == last_round) {
      instruction.a.value = static_cast<uint16_t>(rounds - 1);
    } else if (instruction.a.value == last_slot) {
      instruction.a.value = static_cast<uint16_t>(width - 1);
    } else {
      continue;
    }
    word = ap::encode(instruction);
  }
  return words;
}

std::vector<uint16_t> chain_lut(const FilterTable& table) {
  std::vector<uint16_t> entries(static_cast<std::size_t>(PHASES) * table.width);
  for (int j = 0; j < table.width; ++j) {
    for (int phase = 0; phase < PHASES; ++phase) {
      entries[static_cast<std::size_t>(PHASES) * static_cast<std::size_t>(j) + static_cast<std::size_t>(phase)] =
          table.at(phase, j);
    }
  }
  return entries;
}

std::vector<CmemBlock> chain_filter_blocks(const ArrayChainLayout& layout, int width) {
  const auto f = static_cast<uint32_t>(width);
  std::vector<CmemBlock> blocks;
  // s = x + (F - 1) / 2 + half a phase step (resample_line's offset).
  blocks.push_back(word_block(layout.offset, (f - 1u) * (static_cast<uint32_t>(Q16_16_ONE) / 2u) +
                                                 (static_cast<uint32_t>(Q16_16_ONE) >> (PHASE_BITS + 1))));
  CmemBlock slots{layout.slots, std::vector<uint8_t>(static_cast<std::size_t>(layout.max_width))};
  for (std::size_t j = 0; j < slots.bytes.size(); ++j) {
    slots.bytes[j] = static_cast<uint8_t>(j);
  }
  blocks.push_back(slots);
  blocks.push_back({layout.zero, {0x00}});
  blocks.push_back({layout.ff, {0xff}});
  blocks.push_back({layout.c80, {0x80}});
  blocks.push_back({layout.c7f, {0x7f}});
  blocks.push_back({layout.c40, {0x40}});
  blocks.push_back({layout.cc0, {0xc0}});
  blocks.push_back({layout.none, {0x80}});
  blocks.push_back(word_block(layout.limit, static_cast<uint32_t>(Q16_16_ONE) + 1u));
  blocks.push_back({layout.clamp, {0x00, 0xff, 0x01}});
  return blocks;
}

std::vector<CmemRow> chain_rows(const ArrayChainLayout& layout, const ChainGeometry& geometry,
                                const std::vector<ArrayLine>& lines) {
  const int n = lines.empty() ? 0 : lines.front().texels.count;
  const int rounds = geometry.rounds(n);
  const int block = geometry.borders_per_round();
  const unsigned cus = geometry.cus();
  std::vector<CmemRow> rows;
  // Every row at once: the references row_at hands out stay valid.
  rows.reserve(16 + 3 + 4 * static_cast<std::size_t>(rounds));
  const auto row_at = [&rows, cus](uint16_t address) -> CmemRow& {
    rows.push_back({address, std::vector<uint8_t>(cus, 0)});
    return rows.back();
  };
  // Per CU: its first border's numerator and denominator (wrapping, as the
  // CU's additions do: a border past the line's end is never read), the
  // steps of a round, and its role.
  std::vector<std::vector<uint32_t>> words(4, std::vector<uint32_t>(cus, 0));
  std::vector<uint8_t> texel_cu(cus, 0), relay(cus, 0), started(cus, 0xff);
  for (unsigned cu = 0; cu < cus; ++cu) {
    const unsigned row = cu / geometry.columns, column = cu % geometry.columns;
    (column == 0 ? relay : texel_cu)[cu] = 0xff;
    if (row >= lines.size() || column == 0) {
      continue;
    }
    const LineMapping& m = lines[row].mapping;
    const uint32_t k = column - 1;
    words[0][cu] = static_cast<uint32_t>(m.numerator) + k * static_cast<uint32_t>(m.numerator_step);
    words[1][cu] = static_cast<uint32_t>(block) * static_cast<uint32_t>(m.numerator_step);
    words[2][cu] = static_cast<uint32_t>(m.denominator) + k * static_cast<uint32_t>(m.denominator_step);
    words[3][cu] = static_cast<uint32_t>(block) * static_cast<uint32_t>(m.denominator_step);
    started[cu] = k == 0 ? 0 : 0xff;
  }
  const uint16_t word_addresses[4] = {layout.num, layout.num_step, layout.den, layout.den_step};
  for (unsigned w = 0; w < 4; ++w) {
    for (unsigned byte = 0; byte < 4; ++byte) {
      CmemRow& row = row_at(static_cast<uint16_t>(word_addresses[w] + byte));
      for (unsigned cu = 0; cu < cus; ++cu) {
        row.per_cu[cu] = static_cast<uint8_t>(words[w][cu] >> (24 - 8 * byte));
      }
    }
  }
  row_at(layout.texel_cu).per_cu = texel_cu;
  row_at(layout.relay).per_cu = relay;
  row_at(layout.started).per_cu = started;
  // C_{k-1} and C_k of each CU's border in round q at v = rounds - 1 - q.
  const auto texel = [n](const ArrayLine& line, int t) -> uint32_t {
    if (t < 0 || t >= n) {
      return 0;
    }
    return static_cast<uint32_t>(line.texels[line.reversed ? n - 1 - t : t]);
  };
  for (int q = 0; q < rounds; ++q) {
    const auto v = static_cast<uint16_t>(rounds - 1 - q);
    CmemRow& prev_hi = row_at(static_cast<uint16_t>(layout.prev_hi + v));
    CmemRow& prev_lo = row_at(static_cast<uint16_t>(layout.prev_lo + v));
    CmemRow& cur_hi = row_at(static_cast<uint16_t>(layout.cur_hi + v));
    CmemRow& cur_lo = row_at(static_cast<uint16_t>(layout.cur_lo + v));
    for (unsigned cu = 0; cu < cus; ++cu) {
      const unsigned row = cu / geometry.columns, column = cu % geometry.columns;
      if (row >= lines.size() || column == 0) {
        continue;
      }
      const int k = block * q + static_cast<int>(column) - 1;
      const uint32_t previous = texel(lines[row], k - 1), current = texel(lines[row], k);
      prev_hi.per_cu[cu] = static_cast<uint8_t>(previous >> 8);
      prev_lo.per_cu[cu] = static_cast<uint8_t>(previous);
      cur_hi.per_cu[cu] = static_cast<uint8_t>(current >> 8);
      cur_lo.per_cu[cu] = static_cast<uint8_t>(current);
    }
  }
  return rows;
}

bool gather_chain_line(const ArrayChainLayout& layout, const ChainGeometry& geometry, int texel_count, int width,
                       unsigned row, const std::function<uint8_t(unsigned cu, uint16_t address)>& cmem,
                       LineView pixels) {
  const int rounds = geometry.rounds(texel_count);
  const int block = geometry.borders_per_round();
  const auto cu_of = [&](int k) { return row * geometry.columns + static_cast<unsigned>(k % block) + 1u; };
  const auto v_of = [&](int k) { return static_cast<uint16_t>(rounds - 1 - k / block); };
  for (int k = 0; k <= texel_count; ++k) {
    if (cmem(cu_of(k), static_cast<uint16_t>(layout.err + v_of(k))) != 0) {
      return false;
    }
  }
  for (int p = 0; p < pixels.count; ++p) {
    pixels[p] = 0;
  }
  const auto put = [&pixels](int pixel, uint8_t high, uint8_t low) {
    if (pixel >= 0 && pixel < pixels.count) {
      pixels[pixel] = (high << 8) | low;
    }
  };
  // The predecessor's window's last pixel is numbered; the pixel leaving is
  // F - 1 to its left.
  for (int k = 0; k <= texel_count; ++k) {
    const unsigned cu = cu_of(k);
    const uint16_t v = v_of(k);
    const uint8_t high = cmem(cu, static_cast<uint16_t>(layout.idx_hi + v));
    if (high != 0x80) {
      put(signed16(high, cmem(cu, static_cast<uint16_t>(layout.idx_lo + v))) - (width - 1),
          cmem(cu, static_cast<uint16_t>(layout.val_hi + v)), cmem(cu, static_cast<uint16_t>(layout.val_lo + v)));
    }
  }
  // The last border's CU holds the window the line ends with.
  const unsigned last = cu_of(texel_count);
  const int first =
      signed16(cmem(last, layout.pixel), cmem(last, static_cast<uint16_t>(layout.pixel + 1))) - (width - 1);
  for (int j = 0; j < width; ++j) {
    put(first + j, cmem(last, static_cast<uint16_t>(layout.fin_hi + j)),
        cmem(last, static_cast<uint16_t>(layout.fin_lo + j)));
  }
  return true;
}

}  // namespace tessera::forward_texture
