#include "renderers/ap_object/object_reference.h"

#include "common/pixel_format.h"

namespace tessera::ap_object {

namespace {

uint32_t get(const uint8_t* p, unsigned width) {
  uint32_t v = 0;
  for (unsigned i = 0; i < width; ++i) v = v << 8 | p[i];
  return v;
}

void put(uint8_t* p, uint32_t v, unsigned width) {
  for (unsigned i = 0; i < width; ++i) p[i] = static_cast<uint8_t>(v >> (8 * (width - 1 - i)));
}

// a += b over `width` bytes, modulo 2^(8 width); the carry out.
bool add(uint8_t* a, const uint8_t* b, unsigned width) {
  const uint64_t sum = uint64_t{get(a, width)} + get(b, width);
  put(a, static_cast<uint32_t>(sum), width);
  return (sum >> (8 * width)) != 0;
}

// The row's end of the walk (README.md, "The program"): the left end x + Q
// + carry, the remainder corrected and the start values moved a pixel right
// where it carried; then the row steps; then the right end.
void step_edges(const ObjectLayout& m, uint8_t* rec) {
  const bool left_carry = add(rec + m.ul, rec + m.rl, 3);
  if (left_carry) {
    add(rec + m.ul, rec + m.nl, 3);
    add(rec + m.z, rec + m.zgx, 4);
    for (unsigned k = 0; k < 4; ++k) add(rec + m.c + 2 * k, rec + m.cgx + 2 * k, 2);
    if (!m.zsend) {
      add(rec + m.s, rec + m.sgx, 3);
      add(rec + m.t, rec + m.tgx, 3);
    }
  }
  put(rec + m.xl, get(rec + m.xl, 2) + get(rec + m.ql, 2) + (left_carry ? 1 : 0), 2);
  add(rec + m.z, rec + m.zrow, 4);
  for (unsigned k = 0; k < 4; ++k) add(rec + m.c + 2 * k, rec + m.crow + 2 * k, 2);
  if (!m.zsend) {
    add(rec + m.s, rec + m.srow, 3);
    add(rec + m.t, rec + m.trow, 3);
  }
  const bool right_carry = add(rec + m.ur, rec + m.rr, 3);
  if (right_carry) add(rec + m.ur, rec + m.nr, 3);
  put(rec + m.xr, get(rec + m.xr, 2) + get(rec + m.qr, 2) + (right_carry ? 1 : 0), 2);
}

}  // namespace

void run_reference(const ObjectLayout& m, uint8_t* cmem, const unsigned rows[2]) {
  uint8_t* cacc = cmem + m.cacc;
  uint8_t* tacc = cmem + m.tacc;
  for (unsigned h = 0; h < m.units; ++h) {
    uint8_t* rec = cmem + m.record(h);
    for (int l = static_cast<int>(rows[h]) - 1; l >= 0; --l) {
      const auto row = static_cast<unsigned>(l);
      cmem[m.row_plane(h, 0, row)] = rec[m.xl];
      cmem[m.row_plane(h, 1, row)] = rec[m.xl + 1];
      cmem[m.row_plane(h, 2, row)] = rec[m.xr];
      cmem[m.row_plane(h, 3, row)] = rec[m.xr + 1];
      // The span: z in r0..r3, colour in cacc, s in r4..r6, t in tacc.
      uint8_t z[4] = {rec[m.z], rec[m.z + 1], rec[m.z + 2], rec[m.z + 3]};
      for (unsigned k = 0; k < 8; ++k) cacc[k] = rec[m.c + k];
      uint8_t sv[3] = {rec[m.s], rec[m.s + 1], rec[m.s + 2]};
      for (unsigned k = 0; k < 3; ++k) tacc[k] = rec[m.t + k];
      for (unsigned p = 0; p < m.span; ++p) {
        for (unsigned b = 0; b < 3; ++b) cmem[m.slot(h, p, b, row)] = z[b];
        for (unsigned k = 0; k < 4; ++k) cmem[m.slot(h, p, 3 + k, row)] = cacc[2 * k];
        for (unsigned b = 0; b < 3; ++b) {
          cmem[m.slot(h, p, 7 + b, row)] = sv[b];
          cmem[m.slot(h, p, 10 + b, row)] = tacc[b];
        }
        add(z, rec + m.zgx, 4);
        for (unsigned k = 0; k < 4; ++k) add(cacc + 2 * k, rec + m.cgx + 2 * k, 2);
        add(sv, rec + m.sgx, 3);
        add(tacc, rec + m.tgx, 3);
      }
      step_edges(m, rec);
    }
  }
}

void run_reference_zsend(const ObjectLayout& m, uint8_t* cmem, const unsigned rows[2], std::vector<ZsendPixel>& sent) {
  uint8_t* zacc = cmem + m.zacc;
  uint8_t* cacc = cmem + m.cacc;
  uint8_t* pos = cmem + m.pos;
  uint8_t* pix = cmem + m.pix;
  for (unsigned h = 0; h < m.units; ++h) {
    uint8_t* rec = cmem + m.record(h);
    for (int l = static_cast<int>(rows[h]) - 1; l >= 0; --l) {
      put(pos, get(rec + m.xl, 2) + get(rec + m.ofs, 2), 2);
      pos[2] = rec[m.yw];
      pos[3] = rec[m.yw + 1];
      // Pixels left to the right end, signed; none on a row past the piece.
      auto count = static_cast<int16_t>(get(rec + m.xr, 2) - get(pos, 2));
      if (rec[m.nrows] == 0)
        count = static_cast<int16_t>(static_cast<uint16_t>(count) | 0xff00);
      else
        --rec[m.nrows];
      for (unsigned k = 0; k < 4; ++k) zacc[k] = rec[m.z + k];
      for (unsigned k = 0; k < 6; ++k) cacc[k] = rec[m.c + k];
      for (unsigned p = 0; p < m.span; ++p) {
        // As the host path's fragment_of and write_fragment.
        const uint32_t top = zacc[0];
        const auto z = static_cast<uint16_t>(top >= 0x80 ? 0 : top != 0 ? 0xffff : zacc[1] << 8 | zacc[2]);
        const auto colour = static_cast<uint16_t>(
            pack_pixel(PixelFormat::rgb565, uint32_t{cacc[0]} | uint32_t{cacc[2]} << 8 | uint32_t{cacc[4]} << 16));
        put(pix, z, 2);
        put(pix + 2, colour, 2);
        if (count >= 0)
          sent.push_back(
              ZsendPixel{static_cast<uint16_t>(get(pos, 2)), static_cast<uint16_t>(get(pos + 2, 2)), z, colour});
        put(pos, get(pos, 2) + 1, 2);
        count = static_cast<int16_t>(count - 1);
        add(zacc, rec + m.zgx, 4);
        for (unsigned k = 0; k < 3; ++k) add(cacc + 2 * k, rec + m.cgx + 2 * k, 2);
      }
      put(rec + m.yw, get(rec + m.yw, 2) - 1, 2);
      step_edges(m, rec);
    }
  }
}

}  // namespace tessera::ap_object
