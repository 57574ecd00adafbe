// The z-buffer unit's parameters: zbuf.* (README.md gives the reasoning).
#include <string>

#include "zbuf/zbuf_unit.h"

namespace tessera {

ParamGroup ZbufParams::parameters() {
  using param::boolean;
  using param::integer;
  return {"zbuf",
          {
              boolean("zbuf.enabled", false,
                      "the z-buffer unit beside the array (Davila et al.'s, proposed hardware) is in the SoC: mapped, "
                      "in the statistics, the port of the array's zsend (with array.features.zsend)"),
              integer("zbuf.entries", zbuf::MAX_ENTRIES, 1, zbuf::MAX_ENTRIES, "entries",
                      "16-bit depth and 16-bit colour entries of the unit (the paper's 64K: a 256 x 256 window)"),
              integer("zbuf.ports", 2, 1, 1024, "ports",
                      "pixels the unit takes per array cycle (the paper's 2); a zsend holds them for ceil(senders / "
                      "ports) cycles"),
              boolean("zbuf.pair_halves_only", false,
                      "the paper's rule: pixels share a cycle only when they come from the two CUs of one pair "
                      "(lanes 2k, 2k + 1: the two halves of one triangle), so at most 2 a cycle"),
          },
          [](const Config& config) {
            if (!config.has("array.features.zsend") || !config.get_bool("array.features.zsend")) return;
            // zsend without the unit would stop every program that uses it.
            if (!config.get_bool("zbuf.enabled"))
              throw ConfigError(
                  "configuration: impossible combination: array.features.zsend=true needs zbuf.enabled=true (zsend "
                  "sends to the z-buffer unit, which zbuf.enabled=false leaves out of the SoC)");
            if (config.has("array.issue_skew") && config.get_string("array.issue_skew") == "lane")
              throw ConfigError(
                  "configuration: impossible combination: array.features.zsend=true with array.issue_skew=lane: the "
                  "z-buffer port's reservation is modelled for lockstep and row-sequential issue (none, row) only");
          }};
}

ZbufParams ZbufParams::from_config(const Config& config) {
  ZbufParams p;
  p.enabled = config.get_bool("zbuf.enabled");
  p.core.entries = static_cast<unsigned>(config.get_uint("zbuf.entries"));
  p.core.ports = static_cast<unsigned>(config.get_uint("zbuf.ports"));
  p.core.pair_halves_only = config.get_bool("zbuf.pair_halves_only");
  p.clock_period = sc_core::sc_time(1e3 / config.get_real("array.clock_mhz"), sc_core::SC_NS);
  return p;
}

ZbufParams ZbufParams::defaults() {
  return from_config(Config({ArrayParams::parameters(), parameters()}));
}

}  // namespace tessera
