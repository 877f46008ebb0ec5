// The rig's part of its configuration (TOML, /etc/glarecam/glarecam.toml by convention): where the
// rig is, how its module faces, which inclinometer measures the tilt, the light source (the sun,
// or a fixed lamp in the lab), the camera, the calibration file, the GPIO lines and the instrument
// that measures the source's illuminance ([illuminance], docs/illuminance.md). The same file
// holds glarecamd's sections, which daemon/daemon_config.h reads (daemon::readConfig reads the
// whole file). Every key is documented in firmware-config/glarecam.toml and docs/rig.md. Reading
// validates everything: an unknown key, a wrong type or a value out of range is a kBadInput error
// "FILE:LINE: problem".
#pragma once

#include <toml++/toml.h>

#include <array>
#include <filesystem>
#include <optional>
#include <string>

#include "core/error.h"
#include "core/source_illuminance.h"
#include "core/stack_manifest.h"
#include "rig/gpio/rig_io.h"
#include "rig/illuminance/illuminance_config.h"
#include "rig/inclinometer/tilt.h"
#include "sun/incidence_angle.h"
#include "sun/solar_position.h"

namespace glarecam::rig {

// Where the rig's config lives unless --config says otherwise (the FHS place for a package's).
inline constexpr const char* kDefaultRigConfigPath = "/etc/glarecam/glarecam.toml";

struct InclinometerConfig {
  std::string uri;  // "adxl355:/dev/i2c-1@0x1d", "iio:iio:device0", "sim:30"
  TiltOptions tilt;
};

struct RigConfig {
  std::filesystem::path path;  // the file it was read from, for messages

  std::optional<std::string> camera;  // default camera URI
  // Camera calibration and the inclinometer's zero offset (relative paths resolved against the
  // config file's directory).
  std::optional<std::filesystem::path> calibration;

  std::optional<sun::SiteLocation> site;          // outdoors: α from the sun's position
  std::optional<sun::SkyDirection> fixed_source;  // lab: α against a lamp that does not move
  // [source] illuminance: the lamp's direct normal illuminance at the module, measured once with
  // an illuminance meter (origin given), recorded as every stack's source.
  std::optional<SourceIlluminance> fixed_source_illuminance;

  // The module's facing azimuth, and its tilt when no inclinometer measures it.
  std::optional<double> module_azimuth_deg;
  std::optional<double> module_tilt_deg;

  std::optional<InclinometerConfig> inclinometer;

  // [gpio]: trigger, status LED and button lines (chip "sim" for the simulated rig's).
  std::optional<RigIoConfig> gpio;

  // [illuminance]: the Modbus instrument that gives each stack its source illuminance.
  std::optional<IlluminanceConfig> illuminance;
};

// The sections of a config file the rig's reader reads.
inline constexpr std::array<std::string_view, 6> kRigSections{
    "gpio", "illuminance", "inclinometer", "module", "site", "source"};

// The top-level keys and kRigSections of `root`, parsed from `file` (relative paths resolve
// against its directory). Other sections are their readers' (readConfigFile checks that each
// section has one).
Result<RigConfig> readRigSections(const std::filesystem::path& file, const toml::table& root);

// The camera calibration in the config's calibration file, when it holds one: the file may be
// absent (the flip creates it) or hold only the inclinometer's zero offset.
Result<std::optional<Calibration>> rigCameraCalibration(const RigConfig& config);

}  // namespace glarecam::rig
