// glarecamd --simulate: the whole daemon against a simulated rig, for demos, tests and users
// without hardware. The rig is an ordinary config file written into the output directory
// (glarecamd-simulated.toml, so that SIGHUP and `glarecam doctor` work on it too): the sim: camera,
// the sim: inclinometer (an ADXL355 register simulator) on a south-facing module tilted
// kSimulatedTiltDeg at a site at kSimulatedLatitudeDeg, the simulated GPIO chip, a simulated
// pyrheliometer served over Modbus TCP on loopback ([illuminance] transport "sim"; only in a
// build with libmodbus), and the α-targets schedule (or a fixed interval). Time runs as a time
// lapse from a summer morning, so that the sun sweeps α from 80° down to ≈ 0° at noon and back
// within minutes.
#pragma once

#include <chrono>
#include <filesystem>
#include <optional>
#include <string>

#include "core/error.h"
#include "core/time.h"
#include "rig/rig_config.h"
#include "sun/clock_sync.h"

namespace glarecam::daemon {

// At 48° N on the June solstice the noon sun stands 65.5° high: a module tilted 24.5° south faces
// it squarely, so that α passes every target from 80° to 5°, twice a day.
inline constexpr double kSimulatedLatitudeDeg = 48.0;
inline constexpr double kSimulatedLongitudeDeg = 7.85;
inline constexpr double kSimulatedTiltDeg = 24.5;
inline constexpr double kDefaultTimeLapse = 120.0;  // 2 minutes of sun a second
// The simulated rig's retention ([output], docs/operator.md): a stack is kept a day, its result and
// the day's sheets two, within a budget that a day of its stacks (32: α falls through the 16
// targets in the morning and rises through them in the afternoon, about 11.5 MB a stack and its
// result with the default camera) and the day before's results fit with a margin, so that the
// default run, left going for days, never overruns it (SimulatedRigTest checks the arithmetic).
inline constexpr int kSimulatedKeepStacksDays = 1;
inline constexpr int kSimulatedKeepResultsDays = 2;
inline constexpr double kSimulatedMaxUseGib = 0.6;
inline constexpr const char* kSimulatedRigFileName = "glarecamd-simulated.toml";
inline constexpr const char* kSimulatedCalibrationFileName = "glarecamd-simulated-calibration.json";

struct SimulatedRigOptions {
  std::filesystem::path output;
  std::string camera = "sim:seed=1";
  std::optional<std::chrono::seconds> interval;  // none: the α targets
};

// The simulated clock's start on 2026-06-21: for the α targets 05:25 UTC, ten minutes of sun
// before α falls through 80° at the site; for a fixed interval 06:30 UTC, α already below 70°.
UtcTime defaultSimulationStart(bool alpha_targets);

// Whether `rig` is the simulated rig glarecamd --simulate writes (kSimulatedRigFileName, with the
// sim: camera and the simulated inclinometer), which runs on its own simulated clock.
bool isSimulatedRig(const rig::RigConfig& rig);

// Whether the clock α is computed from is synchronised, as glarecamd's status page, /metrics, the
// stacks' flags and `glarecam doctor` all say it: on a real rig the wall clock's state (`clock`:
// the kernel's), on the simulated rig synchronised by construction (simulatedClockStatus()).
sun::ClockStatus rigClockStatus(const rig::RigConfig& rig, const sun::ClockStatus& clock);

// The simulated sun's direct normal illuminance (lx) at `utc` over `site`: the clear-sky model's
// value (sun/clear_sky.h, IES RP-21), so that the sun's brightness follows the time lapse. It is
// what the simulated rig's illuminance instrument serves ([illuminance] transport "sim", read
// over Modbus TCP on loopback) and what a simulated camera's scene is to be lit with. kBadInput
// while the sun is down there.
Result<double> simulatedSourceIlluminance(UtcTime utc, const sun::SiteLocation& site);

// Writes OUTPUT/glarecamd-simulated.toml (atomically) and returns its path.
Result<std::filesystem::path> writeSimulatedRigConfig(const SimulatedRigOptions& options);

}  // namespace glarecam::daemon
