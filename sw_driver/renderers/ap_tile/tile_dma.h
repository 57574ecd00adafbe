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
#include "renderers/common/array_dma.h"

namespace tessera::ap_tile {

class TileDma {
 public:
  // Allocates the staging buffers (gl::allocate), clears the record
  // buffers and writes the chains. `broadcast`: constants go by broadcast
  // descriptors, else by reshuffles (each CU its copy).
  TileDma(AppEnvironment& env, DmaDriver& dma, const CmemLayout& layout, const FrameGeometry& frame, bool broadcast);

  // A value the same in every CU: `bytes` to CMEM `cmem`, `cmem` + 1, ...
  struct Constant {
    uint16_t cmem = 0;
    std::vector<uint8_t> bytes;
  };
  // Stages the constants, sends them on the input channel as one chain
  // and waits for it.
  void send_constants(const std::vector<Constant>& constants);

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
  // Where row l of tile column x of `plane` (chi, clo, tid, shi, slo, thi or
  // tlo) landed: one byte per CU, in CU order.
  uint32_t staged_row(uint16_t plane, unsigned x, unsigned l) const;

  const renderers::ArrayTraffic& traffic() const { return m_traffic; }

 private:
  static constexpr unsigned INPUT = 0;  // the channel of every write into CMEM
  // The read-back's planes, in the order of a chunk's chain: a colour-only
  // chunk starts the same chain at its first colour plane.
  static constexpr unsigned READ_PLANES = 7, COLOUR_PLANES = 2;

  // Sleeps until `channel`'s interrupt; a DmaError names the renderer.
  void wait(unsigned channel);
  uint32_t chunk_chain(unsigned x, bool textured) const;

  HostApi& m_host;
  DmaDriver& m_dma;
  CmemLayout m_layout;
  FrameGeometry m_frame;
  bool m_broadcast;
  unsigned m_cus;
  uint16_t m_read_planes[READ_PLANES]{};

  uint32_t m_records[2]{};             // per buffer: record byte r of CU k at + r * cus + k
  uint32_t m_record_chains[2]{};       // per buffer: its reshuffle
  uint32_t m_frame_staging = 0;        // per read-back plane: the plane, row r at + r * cus
  uint32_t m_chunk_chains = 0;         // per chunk: READ_PLANES descriptors
  uint32_t m_constants = 0;            // the constants' bytes (each CU's copy for a reshuffle)
  uint32_t m_constant_chain = 0;       // the constants' descriptors
  std::vector<bool> m_staged_live[2];  // per buffer and CU: its slot's live byte is set

  renderers::ArrayTraffic m_traffic;
};

}  // namespace tessera::ap_tile
