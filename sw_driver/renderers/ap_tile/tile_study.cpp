#include "renderers/ap_tile/tile_study.h"

#include <algorithm>
#include <cstring>
#include <stdexcept>

namespace tessera::ap_tile {

namespace {

void put16(uint8_t* at, uint16_t value) {
  at[0] = static_cast<uint8_t>(value >> 8);
  at[1] = static_cast<uint8_t>(value);
}

}  // namespace

unsigned cmem_extent(const ap::Program& program) {
  unsigned end = 0;
  for (const auto& [name, variable] : program.variables)
    end = std::max<unsigned>(end, variable.address + variable.size);
  return end;
}

StudyLayout StudyLayout::of(const ap::Program& program) {
  StudyLayout m;
  m.tile_width = static_cast<unsigned>(ap::constant_value(program, "TILE_W"));
  m.tile_height = static_cast<unsigned>(ap::constant_value(program, "TILE_H"));
  const unsigned pixels = m.tile_width * m.tile_height;
  struct Field {
    uint16_t StudyLayout::*member;
    const char* name;
    unsigned size;
  };
  const Field planes[] = {{&StudyLayout::rg_hi, "rg_hi", pixels}, {&StudyLayout::rg_lo, "rg_lo", pixels},
                          {&StudyLayout::b, "b", pixels},         {&StudyLayout::zb_hi, "zb_hi", pixels},
                          {&StudyLayout::zb_lo, "zb_lo", pixels}, {&StudyLayout::we, "we", pixels},
                          {&StudyLayout::s_hi, "s_hi", pixels},   {&StudyLayout::s_lo, "s_lo", pixels},
                          {&StudyLayout::t_hi, "t_hi", pixels},   {&StudyLayout::t_lo, "t_lo", pixels},
                          {&StudyLayout::tid, "tid", pixels}};
  const Field record[] = {{&StudyLayout::line_a, "line_a", 6},   {&StudyLayout::line_b, "line_b", 6},
                          {&StudyLayout::line_c, "line_c", 6},   {&StudyLayout::z_start, "z_start", 2},
                          {&StudyLayout::z_dx, "z_dx", 2},       {&StudyLayout::z_dy, "z_dy", 2},
                          {&StudyLayout::c_start, "c_start", 6}, {&StudyLayout::c_dx, "c_dx", 6},
                          {&StudyLayout::c_dy, "c_dy", 6},       {&StudyLayout::st_start, "st_start", 4},
                          {&StudyLayout::st_dx, "st_dx", 4},     {&StudyLayout::st_dy, "st_dy", 4},
                          {&StudyLayout::tex, "tex", 1}};
  const Field others[] = {{&StudyLayout::xpos, "xpos", 1},
                          {&StudyLayout::ypos, "ypos", 1},
                          {&StudyLayout::one, "one", 1},
                          {&StudyLayout::ff, "ff", 1},
                          {&StudyLayout::xcounter, "xcounter", m.tile_width},
                          {&StudyLayout::ycounter, "ycounter", m.tile_height},
                          {&StudyLayout::clear_rg, "clear_rg", 2},
                          {&StudyLayout::clear_b, "clear_b", 1},
                          {&StudyLayout::clear_z, "clear_z", 2},
                          {&StudyLayout::product, "product", 3},
                          {&StudyLayout::px, "px", 2},
                          {&StudyLayout::py, "py", 2},
                          {&StudyLayout::erow, "erow", 2},
                          {&StudyLayout::ev, "ev", 2},
                          {&StudyLayout::zrow, "zrow", 2},
                          {&StudyLayout::zv, "zv", 2},
                          {&StudyLayout::flag, "flag", 1},
                          {&StudyLayout::crow, "crow", 6},
                          {&StudyLayout::cv, "cv", 6},
                          {&StudyLayout::rgw, "rgw", 2},
                          {&StudyLayout::bw, "bw", 1},
                          {&StudyLayout::strow, "strow", 4},
                          {&StudyLayout::stv, "stv", 4}};
  for (const Field& field : planes) m.*field.member = ap::variable_address(program, field.name, field.size);
  for (const Field& field : others) m.*field.member = ap::variable_address(program, field.name, field.size);
  unsigned first = ~0u, end = 0, bytes = 0;
  for (const Field& field : record) {
    m.*field.member = ap::variable_address(program, field.name, field.size);
    first = std::min<unsigned>(first, m.*field.member);
    end = std::max<unsigned>(end, m.*field.member + field.size);
    bytes += field.size;
  }
  if (end - first != bytes)
    throw std::invalid_argument(program.source_name + ": the study's record (line_a .. tex) is not contiguous in CMEM");
  m.record_first = static_cast<uint16_t>(first);
  m.record_bytes = static_cast<uint16_t>(bytes);
  m.cmem_bytes = cmem_extent(program);
  return m;
}

void encode_study_record(const StudyRecord& record, const StudyLayout& layout, uint8_t* bytes) {
  std::memset(bytes, 0, layout.record_bytes);
  auto at = [&](uint16_t address) { return bytes + (address - layout.record_first); };
  if (!record.live) {
    put16(at(layout.line_c), 0xffff);
    return;
  }
  for (unsigned e = 0; e < 3; ++e) {
    put16(at(layout.line_a) + 2 * e, static_cast<uint16_t>(record.a[e]));
    put16(at(layout.line_b) + 2 * e, static_cast<uint16_t>(record.b[e]));
    put16(at(layout.line_c) + 2 * e, static_cast<uint16_t>(record.c[e]));
    put16(at(layout.c_start) + 2 * e, record.colour[e]);
    put16(at(layout.c_dx) + 2 * e, record.c_dx[e]);
    put16(at(layout.c_dy) + 2 * e, record.c_dy[e]);
  }
  put16(at(layout.z_start), record.z);
  put16(at(layout.z_dx), record.z_dx);
  put16(at(layout.z_dy), record.z_dy);
  for (unsigned k = 0; k < 2; ++k) {
    put16(at(layout.st_start) + 2 * k, record.st[k]);
    put16(at(layout.st_dx) + 2 * k, record.st_dx[k]);
    put16(at(layout.st_dy) + 2 * k, record.st_dy[k]);
  }
  *at(layout.tex) = record.tex;
}

}  // namespace tessera::ap_tile
