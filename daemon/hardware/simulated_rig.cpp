#include "daemon/hardware/simulated_rig.h"

#include <fmt/format.h>

#include "core/atomic_file.h"
#include "daemon/daemon_clock.h"
#include "rig/illuminance/illuminance_registry.h"
#include "rig/inclinometer/zero_offset_file.h"
#include "sun/clear_sky.h"

namespace glarecam::daemon {

UtcTime defaultSimulationStart(bool alpha_targets) {
  using namespace std::chrono;
  const auto day = sys_days(year(2026) / June / 21);
  return time_point_cast<microseconds>(alpha_targets ? day + hours(5) + minutes(25)
                                                     : day + hours(6) + minutes(30));
}

bool isSimulatedRig(const rig::RigConfig& rig) {
  return rig.path.filename() == kSimulatedRigFileName && rig.camera &&
         rig.camera->starts_with("sim:") && rig.inclinometer &&
         rig.inclinometer->uri.starts_with("sim:");
}

sun::ClockStatus rigClockStatus(const rig::RigConfig& rig, const sun::ClockStatus& clock) {
  return isSimulatedRig(rig) ? simulatedClockStatus() : clock;
}

namespace {

// The simulated pyrheliometer's table (a build without libmodbus has none).
constexpr const char* kSimulatedInstrument = R"(
# A simulated pyrheliometer (direct normal irradiance, W/m², float32 in input registers 0-1),
# served over Modbus TCP on 127.0.0.1 at a free port and read like a real one; it serves the
# clear-sky sun of the simulated time (docs/illuminance.md).
[illuminance]
transport = "sim"
data_type = "float32"
units = "W/m2"
uncertainty_pct = 2
name = "simulated pyrheliometer"
)";

}  // namespace

Result<double> simulatedSourceIlluminance(UtcTime utc, const sun::SiteLocation& site) {
  SourceIlluminance source;
  GLARECAM_ASSIGN(source, sun::clearSkySource(utc, site));
  return source.illuminance_lx;
}

Result<std::filesystem::path> writeSimulatedRigConfig(const SimulatedRigOptions& options) {
  GLARECAM_CHECK(ensureDirectory(options.output));
  const std::string schedule =
      options.interval
          ? fmt::format("mode = \"interval\"\ninterval_s = {}", options.interval->count())
          : std::string("mode = \"alpha-targets\"");
  const std::string text = fmt::format(
      R"(# glarecamd --simulate: the simulated rig (docs/operator.md). Written by glarecamd at each
# start; edit a copy and run glarecamd --config on it to try other settings.
camera = "{camera}"
calibration = "{calibration}"

[site]
latitude_deg = {latitude}
longitude_deg = {longitude}
altitude_m = 278

[module]
azimuth_deg = 180

[inclinometer]
uri = "sim:{tilt}"
samples = 10

[gpio]
chip = "sim"
led = 27
button = 22
{illuminance}
[schedule]
{schedule}

[output]
root = "."
reserve_mb = 64
module = "simulated standard module"
keep_stacks_days = {keep_stacks}    # a stack a day: the next simulated day deletes it
keep_results_days = {keep_results}   # results and day sheets two days
max_use_gib = {budget_gib}        # what a simulated day and the day before's results take, and more
)",
      fmt::arg("camera", options.camera), fmt::arg("calibration", kSimulatedCalibrationFileName),
      fmt::arg("latitude", kSimulatedLatitudeDeg), fmt::arg("longitude", kSimulatedLongitudeDeg),
      fmt::arg("tilt", kSimulatedTiltDeg), fmt::arg("schedule", schedule),
      fmt::arg("illuminance", rig::modbusAvailable() ? kSimulatedInstrument : ""),
      fmt::arg("keep_stacks", kSimulatedKeepStacksDays),
      fmt::arg("keep_results", kSimulatedKeepResultsDays),
      fmt::arg("budget_gib", kSimulatedMaxUseGib));
  // The simulated sensor is mounted without error: its zero offset is zero, known exactly.
  const rig::InclinometerZeroOffset zero{.offset = {0.0, 0.0},
                                         .uncertainty_deg = 0.0,
                                         .measured_with = fmt::format("sim:{}", kSimulatedTiltDeg)};
  const std::filesystem::path calibration = options.output / kSimulatedCalibrationFileName;
  std::error_code error;
  std::filesystem::remove(calibration, error);
  GLARECAM_CHECK(rig::writeZeroOffset(
      calibration, zero, {{"method", "simulated: the sensor is mounted without error"}}));
  const std::filesystem::path path = options.output / kSimulatedRigFileName;
  GLARECAM_CHECK(writeFileAtomic(path, text));
  return path;
}

}  // namespace glarecam::daemon
