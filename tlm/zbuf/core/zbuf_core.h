// The z-buffer unit's functional core, plain C++: a depth plane and a colour
// plane of 16-bit entries beside the array (Davila et al., "the Z-buffer":
// "this matrix stores the 'z' value and the colour of the current pixel in
// the position 'x' and 'y' ... the new pixel colours and 'z' value is only
// stored if this new 'z' coordinate is smaller than the current 'z'"), and
// the ports through which the array's zsend delivers pixels.
//
// The frame: a window of width x height entries at the screen position
// (origin_x, origin_y), entry (y - origin_y) x width + (x - origin_x); a
// screen larger than the unit is drawn in bands, the window moved between
// them. A pixel outside the window is clipped (it still takes its port slot).
//
// The depth test is GL_LESS on 16-bit unsigned depth: a pixel is written,
// depth and colour, where z < the entry's depth.
//
// Ports and cycles: each port takes one pixel per array cycle. The pixels of
// one send are taken in ascending lanes, `ports` per cycle, none before it
// reaches the port (under row-sequential issue row r's pixels arrive r x K
// cycles after the zsend's issue; ap::SendArrival) nor before the previous
// send's last pixel (sends are taken in program order); with
// pair_halves_only (the paper's rule: "we can send two pixels at times,
// because they belong to the same triangle ... so they cannot address the
// same pixel") a cycle takes pixels of one pair of CUs only, lanes 2k and
// 2k + 1 (two neighbouring columns of a row, the two halves of one triangle),
// so more than 2 ports add nothing.
//
// The order rule: pixels of one cycle that hit the same entry are tested one
// after the other in ascending lanes (the port of the higher lane compares
// with the lower lane's result, forwarded), and a cycle sees every earlier
// cycle's writes. The planes after a send are therefore those of its pixels
// applied one at a time in ascending lanes, sends in program order
// (tests/zbuf/core: the scalar model), with or without row-sequential issue:
// ascending lanes are the order in which a send's rows arrive.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "array/core/pixel_port.h"

namespace tessera::zbuf {

// The paper's z-buffer: 64K x 16.
inline constexpr unsigned MAX_ENTRIES = 65536;

struct ZbufCoreParams {
  unsigned entries = MAX_ENTRIES;  // zbuf.entries
  unsigned ports = 2;              // zbuf.ports
  bool pair_halves_only = false;   // zbuf.pair_halves_only
};

// Totals since construction.
struct ZbufCounts {
  uint64_t sends = 0;        // send() calls (zsend instructions)
  uint64_t pixels = 0;       // pixels received
  uint64_t written = 0;      // pixels that passed the depth test (depth and colour written)
  uint64_t failed = 0;       // pixels that failed it
  uint64_t clipped = 0;      // pixels outside the frame's window
  uint64_t conflicts = 0;    // pixels that met a lower lane's pixel at the same entry in the same cycle
  uint64_t port_cycles = 0;  // cycles the ports were busy with sends
  uint64_t clears = 0;       // clear() calls
  uint64_t cleared_entries = 0;
};

class ZbufCore : public ap::PixelPort {
 public:
  // Throws std::invalid_argument when entries is 0 or beyond MAX_ENTRIES, or
  // ports is 0 (the configuration refuses them first, naming the key).
  explicit ZbufCore(const ZbufCoreParams& params);

  const ZbufCoreParams& params() const { return m_params; }

  // The frame's window; an empty string, or why it cannot be (width x
  // height beyond the entries), in which case nothing changed.
  std::string set_frame(unsigned origin_x, unsigned origin_y, unsigned width, unsigned height);
  unsigned origin_x() const { return m_origin_x; }
  unsigned origin_y() const { return m_origin_y; }
  unsigned width() const { return m_width; }
  unsigned height() const { return m_height; }
  unsigned frame_entries() const { return m_width * m_height; }

  // Every entry of the window: depth and colour to the values given.
  void clear(uint16_t depth, uint16_t colour);
  // The cycles a clear of the current window takes: `ports` entries a cycle.
  uint64_t clear_cycles() const;

  // PixelPort: tests and writes the pixels; the cycle each is taken in.
  ap::SendTimes send(const std::vector<ap::SentPixel>& pixels, const ap::SendArrival& arrival) override;
  // A lockstep send from cycle 0: the port cycles (the last one + 1).
  uint64_t send(const std::vector<ap::SentPixel>& pixels) { return send(pixels, ap::SendArrival{}).busy; }

  // The cycle (after the send's issue) in which each pixel of a send is
  // taken, by the rule above; in lockstep from 0, the send taking the last
  // one + 1 cycles (0 with no pixels).
  static std::vector<uint64_t> schedule(const std::vector<ap::SentPixel>& pixels, unsigned ports, bool pair_halves_only,
                                        const ap::SendArrival& arrival = {});

  uint16_t depth(unsigned entry) const { return m_depth[entry]; }
  uint16_t colour(unsigned entry) const { return m_colour[entry]; }
  void set_entry(unsigned entry, uint16_t depth, uint16_t colour) {
    m_depth[entry] = depth;
    m_colour[entry] = colour;
  }
  const std::vector<uint16_t>& colour_plane() const { return m_colour; }
  const ZbufCounts& counts() const { return m_counts; }

 private:
  // The entry of (x, y) in the window, or -1 outside it.
  long entry_of(uint16_t x, uint16_t y) const;
  void take_cycle(const ap::SentPixel* pixels, size_t count);

  ZbufCoreParams m_params;
  unsigned m_origin_x = 0, m_origin_y = 0, m_width = 0, m_height = 0;
  std::vector<uint16_t> m_depth, m_colour;
  ZbufCounts m_counts;
};

}  // namespace tessera::zbuf
