// The driver's parameters: which renderer back end the GL driver uses
// (driver.backend, one of backends.def's names), the back ends' own
// parameters (ap.*, read through AppEnvironment::config), and the check the
// chosen back end makes of the rest of the configuration (its
// check_configuration).
#pragma once

#include <vector>

#include "config/config.h"

namespace tessera {

ParamGroup driver_parameters();

// driver_parameters() and, in backends.def's order, every back end's own
// keys (its `parameters` entry point, e.g. ap.tile.*): what a launcher puts
// in its configuration so that the user may set them whichever back end
// runs. Groups without keys are left out.
std::vector<ParamGroup> driver_parameter_groups();

}  // namespace tessera
