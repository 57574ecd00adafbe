// ap-tile's CMEM traffic through the system/array DMA (README.md, "With the
// DMA"), on the host model: the staging buffers in system memory, the
// descriptors of the transfers whose addresses never change (a pass's
// records, the read-back's chunks) written once as chains, and the
// channels. The renderer decides what moves when and charges the host time
// to its split; this class stages the bytes, describes them, starts and
// waits, and counts the descriptors and the array's data-line traffic.
#pragma once

#include <cstdint>
#include <vector>

#include "device/app_environment.h"
#include "device/dma_driver.h"
#include "renderers/ap_tile/tile_setup.h"
#include "renderers/ap_tile/tile_study.h"
#include "renderers/common/array_dma.h"

namespace tessera::ap_tile {

// What the DMA's staging needs of the running program's CMEM layout (the
// tuned program's or the study's).
struct DmaLayout {
  unsigned tile_height = 0;
  uint16_t record_first = 0, record_bytes = 0;
  // The record byte (from record_first) that is 0 in a dead slot, or -1
  // when the program has none (the study's: every record written is live).
  int live = -1;
  // The bytes (from record_first) a slot gets when its CU has no triangle;
  // the study's program also starts every slot so.
  std::vector<std::pair<uint16_t, uint8_t>> dead;
  // The planes read back, in chain order: the texture planes (tid, s, t)
  // first, then the colour planes, so that an untextured chunk starts the
  // same chain at its first colour plane.
  std::vector<uint16_t> read_planes;
  unsigned colour_planes = 0;
  // Constants sent at once, at most (the staging's descriptors).
  unsigned max_constants = 0;

  static DmaLayout of(const CmemLayout& layout);
  static DmaLayout of(const StudyLayout& layout);
};

class TileDma {
 public:
  // Allocates the staging buffers (gl::allocate), clears the record
  // buffers and writes the chains. `broadcast`: constants go by broadcast
  // descriptors, else by reshuffles (each CU its copy).
  TileDma(AppEnvironment& env, DmaDriver& dma, const DmaLayout& layout, const FrameGeometry& frame, bool broadcast);

  // A value the same in every CU: `bytes` to CMEM `cmem`, `cmem` + 1, ...
  struct Constant {
    uint16_t cmem = 0;
    std::vector<uint8_t> bytes;
  };
  // Stages the constants and `per_cu` (one byte per CU, in CU order, at
  // its `cmem`: a reshuffle whatever the broadcast), sends them on the
  // input channel as one chain and waits for it.
  void send_constants(const std::vector<Constant>& constants, const std::vector<Constant>& per_cu = {});

  // Stages a pass's records in buffer `buffer` (0 or 1): `bytes` holds
  // every CU's record (record_bytes each, in CU order), of which the CUs
  // with `has_record` set are written; a CU without one whose slot still
  // holds a live record gets live = 0 (the program draws nothing in a CU
  // whose live is 0, whatever the rest of its record). The buffer must not
  // be in use by a DMA.
  void stage_records(unsigned buffer, const std::vector<uint8_t>& bytes, const std::vector<bool>& has_record);
  // One reshuffle on the input channel: buffer `buffer` to every CU's record.
  void start_records(unsigned buffer);
  void wait_input() { wait(INPUT); }

  // The read-back in chunks: chunk x is tile column x of every tile, of the
  // colour planes and, when `textured`, of tid, s and t; on channel x % 2.
  unsigned chunks() const { return m_frame.tile_width; }
  void start_chunk(unsigned x, bool textured);
  void wait_chunk(unsigned x) { wait(x % 2); }
  // Where row l of tile column x of `plane` (one of the layout's
  // read_planes) landed: one byte per CU, in CU order.
  uint32_t staged_row(uint16_t plane, unsigned x, unsigned l) const;

  const renderers::ArrayTraffic& traffic() const { return m_traffic; }

 private:
  static constexpr unsigned INPUT = 0;  // the channel of every write into CMEM

  // Sleeps until `channel`'s interrupt; a DmaError names the renderer.
  void wait(unsigned channel);
  uint32_t chunk_chain(unsigned x, bool textured) const;

  HostApi& m_host;
  DmaDriver& m_dma;
  DmaLayout m_layout;
  FrameGeometry m_frame;
  bool m_broadcast;
  unsigned m_cus;
  unsigned m_read_planes;  // m_layout.read_planes.size()

  uint32_t m_records[2]{};             // per buffer: record byte r of CU k at + r * cus + k
  uint32_t m_record_chains[2]{};       // per buffer: its reshuffle
  uint32_t m_frame_staging = 0;        // per read-back plane: the plane, row r at + r * cus
  uint32_t m_chunk_chains = 0;         // per chunk: a descriptor per read plane
  uint32_t m_constants = 0;            // the constants' bytes (each CU's copy for a reshuffle)
  uint32_t m_constant_chain = 0;       // the constants' descriptors
  std::vector<bool> m_staged_live[2];  // per buffer and CU: its slot's live byte is set

  renderers::ArrayTraffic m_traffic;
};

}  // namespace tessera::ap_tile
