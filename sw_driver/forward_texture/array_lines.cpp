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
  m.table_factors = ap::constant_value(program, "TABLE_FACTORS") != 0;
  m.offset = at("offset", 4);
  if (m.table_factors) {
    m.slot_hi = at("slot_hi", width);
  } else {
    m.q_hi = at("q_hi", width);
    m.q_lo = at("q_lo", width);
    m.r_j = at("r_j", width);
    m.two_f = at("two_f", 1);
  }
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

std::string array_line_error(const ArrayLineLayout& layout, const FilterTable& table, int texel_count,
                             unsigned lut_table_entries) {
  if (!layout.table_factors && table.kind != FilterKind::box) {
    return std::string(
               "the J2210 program computes the box filter's factors only (it has no shared table to look "
               "up the ") +
           filter_name(table.kind) + "'s): use filter box";
  }
  if (table.width < 1 || table.width > layout.max_width) {
    return "filter width F = " + std::to_string(table.width) + " is beyond the array program's window of 1 .. " +
           std::to_string(layout.max_width) + " pixels";
  }
  const auto needed = static_cast<unsigned>(PHASES * table.width);
  if (layout.table_factors && lut_table_entries == 0) {
    return "the array program looks the filter's factors up in the shared lookup table, which this array has "
           "not (array.features.lut = false)";
  }
  if (layout.table_factors && needed > lut_table_entries) {
    return "filter width F = " + std::to_string(table.width) + " needs " + std::to_string(needed) +
           " lookup table entries (" + std::to_string(PHASES) +
           " phases x F), more than array.lut.entries = " + std::to_string(lut_table_entries);
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

std::vector<uint16_t> lut_entries(const FilterTable& table) {
  const auto width = static_cast<std::size_t>(table.width);
  std::vector<uint16_t> entries(PHASES * width);
  for (std::size_t slot = 0; slot < width; ++slot) {
    const int j = table.width - 1 - static_cast<int>(slot);
    for (int phase = 0; phase < PHASES; ++phase) {
      entries[PHASES * slot + static_cast<std::size_t>(phase)] = table.at(phase, j);
    }
  }
  return entries;
}

std::vector<CmemBlock> filter_blocks(const ArrayLineLayout& layout, int width) {
  const auto f = static_cast<uint32_t>(width);
  const uint32_t divisor = 2u * f;
  std::vector<CmemBlock> blocks;
  // s = x + (F - 1) / 2 + half a phase step (resample_line's offset).
  blocks.push_back(word_block(layout.offset, (f - 1u) * (static_cast<uint32_t>(Q16_16_ONE) / 2u) +
                                                 (static_cast<uint32_t>(Q16_16_ONE) >> (PHASE_BITS + 1))));
  const std::vector<uint8_t> slots(static_cast<std::size_t>(layout.max_width), 0);
  if (layout.table_factors) {
    // Slot j's entries start at 256 (F - 1 - j) (lut_entries).
    CmemBlock slot_hi{layout.slot_hi, slots};
    for (uint32_t j = 0; j < f; ++j) {
      slot_hi.bytes[j] = static_cast<uint8_t>(f - 1u - j);
    }
    blocks.push_back(slot_hi);
  } else {
    // Slot j's share of the box's table row: 65536 (F - 1 - j) + F = q_j 2F + r_j.
    CmemBlock q_hi{layout.q_hi, slots};
    CmemBlock q_lo{layout.q_lo, slots};
    CmemBlock r_j{layout.r_j, slots};
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
  }
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

bool orient_line(const LineMapping& mapping, LineView texels, ArrayLine& line) {
  // step_borders' last values: n steps of 32-bit additions, in range (the
  // set-up checked the line's ends).
  const auto n = static_cast<uint32_t>(texels.count);
  const auto last_numerator =
      static_cast<q12_20>(static_cast<uint32_t>(mapping.numerator) + n * static_cast<uint32_t>(mapping.numerator_step));
  const auto last_denominator = static_cast<q2_30>(static_cast<uint32_t>(mapping.denominator) +
                                                   n * static_cast<uint32_t>(mapping.denominator_step));
  if (!divide_border(mapping.numerator, mapping.denominator, line.first_border) ||
      !divide_border(last_numerator, last_denominator, line.last_border)) {
    return false;
  }
  line.texels = texels;
  line.reversed = line.last_border < line.first_border;
  line.mapping = mapping;
  if (line.reversed) {
    line.mapping = {last_numerator, static_cast<q12_20>(0u - static_cast<uint32_t>(mapping.numerator_step)),
                    last_denominator, static_cast<q2_30>(0u - static_cast<uint32_t>(mapping.denominator_step))};
  }
  return true;
}

std::vector<CmemRow> line_rows(const ArrayLineLayout& layout, const std::vector<ArrayLine>& lines, unsigned cus) {
  const int n = lines.empty() ? 0 : lines.front().texels.count;
  std::vector<CmemRow> rows;
  const auto word_rows = [&rows, &lines, cus](uint16_t address, int32_t LineMapping::*member) {
    for (unsigned byte = 0; byte < 4; ++byte) {
      CmemRow row{static_cast<uint16_t>(address + byte), std::vector<uint8_t>(cus, 0)};
      for (std::size_t k = 0; k < lines.size(); ++k) {
        row.per_cu[k] = static_cast<uint8_t>(static_cast<uint32_t>(lines[k].mapping.*member) >> (24 - 8 * byte));
      }
      rows.push_back(row);
    }
  };
  word_rows(layout.num, &LineMapping::numerator);
  word_rows(layout.num_step, &LineMapping::numerator_step);
  word_rows(layout.den, &LineMapping::denominator);
  word_rows(layout.den_step, &LineMapping::denominator_step);
  // C_k (the k-th texel from the left) at index n - k; 0 at 0 and n + 1.
  const std::size_t first_texel_row = rows.size();
  for (int index = 0; index <= n + 1; ++index) {
    rows.push_back({static_cast<uint16_t>(layout.tex_hi + index), std::vector<uint8_t>(cus, 0)});
  }
  for (int index = 0; index <= n + 1; ++index) {
    rows.push_back({static_cast<uint16_t>(layout.tex_lo + index), std::vector<uint8_t>(cus, 0)});
  }
  CmemRow* high = &rows[first_texel_row];
  CmemRow* low = high + n + 2;
  for (std::size_t lane = 0; lane < lines.size(); ++lane) {
    const ArrayLine& line = lines[lane];
    for (int k = 0; k < n; ++k) {
      const auto value = static_cast<uint32_t>(line.texels[line.reversed ? n - 1 - k : k]);
      high[n - k].per_cu[lane] = static_cast<uint8_t>(value >> 8);
      low[n - k].per_cu[lane] = static_cast<uint8_t>(value);
    }
  }
  return rows;
}

// result_addresses' order: the border planes idx_hi, idx_lo, val_hi,
// val_lo (n + 1 rows each), last_pixel (2), fin_hi, fin_lo (F each), err.
std::vector<uint16_t> result_addresses(const ArrayLineLayout& layout, int texel_count, int width) {
  std::vector<uint16_t> addresses;
  for (const uint16_t plane : {layout.idx_hi, layout.idx_lo, layout.val_hi, layout.val_lo}) {
    for (int v = 0; v <= texel_count; ++v) {
      addresses.push_back(static_cast<uint16_t>(plane + v));
    }
  }
  addresses.push_back(layout.last_pixel);
  addresses.push_back(static_cast<uint16_t>(layout.last_pixel + 1));
  for (const uint16_t plane : {layout.fin_hi, layout.fin_lo}) {
    for (int j = 0; j < width; ++j) {
      addresses.push_back(static_cast<uint16_t>(plane + j));
    }
  }
  addresses.push_back(layout.err);
  return addresses;
}

bool scatter_line(int texel_count, int width, const std::vector<CmemRow>& results, unsigned lane, LineView pixels) {
  const auto borders = static_cast<std::size_t>(texel_count) + 1;
  const auto byte = [&results, lane](std::size_t row) { return results[row].per_cu[lane]; };
  const std::size_t last = 4 * borders;
  const std::size_t fin = last + 2;
  const std::size_t err = fin + 2 * static_cast<std::size_t>(width);
  if (byte(err) != 0) {
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
  // The window's last pixel is numbered; the pixel leaving is F - 1 to its left.
  for (std::size_t v = 0; v < borders; ++v) {
    if (byte(v) != 0x80) {
      put(signed16(byte(v), byte(borders + v)) - (width - 1), byte(2 * borders + v), byte(3 * borders + v));
    }
  }
  const int first = signed16(byte(last), byte(last + 1)) - (width - 1);
  const auto slots = static_cast<std::size_t>(width);
  for (std::size_t j = 0; j < slots; ++j) {
    put(first + static_cast<int>(j), byte(fin + j), byte(fin + slots + j));
  }
  return true;
}

}  // namespace tessera::forward_texture
