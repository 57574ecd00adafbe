// Driver of the display controller. Reads the display's geometry and mode
// from its registers and presents frames the way the hardware wants:
//  - port mode: the host copies the back buffer into the display port with
//    LDM/STM bursts and writes PRESENT (host time, as on the J2210);
//  - DMA mode: the host writes BACK_BASE and SWAP, then sleeps until the
//    swap-done interrupt (the swap happens at vertical blank), and draws the
//    next frame into the other buffer.
#pragma once

#include <cstdint>
#include <vector>

#include "common/pixel_format.h"
#include "device/app_environment.h"

namespace tessera {

class DisplayDriver {
 public:
  explicit DisplayDriver(AppEnvironment& env);

  unsigned width() const { return m_width; }
  unsigned height() const { return m_height; }
  unsigned bytes_per_pixel() const { return tessera::bytes_per_pixel(m_format); }
  PixelFormat format() const { return m_format; }
  bool dma() const { return m_dma; }
  // The buffer to draw the next frame into.
  uint32_t back_buffer() const { return m_buffers[m_back]; }
  uint32_t stride() const { return m_width * bytes_per_pixel(); }

  // Shows the back buffer; returns when the buffer may be drawn again.
  void present();

 private:
  HostApi& m_host;
  uint32_t m_buffers[2];
  unsigned m_back = 0;
  unsigned m_width;
  unsigned m_height;
  PixelFormat m_format;
  bool m_dma;
#if !defined(TESSERA_HOST_ISS)
  std::vector<uint64_t> m_copy_cycles;  // each copied block's cycles (HostApi::copy_words)
#endif
};

}  // namespace tessera
