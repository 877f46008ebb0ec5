#include "daemon/hardware/rig_doctor.h"

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <memory>

#include "capture/bracketing.h"
#include "capture/camera_registry.h"
#include "core/time.h"
#include "daemon/hardware/simulated_rig.h"
#include "pipeline/limit_curve.h"
#include "rig/illuminance/illuminance_registry.h"
#include "rig/rig_config.h"
#include "rig/rig_geometry.h"
#include "sun/clock_sync.h"

namespace glarecam::daemon {

namespace fs = std::filesystem;

namespace {

constexpr const char* kUnit = "glarecamd.service";
// The test frame's exposure: 1 ms, mid-range of machine-vision exposures, clamped to the camera.
constexpr double kTestExposureUs = 1000.0;

DoctorCheck ok(std::string name, std::string detail) {
  return {std::move(name), CheckLevel::kOk, std::move(detail)};
}
DoctorCheck warn(std::string name, std::string detail) {
  return {std::move(name), CheckLevel::kWarn, std::move(detail)};
}
DoctorCheck failed(std::string name, std::string detail) {
  return {std::move(name), CheckLevel::kFail, std::move(detail)};
}
DoctorCheck skipped(std::string name, std::string detail) {
  return {std::move(name), CheckLevel::kSkip, std::move(detail)};
}

Result<std::string> systemctlUnitState(const std::string& unit) {
  const std::string command =
      "systemctl show " + unit + " --property=ActiveState,SubState,UnitFileState 2>&1";
  std::unique_ptr<FILE, int (*)(FILE*)> pipe(popen(command.c_str(), "r"), pclose);
  if (!pipe) return fail(ErrorCode::kInternal, "cannot run systemctl");
  std::string output;
  std::array<char, 256> buffer{};
  while (fgets(buffer.data(), buffer.size(), pipe.get())) output += buffer.data();
  const int status = pclose(pipe.release());
  const auto value = [&output](const std::string& key) {
    const std::size_t at = output.find(key + "=");
    if (at == std::string::npos) return std::string();
    const std::size_t begin = at + key.size() + 1;
    return output.substr(begin, output.find('\n', begin) - begin);
  };
  if (status != 0 || value("ActiveState").empty())
    return fail(ErrorCode::kInternal, output.substr(0, output.find('\n')));
  return fmt::format("{} ({}), {}", value("ActiveState"), value("SubState"),
                     value("UnitFileState").empty() ? "not installed" : value("UnitFileState"));
}

DoctorCheck checkCamera(const Config& config, const CameraOpener& open,
                        const std::optional<double>& alpha_deg) {
  if (!config.rig.camera) return failed("camera", "the config names no camera (camera = \"URI\")");
  auto camera = open(*config.rig.camera, capture::cameraOptions(config.daemon.capture),
                     [alpha_deg] { return capture::SceneState{.alpha_deg = alpha_deg}; });
  if (!camera) return failed("camera", camera.error().message);
  const capture::CameraLimits limits = (*camera)->limits();
  // The camera's own range (Camera::capture refuses anything outside it): a sensor whose least
  // analogue gain is above 1× takes its test frame there.
  const capture::ExposureRequest request{
      .exposure_us = std::clamp(kTestExposureUs, limits.min_exposure_us, limits.max_exposure_us),
      .gain_db = std::clamp(0.0, limits.min_gain_db, limits.max_gain_db)};
  auto frames = (*camera)->capture(std::span(&request, 1));
  if (!frames) return failed("camera", frames.error().message);
  const RawFrame& frame = frames->front().image;
  int maximum = 0;
  for (int y = 0; y < frame.height(); ++y)
    for (int x = 0; x < frame.width(); ++x) maximum = std::max<int>(maximum, frame.at(x, y));
  const capture::CameraInfo& info = (*camera)->info();
  return ok(
      "camera",
      fmt::format("{} ({} {}, serial {}{}): a {}x{} {} frame at {:g} µs, max {} DN", info.uri,
                  info.vendor, info.model, info.serial.empty() ? "-" : info.serial,
                  info.detail.empty() ? "" : "; " + info.detail, frame.width(), frame.height(),
                  (*camera)->format().pixel_format, frames->front().exposure_us, maximum));
}

// Where the user running this cannot read or write what glarecamd needs.
std::vector<std::string> permissionProblems(const Config& config) {
  std::vector<std::string> problems;
  const auto need = [&problems](const fs::path& path, int mode, const char* what) {
    if (access(path.c_str(), mode) != 0)
      problems.push_back(fmt::format("{} {}: {}", what, path.string(), errnoText(errno)));
  };
  need(config.daemon.output.root, R_OK | W_OK | X_OK, "output");
  std::error_code error;
  if (config.rig.calibration && fs::exists(*config.rig.calibration, error))
    need(*config.rig.calibration, R_OK, "calibration");
  constexpr std::string_view kAdxl355 = "adxl355:";
  if (config.rig.inclinometer && config.rig.inclinometer->uri.starts_with(kAdxl355)) {
    const std::string& uri = config.rig.inclinometer->uri;
    need(uri.substr(kAdxl355.size(), uri.find('@') - kAdxl355.size()), R_OK | W_OK, "I2C bus");
  }
  if (config.rig.illuminance && config.rig.illuminance->transport == rig::ModbusTransport::kRtu)
    need(config.rig.illuminance->device, R_OK | W_OK, "serial device");
  if (config.rig.gpio && config.rig.gpio->chip.starts_with("gpiochip"))
    need("/dev/" + config.rig.gpio->chip, R_OK | W_OK, "GPIO chip");
  else if (config.rig.gpio && config.rig.gpio->chip.starts_with("/dev/"))
    need(config.rig.gpio->chip, R_OK | W_OK, "GPIO chip");
  return problems;
}

DoctorCheck checkDisk(const Config& config, DiskProbe& disk) {
  const fs::path& root = config.daemon.output.root;
  const auto state = disk.probe(root);
  if (!state) return failed("disk", state.error().message);
  const std::string pause = diskPauseReason(*state, config.daemon.output.reserve_bytes, root);
  if (!pause.empty()) return failed("disk", pause + ": capture would pause");
  return ok("disk", fmt::format("{} free of {} on {} (reserve {})", formatBytes(state->free_bytes),
                                formatBytes(state->total_bytes), root.string(),
                                formatBytes(config.daemon.output.reserve_bytes)));
}

DoctorCheck checkPermissions(const Config& config) {
  const std::vector<std::string> problems = permissionProblems(config);
  if (!problems.empty()) return failed("permissions", fmt::format("{}", fmt::join(problems, "; ")));
  return ok("permissions",
            fmt::format("uid {} reaches the output, calibration and devices", getuid()));
}

DoctorCheck checkClock(const Config& config, const sun::ClockStatus& clock) {
  if (clock.synchronised && isSimulatedRig(config.rig)) return ok("clock", clock.detail);
  if (clock.synchronised)
    return ok("clock",
              fmt::format("synchronised (estimated error {:.3f} s)", clock.estimated_error_s));
  if (config.rig.site)
    return failed("clock", "not synchronised: " + clock.detail + "; a wrong clock is a wrong α");
  return warn("clock", "not synchronised: " + clock.detail + " (α here does not depend on it)");
}

// The inclinometer's reading and the sun's position, from one measurement of the rig.
struct SensorChecks {
  DoctorCheck inclinometer = skipped("inclinometer", "none: the config gives the module's tilt");
  DoctorCheck sun = skipped("sun", "no [site]: α against a fixed source");
  std::optional<double> alpha_deg;
};

DoctorCheck sunCheck(const rig::RigGeometry& geometry) {
  if (geometry.sun->elevation_deg <= 0)
    return warn("sun", fmt::format("below the horizon (elevation {:.2f}°): nothing to measure now",
                                   geometry.sun->elevation_deg));
  return ok("sun", fmt::format("elevation {:.2f}°, azimuth {:.2f}°, α {:.2f}° ± {:.2f}°",
                               geometry.sun->elevation_deg, geometry.sun->azimuth_deg,
                               geometry.alpha_deg, geometry.alpha_uncertainty_deg));
}

// measureTilt() already refused a moving rig (scatter above the config's bound); the tilt must
// also be plausible, as glarecamd judges it ([faults] min/max_tilt_deg).
DoctorCheck tiltCheck(const Config& config, const rig::TiltReading& tilt) {
  const FaultConfig& faults = config.daemon.faults;
  const std::string reading =
      fmt::format("{}: tilt {:.3f}°, scatter {:.4f}° over {} samples", config.rig.inclinometer->uri,
                  tilt.module_tilt_deg, tilt.tilt_std_deg, tilt.samples);
  if (!(tilt.module_tilt_deg >= faults.min_tilt_deg && tilt.module_tilt_deg <= faults.max_tilt_deg))
    return failed("inclinometer", fmt::format("{}: implausible (outside [{:g}, {:g}]°)", reading,
                                              faults.min_tilt_deg, faults.max_tilt_deg));
  return ok("inclinometer", fmt::format("{} (steady: below {:g}°)", reading,
                                        config.rig.inclinometer->tilt.max_tilt_std_deg));
}

SensorChecks checkSensors(const Config& config) {
  SensorChecks checks;
  if (!config.rig.site && !config.rig.fixed_source) return checks;
  auto sensors = rig::RigSensors::open(config.rig);
  const auto measured = sensors ? (*sensors)->measure(utcNow())
                                : Result<rig::RigGeometry>(std::unexpected(sensors.error()));
  if (config.rig.inclinometer && !measured)
    checks.inclinometer = failed("inclinometer", measured.error().message);
  if (!measured) {
    if (config.rig.site) checks.sun = skipped("sun", "needs the module's tilt");
    return checks;
  }
  checks.alpha_deg = measured->alpha_deg;
  if (measured->tilt) checks.inclinometer = tiltCheck(config, *measured->tilt);
  if (measured->sun) checks.sun = sunCheck(*measured);
  return checks;
}

// One reading of the [illuminance] instrument. A failure is a warning: glarecamd captures on,
// its stacks unreferred. The simulated instrument is served here for the reading, with the
// simulated sun of now at the site.
DoctorCheck checkIlluminance(const Config& config, bool daemon_running) {
  if (!config.rig.illuminance)
    return skipped("illuminance", "no [illuminance] instrument: the stacks are unreferred");
  const rig::IlluminanceConfig& instrument = *config.rig.illuminance;
  // Two masters on one RS-485 line garble each other's frames.
  if (daemon_running && instrument.transport == rig::ModbusTransport::kRtu)
    return skipped("illuminance", "glarecamd is running and owns " + instrument.device);
  auto opened = rig::openIlluminance(instrument);
  if (!opened) return warn("illuminance", opened.error().message + " (stacks unreferred)");
  if (opened->simulator && config.rig.site) {
    const auto lx = simulatedSourceIlluminance(utcNow(), *config.rig.site);
    if (lx) rig::setSimulatedIlluminance(*opened, *lx);
  }
  const auto reading = opened->instrument->read();
  if (!reading) return warn("illuminance", reading.error().message + " (stacks unreferred)");
  const rig::IlluminanceInstrumentInfo& info = opened->instrument->info();
  const double u_rel = std::hypot(info.instrument_u_rel, info.efficacy_u_rel);
  return ok("illuminance", fmt::format("{}: {:.1f} klx ± {:.1f} % ({:g} {})", info.description,
                                       reading->illuminance_lx / 1000, 100 * u_rel,
                                       reading->raw_value, rig::unitsText(instrument.units)));
}

DoctorCheck unitCheck(const Result<std::string>& unit) {
  if (!unit) return warn("systemd", "cannot ask systemd: " + unit.error().message);
  const std::string detail = fmt::format("{}: {}", kUnit, *unit);
  return unit->starts_with("active") ? ok("systemd", detail) : warn("systemd", detail);
}

void checkRig(const Config& config, DoctorOptions& options, bool daemon_running,
              std::vector<DoctorCheck>& checks) {
  SensorChecks sensors = checkSensors(config);
  // The camera is told the α the rig measures (a simulated one shows its scene there), when it is
  // within the method's range.
  std::optional<double> scene_alpha_deg = sensors.alpha_deg;
  if (scene_alpha_deg &&
      !(*scene_alpha_deg >= 0 && *scene_alpha_deg <= pipeline::kMaxLimitAlphaDeg))
    scene_alpha_deg.reset();
  checks.push_back(daemon_running ? skipped("camera", "glarecamd is running and owns the camera")
                                  : checkCamera(config, options.open_camera, scene_alpha_deg));
  checks.push_back(std::move(sensors.inclinometer));
  checks.push_back(std::move(sensors.sun));
  checks.push_back(checkIlluminance(config, daemon_running));
  checks.push_back(checkClock(config, rigClockStatus(config.rig, options.clock_status())));
  checks.push_back(checkDisk(config, *options.disk));
  checks.push_back(checkPermissions(config));
}

}  // namespace

std::vector<DoctorCheck> runDoctor(DoctorOptions& options) {
  if (!options.open_camera) options.open_camera = capture::openCamera;
  if (!options.unit_state) options.unit_state = systemctlUnitState;
  if (!options.clock_status) options.clock_status = sun::systemClockStatus;
  std::unique_ptr<DiskProbe> statvfs;
  if (!options.disk) {
    statvfs = makeStatvfsDiskProbe();
    options.disk = statvfs.get();
  }
  std::vector<DoctorCheck> checks;
  const auto config = readConfig(options.config_path);
  const auto unit = options.unit_state(kUnit);
  if (config) {
    checks.push_back(ok("config", options.config_path.string() + " is valid"));
    checkRig(*config, options, unit && unit->starts_with("active"), checks);
  } else {
    options.config_bad_input = config.error().code == ErrorCode::kBadInput;
    checks.push_back(failed("config", config.error().message));
    for (const char* name :
         {"camera", "inclinometer", "sun", "illuminance", "clock", "disk", "permissions"})
      checks.push_back(skipped(name, "the config is not valid"));
  }
  checks.push_back(unitCheck(unit));
  return checks;
}

const char* checkLevelName(CheckLevel level) {
  switch (level) {
    case CheckLevel::kOk:
      return "ok";
    case CheckLevel::kWarn:
      return "warn";
    case CheckLevel::kFail:
      return "FAIL";
    case CheckLevel::kSkip:
      break;
  }
  return "skip";
}

std::string doctorTable(const std::vector<DoctorCheck>& checks) {
  std::string table;
  for (const DoctorCheck& check : checks)
    table +=
        fmt::format("{:<13} {:<5} {}\n", check.name, checkLevelName(check.level), check.detail);
  return table;
}

nlohmann::json doctorJson(const std::vector<DoctorCheck>& checks) {
  nlohmann::json document = {{"checks", nlohmann::json::array()}, {"ok", !anyFailed(checks)}};
  for (const DoctorCheck& check : checks)
    document["checks"].push_back(
        {{"name", check.name}, {"level", checkLevelName(check.level)}, {"detail", check.detail}});
  return document;
}

bool anyFailed(const std::vector<DoctorCheck>& checks) {
  return std::any_of(checks.begin(), checks.end(),
                     [](const DoctorCheck& c) { return c.level == CheckLevel::kFail; });
}

}  // namespace glarecam::daemon
