// The host's side of resample_lines.s (array_lines.h).
#include "forward_texture/array_lines.h"

#include "array/isa/ap_isa.h"

namespace tessera::forward_texture {

namespace {

void put32(std::vector<uint8_t>& bytes, std::size_t at, uint32_t value) {
  for (int k = 0; k < 4; ++k) {
    bytes[at + static_cast<std::size_t>(k)] = static_cast<uint8_t>(value >> (24 - 8 * k));
  }
}

CmemBlock word_block(uint16_t address, uint32_t value) {
  CmemBlock block{address, std::vector<uint8_t>(4)};
  put32(block.bytes, 0, value);
  return block;
}

// The bytes of `blocks` at `address`, which one of them holds.
const CmemBlock& block_at(const std::vector<CmemBlock>& blocks, uint16_t address) {
  for (const CmemBlock& block : blocks) {
    if (block.address == address) {
      return block;
    }
  }
  return blocks.front();  // result_blocks lists every address scatter_line reads
}

int16_t signed16(uint8_t high, uint8_t low) {
  return static_cast<int16_t>(static_cast<uint16_t>((high << 8) | low));
}

}  // namespace

ArrayLineLayout ArrayLineLayout::of(const ap::Program& program) {
  ArrayLineLayout m;
  m.max_texels = ap::constant_value(program, "MAX_TEXELS");
  m.max_width = ap::constant_value(program, "MAX_WIDTH");
  const auto texel_plane = static_cast<unsigned>(m.max_texels + 2);
  const auto result_plane = static_cast<unsigned>(m.max_texels + 1);
  const auto width = static_cast<unsigned>(m.max_width);
  const auto at = [&program](const char* name, unsigned size) { return ap::variable_address(program, name, size); };
  m.num = at("num", 4);
  m.num_step = at("num_step", 4);
  m.den = at("den", 4);
  m.den_step = at("den_step", 4);
  m.tex_hi = at("tex_hi", texel_plane);
  m.tex_lo = at("tex_lo", texel_plane);
  m.offset = at("offset", 4);
  m.q_hi = at("q_hi", width);
  m.q_lo = at("q_lo", width);
  m.r_j = at("r_j", width);
  m.two_f = at("two_f", 1);
  m.zero = at("zero", 1);
  m.ff = at("ff", 1);
  m.c80 = at("c80", 1);
  m.c40 = at("c40", 1);
  m.cc0 = at("cc0", 1);
  m.none = at("none", 1);
  m.limit = at("limit", 4);
  m.clamp = at("clamp", 3);
  m.idx_hi = at("idx_hi", result_plane);
  m.idx_lo = at("idx_lo", result_plane);
  m.val_hi = at("val_hi", result_plane);
  m.val_lo = at("val_lo", result_plane);
  m.last_pixel = at("last_pixel", 2);
  m.fin_hi = at("fin_hi", width);
  m.fin_lo = at("fin_lo", width);
  m.err = at("err", 1);
  return m;
}

std::string array_line_error(const ArrayLineLayout& layout, const FilterTable& table, int texel_count) {
  if (table.kind != FilterKind::box) {
    return std::string(
               "the J2210 program computes the box filter's factors only (it has no shared table to look "
               "up the ") +
           filter_name(table.kind) + "'s): use filter box";
  }
  if (table.width < 1 || table.width > layout.max_width) {
    return "filter width F = " + std::to_string(table.width) + " is beyond the array program's window of 1 .. " +
           std::to_string(layout.max_width) + " pixels";
  }
  if (texel_count < 1 || texel_count > layout.max_texels) {
    return "a line of " + std::to_string(texel_count) + " texels does not fit the array program's CMEM budget of " +
           std::to_string(layout.max_texels) + " texels a line";
  }
  return {};
}

std::vector<uint64_t> program_for_lines(const ap::Program& program, int texel_count, int width) {
  const auto max_texels = static_cast<uint16_t>(ap::constant_value(program, "MAX_TEXELS"));
  const auto last_slot = static_cast<uint16_t>(ap::constant_value(program, "MAX_WIDTH") - 1);
  std::vector<uint64_t> words = program.words;
  for (uint64_t& word : words) {
    ap::Decoded decoded = ap::decode(word);
    ap::Instruction& instruction = decoded.instruction;
    if (!decoded.error.empty() || instruction.opcode != ap::Opcode::op_loop) {
      continue;
    }
    // The loop's start is in a (ap_isa.h).
    if (instruction.a.value == max_texels) {
      instruction.a.value = static_cast<uint16_t>(texel_count);
    } else if (instruction.a.value == last_slot) {
      instruction.a.value = static_cast<uint16_t>(width - 1);
    } else {
      continue;
    }
    word = ap::encode(instruction);
  }
  return words;
}

std::vector<CmemBlock> filter_blocks(const ArrayLineLayout& layout, int width) {
  const auto f = static_cast<uint32_t>(width);
  const uint32_t divisor = 2u * f;
  std::vector<CmemBlock> blocks;
  // s = x + (F - 1) / 2 + half a phase step (resample_line's offset).
  blocks.push_back(word_block(layout.offset, (f - 1u) * (static_cast<uint32_t>(Q16_16_ONE) / 2u) +
                                                 (static_cast<uint32_t>(Q16_16_ONE) >> (PHASE_BITS + 1))));
  // Slot j's share of the box's table row: 65536 (F - 1 - j) + F = q_j 2F + r_j.
  CmemBlock q_hi{layout.q_hi, std::vector<uint8_t>(static_cast<std::size_t>(layout.max_width), 0)};
  CmemBlock q_lo{layout.q_lo, q_hi.bytes};
  CmemBlock r_j{layout.r_j, q_hi.bytes};
  for (uint32_t j = 0; j < f; ++j) {
    const uint32_t constant = 65536u * (f - 1u - j) + f;
    const uint32_t quotient = constant / divisor;
    q_hi.bytes[j] = static_cast<uint8_t>(quotient >> 8);
    q_lo.bytes[j] = static_cast<uint8_t>(quotient);
    r_j.bytes[j] = static_cast<uint8_t>(constant - quotient * divisor);
  }
  blocks.push_back(q_hi);
  blocks.push_back(q_lo);
  blocks.push_back(r_j);
  blocks.push_back({layout.two_f, {static_cast<uint8_t>(divisor)}});
  blocks.push_back({layout.zero, {0x00}});
  blocks.push_back({layout.ff, {0xff}});
  blocks.push_back({layout.c80, {0x80}});
  blocks.push_back({layout.c40, {0x40}});
  blocks.push_back({layout.cc0, {0xc0}});
  blocks.push_back({layout.none, {0x80}});
  blocks.push_back(word_block(layout.limit, static_cast<uint32_t>(Q16_16_ONE) + 1u));
  blocks.push_back({layout.clamp, {0x00, 0xff, 0x01}});
  return blocks;
}

bool orient_line(const LineMapping& mapping, int texel_count, ArrayLine& line) {
  // step_borders' last values: n steps of 32-bit additions, in range (the
  // set-up checked the line's ends).
  const auto n = static_cast<uint32_t>(texel_count);
  const auto last_numerator =
      static_cast<q12_20>(static_cast<uint32_t>(mapping.numerator) + n * static_cast<uint32_t>(mapping.numerator_step));
  const auto last_denominator = static_cast<q2_30>(static_cast<uint32_t>(mapping.denominator) +
                                                   n * static_cast<uint32_t>(mapping.denominator_step));
  q16_16 first = 0;
  q16_16 last = 0;
  if (!divide_border(mapping.numerator, mapping.denominator, first) ||
      !divide_border(last_numerator, last_denominator, last)) {
    return false;
  }
  line.reversed = last < first;
  line.mapping = mapping;
  if (line.reversed) {
    line.mapping = {last_numerator, static_cast<q12_20>(0u - static_cast<uint32_t>(mapping.numerator_step)),
                    last_denominator, static_cast<q2_30>(0u - static_cast<uint32_t>(mapping.denominator_step))};
  }
  return true;
}

std::vector<CmemBlock> line_blocks(const ArrayLineLayout& layout, const ArrayLine& line, LineView texels) {
  const int n = texels.count;
  std::vector<CmemBlock> blocks;
  blocks.push_back(word_block(layout.num, static_cast<uint32_t>(line.mapping.numerator)));
  blocks.push_back(word_block(layout.num_step, static_cast<uint32_t>(line.mapping.numerator_step)));
  blocks.push_back(word_block(layout.den, static_cast<uint32_t>(line.mapping.denominator)));
  blocks.push_back(word_block(layout.den_step, static_cast<uint32_t>(line.mapping.denominator_step)));
  // C_k (the k-th texel from the left) at index n - k; 0 at 0 and n + 1.
  CmemBlock high{layout.tex_hi, std::vector<uint8_t>(static_cast<std::size_t>(n) + 2, 0)};
  CmemBlock low{layout.tex_lo, high.bytes};
  for (int k = 0; k < n; ++k) {
    const auto value = static_cast<uint32_t>(texels[line.reversed ? n - 1 - k : k]);
    high.bytes[static_cast<std::size_t>(n - k)] = static_cast<uint8_t>(value >> 8);
    low.bytes[static_cast<std::size_t>(n - k)] = static_cast<uint8_t>(value);
  }
  blocks.push_back(high);
  blocks.push_back(low);
  return blocks;
}

std::vector<CmemBlock> result_blocks(const ArrayLineLayout& layout, int texel_count, int width) {
  const auto borders = static_cast<std::size_t>(texel_count) + 1;
  const auto slots = static_cast<std::size_t>(width);
  return {{layout.idx_hi, std::vector<uint8_t>(borders)}, {layout.idx_lo, std::vector<uint8_t>(borders)},
          {layout.val_hi, std::vector<uint8_t>(borders)}, {layout.val_lo, std::vector<uint8_t>(borders)},
          {layout.last_pixel, std::vector<uint8_t>(2)},   {layout.fin_hi, std::vector<uint8_t>(slots)},
          {layout.fin_lo, std::vector<uint8_t>(slots)},   {layout.err, std::vector<uint8_t>(1)}};
}

bool scatter_line(const ArrayLineLayout& layout, int texel_count, int width, const std::vector<CmemBlock>& results,
                  LineView pixels) {
  if (block_at(results, layout.err).bytes[0] != 0) {
    return false;
  }
  for (int p = 0; p < pixels.count; ++p) {
    pixels[p] = 0;
  }
  const auto put = [&pixels](int pixel, uint8_t high, uint8_t low) {
    if (pixel >= 0 && pixel < pixels.count) {
      pixels[pixel] = (high << 8) | low;
    }
  };
  const std::vector<uint8_t>& idx_hi = block_at(results, layout.idx_hi).bytes;
  const std::vector<uint8_t>& idx_lo = block_at(results, layout.idx_lo).bytes;
  const std::vector<uint8_t>& val_hi = block_at(results, layout.val_hi).bytes;
  const std::vector<uint8_t>& val_lo = block_at(results, layout.val_lo).bytes;
  // The window's last pixel is numbered; its first is F - 1 to the left.
  for (int v = 0; v <= texel_count; ++v) {
    const auto slot = static_cast<std::size_t>(v);
    if (idx_hi[slot] != 0x80) {
      put(signed16(idx_hi[slot], idx_lo[slot]) - (width - 1), val_hi[slot], val_lo[slot]);
    }
  }
  const std::vector<uint8_t>& last = block_at(results, layout.last_pixel).bytes;
  const std::vector<uint8_t>& fin_hi = block_at(results, layout.fin_hi).bytes;
  const std::vector<uint8_t>& fin_lo = block_at(results, layout.fin_lo).bytes;
  const int first = signed16(last[0], last[1]) - (width - 1);
  for (int j = 0; j < width; ++j) {
    put(first + j, fin_hi[static_cast<std::size_t>(j)], fin_lo[static_cast<std::size_t>(j)]);
  }
  return true;
}

}  // namespace tessera::forward_texture
