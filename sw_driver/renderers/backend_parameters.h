// The driver's parameters (driver.*): which renderer back end the GL driver
// uses, and the checks a back end makes of the rest of the configuration.
#pragma once

#include "config/config.h"

namespace tessera {

ParamGroup driver_parameters();

}  // namespace tessera
