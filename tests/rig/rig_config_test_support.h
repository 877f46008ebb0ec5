// A rig config in a file, for the tests of the config and of what is computed from it: the
// reader of the rig's sections alone, a file written in one line, and a config at NREL's SPA test
// site.
#pragma once

#include <filesystem>
#include <fstream>
#include <string>

#include "core/config_table.h"
#include "rig/rig_config.h"
#include "support/test_support.h"

namespace glarecam::testing {

// A config file holding only the rig's sections (glarecamd's config holds more:
// daemon::readConfig reads it whole).
inline Result<rig::RigConfig> readRigConfig(const std::filesystem::path& path) {
  toml::table root;
  GLARECAM_ASSIGN(root, readConfigFile(path, rig::kRigSections));
  return rig::readRigSections(path, root);
}

inline std::filesystem::path writeText(const TempDir& dir, const std::string& name,
                                       const std::string& text) {
  std::ofstream(dir / name) << text;
  return dir / name;
}

inline constexpr const char* kSunConfig = R"(calibration = "calib.json"
[site]
latitude_deg = 39.742476
longitude_deg = -105.1786
altitude_m = 1830.14
pressure_hpa = 820
temperature_c = 11

[module]
azimuth_deg = 180

[inclinometer]
uri = "sim:30"
samples = 20
)";

}  // namespace glarecam::testing
