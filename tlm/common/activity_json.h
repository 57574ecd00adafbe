// Activity counters as nested JSON objects: "vertex_cache.hits" becomes
// {"vertex_cache": {"hits": n}}.
#pragma once

#include <nlohmann/json.hpp>

#include "common/activity_counters.h"

namespace tessera {

inline nlohmann::json to_json(const ActivityCounters& counters) {
  nlohmann::json doc = nlohmann::json::object();
  for (const ActivityCounter& c : counters.all()) {
    nlohmann::json* node = &doc;
    std::string rest = c.name;
    for (auto dot = rest.find('.'); dot != std::string::npos; dot = rest.find('.')) {
      node = &(*node)[rest.substr(0, dot)];
      rest = rest.substr(dot + 1);
    }
    (*node)[rest] = c.value;
  }
  return doc;
}

}  // namespace tessera
