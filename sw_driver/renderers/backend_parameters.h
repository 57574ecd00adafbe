// The driver's parameters: which renderer back end the GL driver uses
// (driver.backend, one of backends.def's names), the back ends' own
// parameters (ap.*, read through AppEnvironment::config), and the check the
// chosen back end makes of the rest of the configuration (its
// check_configuration).
#pragma once

#include "config/config.h"

namespace tessera {

ParamGroup driver_parameters();

}  // namespace tessera
