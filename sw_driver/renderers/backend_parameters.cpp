#include "renderers/backend_parameters.h"

#include <iterator>
#include <string>
#include <utility>
#include <vector>

#include "gl/renderer.h"
#include "renderers/backends.h"

namespace tessera {

ParamGroup driver_parameters() {
  std::vector<std::string> names;
  std::string description = "renderer back end of the GL ES driver: ";
  for (const backends::Backend& entry : backends::BACKENDS) {
    if (!names.empty()) description += names.size() + 1 == std::size(backends::BACKENDS) ? " or " : ", ";
    description += std::string(entry.name) + " (" + entry.description + ")";
    names.emplace_back(entry.name);
  }
  return {"driver",
          {
              param::choice("driver.backend", "arm", names, description),
              param::integer("driver.texture_units", gl::DEFAULT_TEXTURE_UNITS, 1, gl::MAX_TEXTURE_UNITS, "units",
                             "texture units the GL ES driver offers (GL_MAX_TEXTURE_UNITS; ES 1.1 requires at "
                             "least 2)"),
          },
          [](const Config& config) {
            // The choice has been checked against the same names already.
            if (const backends::Backend* chosen = backends::find_backend(config.get_string("driver.backend")))
              chosen->check_configuration(config);
          }};
}

std::vector<ParamGroup> driver_parameter_groups() {
  std::vector<ParamGroup> groups = {driver_parameters()};
  for (const backends::Backend& entry : backends::BACKENDS) {
    ParamGroup group = entry.parameters();
    if (!group.specs.empty()) groups.push_back(std::move(group));
  }
  return groups;
}

}  // namespace tessera
