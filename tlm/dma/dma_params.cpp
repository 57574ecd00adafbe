// The system/array DMA's parameters: dma.* (README.md, "Data flow and
// timing", gives the reasoning behind each default).
#include <string>

#include "dma/dma.h"
#include "dma/dma_regs.h"

namespace tessera {

ParamGroup DmaParams::parameters() {
  using param::boolean;
  using param::integer;
  return {"dma",
          {
              boolean("dma.enabled", false,
                      "the system/array DMA (proposed hardware) is in the SoC: mapped, on interrupt line 3, in the "
                      "statistics"),
              boolean("dma.broadcast", false, "renderers may use the DMA's broadcast write (a renderer switch)"),
              integer("dma.channels", 2, 1, dma_regs::MAX_CHANNELS, "", "descriptor channels of the DMA"),
              integer("dma.burst_beats", 16, 1, 256, "beats", "longest burst of the DMA's bus accesses"),
              integer("dma.cmem_bytes_per_cycle", 4, 1, 64, "bytes",
                      "bytes the DMA puts on the CUs' shared data lines per array cycle (32 lines, as the CIU's "
                      "WriteMem32 word)"),
              integer("dma.row_buffer_bytes", 256, 16, 65536, "bytes",
                      "the DMA's row buffer: a reshuffle row (CUs x element bytes) must fit"),
          },
          [](const Config& config) {
            // The broadcast is a write of the DMA: without the DMA in the SoC
            // the switch would change nothing, silently.
            if (config.get_bool("dma.broadcast") && !config.get_bool("dma.enabled"))
              throw ConfigError(
                  "configuration: impossible combination: dma.broadcast=true needs dma.enabled=true (the broadcast is "
                  "a write of the system/array DMA, which dma.enabled=false leaves out of the SoC): set "
                  "dma.enabled=true too, or leave dma.broadcast out");
            if (!config.has("array.columns") || !config.has("array.rows")) return;
            const uint64_t row = config.get_uint("dma.row_buffer_bytes");
            const uint64_t lanes = config.get_uint("array.columns") * config.get_uint("array.rows");
            if (config.get_bool("dma.enabled") && row < 2 * lanes)
              throw ConfigError("configuration: impossible combination: dma.row_buffer_bytes=" + std::to_string(row) +
                                " cannot hold a reshuffle row of 2-byte values for " + std::to_string(lanes) +
                                " CUs (array.columns x array.rows x 2)");
          }};
}

DmaParams DmaParams::from_config(const Config& config) {
  DmaParams p;
  p.enabled = config.get_bool("dma.enabled");
  p.broadcast = config.get_bool("dma.broadcast");
  p.channels = static_cast<unsigned>(config.get_uint("dma.channels"));
  p.burst_beats = static_cast<unsigned>(config.get_uint("dma.burst_beats"));
  p.cmem_bytes_per_cycle = static_cast<unsigned>(config.get_uint("dma.cmem_bytes_per_cycle"));
  p.row_buffer_bytes = static_cast<unsigned>(config.get_uint("dma.row_buffer_bytes"));
  return p;
}

DmaParams DmaParams::defaults() {
  return from_config(Config({parameters()}));
}

}  // namespace tessera
