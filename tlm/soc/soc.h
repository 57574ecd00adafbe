// The SoC assembled from one Config: host, bus, system memory, display and
// rasterizer, bound by the memory map (memory_map.def) and the interrupt map
// (irq_map.def). What is recorded of the run (frame records, power windows,
// statistics, the VCD trace) is its recorder's (soc_recorder.h).
#pragma once

#include <memory>
#include <string>

#include <systemc>

#include "array/array_processor.h"
#include "array/ciu.h"
#include "bus/ahb_bus.h"
#include "config/config.h"
#include "display/display_controller.h"
#include "display/display_dma.h"
#include "dma/dma.h"
#include "host/host.h"
#include "intc/interrupt_controller.h"
#include "mem/memory.h"
#include "raster/rasterizer.h"
#include "soc/irq_map.h"
#include "soc/roi_register.h"
#include "soc/soc_recorder.h"
#include "zbuf/zbuf_unit.h"

namespace tessera {

// Bus priorities under fixed-priority arbitration (lower is served first):
// the display DMA has a deadline every line, the host has none; the
// rasterizer's tile traffic comes between: the host waits for it anyway.
struct BusPriority {
  static constexpr unsigned DISPLAY_DMA = 0;
  static constexpr unsigned RASTER = 1;
  // The system/array DMA feeds and drains the array for the host, which
  // waits for it; but the rasterizer's tile stream stalls a pipeline.
  static constexpr unsigned DMA = 2;
  static constexpr unsigned HOST = 3;
};

class Soc : public sc_core::sc_module {
 public:
  SC_HAS_PROCESS(Soc);

  // The configuration must hold parameter_groups(); it is validated here.
  Soc(sc_core::sc_module_name name, const Config& config);

  // The SoC's parameters: its own (the simulation's timing) and every
  // block's, in the order of the configuration reference.
  static std::vector<ParamGroup> parameter_groups();
  ~Soc() override;

  AhbBus bus;
  Memory memory;
  Host host;
  DisplayController display;
  DisplayDma display_dma;
  Rasterizer raster;
  ArrayProcessor array;
  Ciu ciu;
  // The system/array DMA, built only when dma.enabled (otherwise the SoC is
  // exactly what it was without it: no bus initiator, no statistics).
  std::unique_ptr<Dma> dma;
  // The z-buffer unit beside the array, built only when zbuf.enabled (the
  // port of the array's zsend; tlm/zbuf/README.md).
  std::unique_ptr<ZbufUnit> zbuf;
  // The interrupt controller, built only when host.model=iss (the software
  // on the ISS needs it; host-compiled software waits on the lines).
  std::unique_ptr<InterruptController> intc;

  // Runs the host program; the simulation stops when it has finished and
  // the display has shown every frame handed to it.
  void set_program(Host::Program program) { host.set_program(std::move(program)); }
  bool done() const { return m_done; }

  // Every block, in the order of the statistics and the summary. The
  // recorder gathers statistics and traces over this list, and soc_sim
  // prints the summary from it, so neither names a block.
  const std::vector<Block*>& blocks() const { return m_blocks; }

  // The run's records: frames, power windows, statistics and the VCD trace.
  SocRecorder& recorder() { return m_recorder; }
  const SocRecorder& recorder() const { return m_recorder; }

 private:
  void finish();       // SC_THREAD
  void trace_power();  // SC_THREAD: the recorder's power windows

  std::vector<Block*> m_blocks;
  SocRecorder m_recorder;
  // The region of interest's register (sim_control in the memory map): the
  // model's marker, not a block of the chip; its edges go to the recorder.
  RoiRegister m_roi;
  std::vector<std::unique_ptr<sc_core::sc_signal<bool>>> m_irq_lines;
  std::unique_ptr<sc_core::sc_signal<bool>> m_core_irq, m_core_fiq;
  sc_core::sc_event m_host_finished;
  bool m_done = false;
};

}  // namespace tessera
