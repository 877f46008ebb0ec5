#include "apps/common/value_types.h"

#include <string_view>
#include <utility>

namespace glarecam::apps {
namespace {

// Long option name -> what its value is (units as the option's description gives them).
constexpr std::pair<std::string_view, std::string_view> kValueTypes[] = {
    {"alpha", "DEG"},
    {"lat", "DEG"},
    {"lon", "DEG"},
    {"offset-deg", "H,V"},
    {"threshold", "CD_M2"},
    {"thresholds", "CD_M2,..."},
    {"gain", "DB"},
    {"f-number", "N"},
    {"nd-transmission", "FRACTION"},
    {"exposures", "US,..."},
    {"count", "N"},
    {"max-retries", "N"},
    {"samples", "N"},
    {"trigger", "N"},
    {"seed", "UINT"},
    {"sensor-seed", "UINT"},
    {"altitude-m", "M"},
    {"pressure-hpa", "HPA"},
    {"temperature-c", "DEG_C"},
    {"delta-t-s", "S"},
    {"delta-ut1-s", "S"},
    {"size", "WxH"},
    {"board", "COLSxROWS"},
    {"roi", "X,Y,W,H"},
    {"distortion", "K1,K2,P1,P2,K3"},
    {"time", "ISO8601"},
    {"start", "ISO8601"},
    {"date", "YYYY-MM-DD"},
    {"camera", "URI"},
    {"inclinometer", "URI"},
    {"config", "FILE"},
    {"calibration", "FILE"},
    {"alpha-from", "FILE"},
    {"log", "FILE"},
    {"from", "FILE"},
    {"out", "PATH"},
    {"output", "DIR"},
    {"calibration-out", "DIR"},
    {"module", "NAME"},
    {"serial", "SERIAL"},
    {"interface", "ADDRESS"},
    {"pixel-format", "FORMAT"},
    {"led", "STATE"},
    {"log-target", "TARGET"},
    {"profile", "FILE"},
    {"models", "MODEL,..."},
    {"criteria", "ID,..."},
    {"surface", "NAME|FILE"},
    {"distribution", "NAME"},
    {"format", "FORMAT"},
};

}  // namespace

void nameOptionValues(CLI::App& app) {
  for (CLI::Option* option : app.get_options()) {
    if (option->get_type_name() != "TEXT" || option->get_lnames().empty()) continue;
    for (const auto& [name, type] : kValueTypes) {
      if (option->get_lnames().front() == name) option->type_name(std::string(type));
    }
  }
  for (CLI::App* sub : app.get_subcommands({})) nameOptionValues(*sub);
}

}  // namespace glarecam::apps
