#include "rig/rig_config.h"

#include <fmt/format.h>
#include <toml++/toml.h>

#include <cmath>

#include "core/config_table.h"
#include "core/json.h"
#include "core/stack_io.h"

namespace glarecam::rig {

namespace {

// Far beyond any chip; the chip itself checks.
constexpr std::int64_t kMaxGpioOffset = 65535;

// A GPIO line: its offset (an integer) or its name (a string), with `KEY_active_low` (default
// `default_active_low`).
Result<std::optional<GpioLine>> readGpioLine(TableReader& reader, const std::string& key,
                                             bool default_active_low = false) {
  reader.markUsed(key);
  const std::string active_low_key = key + "_active_low";
  std::optional<bool> active_low;
  GLARECAM_ASSIGN(active_low, reader.boolean(active_low_key.c_str()));
  const toml::node* line_node = reader.table().get(key);
  if (!line_node) {
    if (active_low)
      return reader.error(
          *reader.table().get(active_low_key),
          fmt::format("{} without {}", reader.qualified(active_low_key), reader.qualified(key)));
    return std::nullopt;
  }
  GpioLine line;
  if (line_node->is_integer() && *line_node->value<std::int64_t>() >= 0 &&
      *line_node->value<std::int64_t>() <= kMaxGpioOffset) {
    line.line = static_cast<unsigned>(*line_node->value<std::int64_t>());
  } else if (line_node->is_string() && !line_node->value<std::string>()->empty()) {
    line.line = *line_node->value<std::string>();
  } else {
    return reader.error(*line_node, fmt::format("{} must be a line offset (0..{}) or a line name",
                                                reader.qualified(key), kMaxGpioOffset));
  }
  line.active_low = active_low.value_or(default_active_low);
  return line;
}

constexpr std::int64_t kMaxTiltSamples = 100000;  // ≈ 2 h at the ADXL355's 15.6 Hz

Result<std::optional<sun::SiteLocation>> readSite(const std::filesystem::path& file,
                                                  const toml::table* table) {
  if (!table) return std::nullopt;
  TableReader site(file, *table, "site");
  sun::SiteLocation location;
  GLARECAM_ASSIGN(location.latitude_deg, site.requiredNumber("latitude_deg", -90, 90));
  GLARECAM_ASSIGN(location.longitude_deg, site.requiredNumber("longitude_deg", -180, 180));
  std::optional<double> altitude, pressure, temperature;
  // The ranges SPA accepts (solar_position.h); validate() below has the last word.
  GLARECAM_ASSIGN(altitude, site.number("altitude_m", -1000, 10000));
  GLARECAM_ASSIGN(pressure, site.number("pressure_hpa", 0, 5000));
  GLARECAM_ASSIGN(temperature, site.number("temperature_c", -273, 100));
  GLARECAM_CHECK(site.checkNoUnknownKeys());
  location.altitude_m = altitude.value_or(0.0);
  location.pressure_hpa = pressure.value_or(sun::standardPressureHpa(location.altitude_m));
  if (temperature) location.temperature_c = *temperature;
  const Status valid = validate(location);
  if (!valid) return site.tableError(valid.error().message);
  return location;
}

// [source]: the lamp's direction, and its illuminance at the module when measured ("92500±2800",
// or a number of lx).
Status readSource(const std::filesystem::path& file, const toml::table* table, RigConfig& rig) {
  if (!table) return {};
  TableReader source(file, *table, "source");
  sun::SkyDirection direction;
  GLARECAM_ASSIGN(direction.elevation_deg, source.requiredNumber("elevation_deg", -90, 90));
  GLARECAM_ASSIGN(direction.azimuth_deg, source.requiredNumber("azimuth_deg", 0, 360));
  rig.fixed_source = direction;
  if (const toml::node* node = source.node("illuminance")) {
    std::string text;
    if (const auto number = node->value<double>()) {
      text = fmt::format("{}", *number);
    } else if (const auto string = node->value<std::string>()) {
      text = *string;
    } else {
      return source.error(*node, fmt::format("{} must be a number of lx or \"LX±U\"",
                                             source.qualified("illuminance")));
    }
    auto illuminance = parseGivenIlluminance(text, source.qualified("illuminance"));
    if (!illuminance) return source.error(*node, illuminance.error().message);
    rig.fixed_source_illuminance = *illuminance;
  }
  return source.checkNoUnknownKeys();
}

Result<std::optional<InclinometerConfig>> readInclinometer(const std::filesystem::path& file,
                                                           const toml::table* table) {
  if (!table) return std::nullopt;
  TableReader reader(file, *table, "inclinometer");
  InclinometerConfig config;
  GLARECAM_ASSIGN(config.uri, reader.requiredString("uri"));
  std::optional<std::int64_t> samples;
  std::optional<double> max_std, tolerance;
  GLARECAM_ASSIGN(samples, reader.integer("samples", 2, kMaxTiltSamples));
  GLARECAM_ASSIGN(max_std, reader.number("max_tilt_std_deg", 1e-6, 10));
  GLARECAM_ASSIGN(tolerance, reader.number("gravity_tolerance_g", 1e-3, 0.9));
  GLARECAM_CHECK(reader.checkNoUnknownKeys());
  if (samples) config.tilt.samples = static_cast<int>(*samples);
  if (max_std) config.tilt.max_tilt_std_deg = *max_std;
  if (tolerance) config.tilt.gravity_tolerance_g = *tolerance;
  return config;
}

Result<std::optional<RigIoConfig>> readGpio(const std::filesystem::path& file,
                                            const toml::table* table) {
  if (!table) return std::nullopt;
  TableReader reader(file, *table, "gpio");
  RigIoConfig gpio;
  std::optional<std::string> chip;
  GLARECAM_ASSIGN(chip, reader.string("chip"));
  if (chip) gpio.chip = *chip;
  std::optional<bool> pull_up;
  GLARECAM_ASSIGN(pull_up, reader.boolean("button_pull_up"));
  if (pull_up) gpio.button_pull_up = *pull_up;
  GLARECAM_ASSIGN(gpio.trigger, readGpioLine(reader, "trigger"));
  GLARECAM_ASSIGN(gpio.led, readGpioLine(reader, "led"));
  // A button on the pull-up goes to ground: active-low unless said otherwise.
  GLARECAM_ASSIGN(gpio.button, readGpioLine(reader, "button", gpio.button_pull_up));
  std::optional<std::int64_t> debounce_ms, pulse_us;
  GLARECAM_ASSIGN(debounce_ms, reader.integer("debounce_ms", 0, kMaxDebounce.count()));
  GLARECAM_ASSIGN(pulse_us, reader.integer("trigger_pulse_us", 1, kMaxTriggerPulse.count()));
  GLARECAM_CHECK(reader.checkNoUnknownKeys());
  if (debounce_ms) gpio.debounce = std::chrono::milliseconds(*debounce_ms);
  if (pulse_us) gpio.trigger_pulse = std::chrono::microseconds(*pulse_us);
  const Status valid = gpio.validate();
  if (!valid) return reader.tableError(valid.error().message);
  return gpio;
}

Status readModule(const std::filesystem::path& file, const toml::table* table, RigConfig& rig) {
  if (!table) return {};
  TableReader module(file, *table, "module");
  GLARECAM_ASSIGN(rig.module_azimuth_deg, module.number("azimuth_deg", 0, 360));
  GLARECAM_ASSIGN(rig.module_tilt_deg, module.number("tilt_deg", 0, 180));
  return module.checkNoUnknownKeys();
}

Status checkConsistent(const RigConfig& rig) {
  const std::string file = rig.path.string();
  if (rig.site && rig.fixed_source)
    return badInput(file +
                    ": give either [site] (α against the sun) or [source] (a fixed lamp), "
                    "not both");
  if (rig.inclinometer && rig.module_tilt_deg)
    return badInput(file +
                    ": give [module] tilt_deg (a fixed tilt) or an [inclinometer] that "
                    "measures it, not both");
  if ((rig.site || rig.fixed_source) && !rig.module_azimuth_deg)
    return badInput(file + ": [module] azimuth_deg is needed to compute α");
  return {};
}

}  // namespace

Result<RigConfig> readRigSections(const std::filesystem::path& path, const toml::table& root) {
  RigConfig rig;
  rig.path = path;
  TableReader top(path, root, "");
  GLARECAM_ASSIGN(rig.camera, top.string("camera"));
  std::optional<std::string> calibration;
  GLARECAM_ASSIGN(calibration, top.string("calibration"));
  GLARECAM_CHECK(top.checkNoUnknownKeys());
  if (calibration) rig.calibration = path.parent_path() / *calibration;
  GLARECAM_ASSIGN(rig.site, readSite(path, root["site"].as_table()));
  GLARECAM_CHECK(readSource(path, root["source"].as_table(), rig));
  GLARECAM_ASSIGN(rig.inclinometer, readInclinometer(path, root["inclinometer"].as_table()));
  GLARECAM_CHECK(readModule(path, root["module"].as_table(), rig));
  GLARECAM_ASSIGN(rig.gpio, readGpio(path, root["gpio"].as_table()));
  if (const toml::table* illuminance = root["illuminance"].as_table())
    GLARECAM_ASSIGN(rig.illuminance, readIlluminanceTable(path, *illuminance));
  GLARECAM_CHECK(checkConsistent(rig));
  return rig;
}

Result<std::optional<Calibration>> rigCameraCalibration(const RigConfig& config) {
  std::error_code ec;
  if (!config.calibration || !std::filesystem::exists(*config.calibration, ec)) return std::nullopt;
  nlohmann::json document;
  GLARECAM_ASSIGN(document, readJsonFile(config.calibration->string()));
  if (!document.is_object() || !document.contains("black_level_dn")) return std::nullopt;
  return readCalibrationFile(config.calibration->string());
}

}  // namespace glarecam::rig
