// The driver's parameters (driver.*): which renderer back end the GL driver
// uses (one of backends.def's names), and the check the chosen back end
// makes of the rest of the configuration (its check_configuration).
#pragma once

#include "config/config.h"

namespace tessera {

ParamGroup driver_parameters();

}  // namespace tessera
