#include "check/check_report_json.h"

#include <nlohmann/json.hpp>

namespace sp {

std::string check_report_json(const CheckReport& report) {
  nlohmann::ordered_json json;
  json["triangles"] = report.triangles;
  json["findings"] = nlohmann::ordered_json::array();
  for (const CheckFinding& f : report.findings) {
    nlohmann::ordered_json layers = nlohmann::ordered_json::array();
    for (const CheckLayerCount& layer : f.layers) layers.push_back({{"name", layer.name}, {"count", layer.count}});
    json["findings"].push_back({{"code", f.code}, {"count", f.count}, {"message", f.message}, {"layers", layers}});
  }
  json["probe"] = {{"penetrations", report.probe.penetrations},
                   {"no_way_out", report.probe.no_way_out},
                   {"no_way_out_within_max_wall_thickness", report.probe_at_config.no_way_out},
                   {"hits", report.probe.hits},
                   {"back_face_hits", report.probe.back_face_hits}};
  // dump() throws on invalid UTF-8 unless told otherwise; replace keeps
  // every valid byte and marks each invalid one.
  return json.dump(2, ' ', /*ensure_ascii=*/false, nlohmann::ordered_json::error_handler_t::replace) + "\n";
}

}  // namespace sp
