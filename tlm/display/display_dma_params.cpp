// The display DMA's parameters: display_dma.*.
#include "display/display_dma.h"

namespace tessera {

ParamGroup DisplayDmaParams::parameters() {
  using param::integer;
  return {"display_dma",
          {
              integer("display_dma.burst_beats", 16, 1, 256, "beats", "burst length of the display DMA's fetches"),
              integer("display_dma.fifo_lines", 1, 1, 16, "lines",
                      "line buffer of the display DMA: how many lines ahead it may fetch"),
          },
          {}};
}

DisplayDmaParams DisplayDmaParams::from_config(const Config& config) {
  DisplayDmaParams p;
  p.burst_beats = static_cast<unsigned>(config.get_uint("display_dma.burst_beats"));
  p.fifo_lines = static_cast<unsigned>(config.get_uint("display_dma.fifo_lines"));
  return p;
}

DisplayDmaParams DisplayDmaParams::defaults() {
  return from_config(Config({parameters()}));
}

}  // namespace tessera
