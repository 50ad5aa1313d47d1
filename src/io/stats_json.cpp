#include <algorithm>
#include <cmath>

#include <nlohmann/json.hpp>

#include "io/output.h"

namespace sp {

double median(std::vector<double> values) {
  if (values.empty()) return 0.0;
  auto middle = values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2);
  std::nth_element(values.begin(), middle, values.end());
  double upper = *middle;
  if (values.size() % 2 == 1) return upper;
  double lower = *std::max_element(values.begin(), middle);
  return (lower + upper) / 2.0;
}

double percentile(std::vector<double> values, double p) {
  if (values.empty()) return 0.0;
  std::sort(values.begin(), values.end());
  double rank = std::ceil(std::clamp(p, 0.0, 100.0) / 100.0 * static_cast<double>(values.size()));
  std::size_t index = rank < 1.0 ? 0 : static_cast<std::size_t>(rank) - 1;
  return values[std::min(index, values.size() - 1)];
}

std::string stats_json(const World& world, const SimulationStats& stats, const char* backend_name,
                       const std::string& device, const StepTimings& timings) {
  nlohmann::ordered_json json;
  json["steps"] = stats.steps;
  json["backend"] = backend_name;
  json["device"] = device;
  json["casts"] = stats.casts;
  json["max_casts_per_step"] = stats.max_casts_per_step;
  json["rays_emitted"] = stats.rays_emitted;
  json["indicators"] = stats.indicators;
  json["casts_cut_short"] = stats.casts_cut_short;
  json["connections"] = stats.connections;  // casts from spots to the listener
  std::uint64_t diffractions = 0;
  for (const LayerCounters& c : stats.layers) diffractions += c.diffractions;
  json["diffractions"] = diffractions;  // the run's total (contract: README.md, "Command line")
  nlohmann::ordered_json layers = nlohmann::ordered_json::object();
  for (std::size_t l = 0; l < world.layer_names.size() && l < stats.layers.size(); ++l) {
    const LayerCounters& c = stats.layers[l];
    layers[world.layer_names[l]] = {{"hits", c.hits},
                                    {"reflections", c.reflections},
                                    {"penetrations", c.penetrations},
                                    {"no_way_out", c.no_way_out},
                                    // The same count under the paper's name: SPEC's
                                    // contract, deprecated (CHANGELOG.md 0.2.0).
                                    {"backcast_misses", c.no_way_out},
                                    {"back_face_hits", c.back_face_hits},
                                    {"diffractions", c.diffractions}};
  }
  json["layers"] = layers;
  nlohmann::ordered_json timing;
  timing["ms_per_step_median"] = median(timings.wall_ms);
  timing["ms_per_step_p99"] = percentile(timings.wall_ms, 99.0);
  if (!timings.gpu_ms.empty()) timing["gpu_ms_per_step_median"] = median(timings.gpu_ms);
  json["timing"] = timing;
  // Layer names from a Scene built in code need not be UTF-8: such bytes
  // become U+FFFD rather than throw (files' names are UTF-8 already).
  return json.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n";
}

}  // namespace sp
