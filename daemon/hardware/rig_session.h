// The rig around the camera while stacks are taken: the inclinometer and the site or lab source
// that give each stack its α and geometry block (rig/rig_geometry.h), the status LED and the
// operator's button. One session serves both `glarecam capture --config` and glarecamd, so that
// one rig config means the same in both:
//
//   a tilt outside [faults] min_tilt_deg … max_tilt_deg is a fault (a loose sensor, a module
//   blown over), never an α;
//   what is wrong with the sensors' setup (no zero offset stored, one of another sensor) is
//   logged once per session and recorded in every stack's geometry block;
//   α is measured before each bracket and retimed to the bracket's middle (the sun moves while
//   the frames expose; a fixed lab source does not).
//
// The session keeps the last geometry it measured: the module's orientation for planning α
// targets, and the α a simulated camera shows (its SceneSource). As a capture::SeriesRig it
// prepares and finishes each stack of `glarecam capture`'s series, waiting for the button when
// asked to, and samples the config's [illuminance] instrument during each bracket (unless the
// series was given its source illuminance): a stack whose instrument fails is written unreferred,
// with a warning. glarecamd decides itself what a fault means for capture ([faults] inclinometer)
// and samples the instrument itself (illuminance_session.h).
#pragma once

#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <thread>

#include "capture/bracketer.h"
#include "capture/camera_registry.h"
#include "capture/capture_series.h"
#include "core/error.h"
#include "core/time.h"
#include "daemon/daemon_config.h"
#include "rig/gpio/rig_io.h"
#include "rig/gpio/status_led.h"
#include "rig/illuminance/illuminance_registry.h"
#include "rig/illuminance/illuminance_sampler.h"
#include "rig/rig_config.h"
#include "rig/rig_geometry.h"
#include "sun/clock_sync.h"

namespace glarecam::daemon {

// After a failed button read, how long the button's watcher waits before reading again.
inline constexpr std::chrono::seconds kButtonRetry{5};

using RigIoOpener = std::function<Result<std::unique_ptr<rig::RigIo>>(const rig::RigIoConfig&)>;

struct RigSessionOptions {
  FaultConfig faults;                  // the tilt's plausible range
  RigIoOpener open_rig_io{};           // default rig::openRigIo
  std::string log_name = "glarecamd";  // what its log lines start with
  bool show_progress = false;          // a progress line over the inclinometer's samples on stderr
  // As a SeriesRig: wait for a press of the button before each stack, and re-measure then.
  bool on_button = false;
};

class RigSession final : public capture::SeriesRig {
 public:
  RigSession(rig::RigConfig config, RigSessionOptions options);
  ~RigSession() override;  // the LED dark: nothing drives it any more
  RigSession(const RigSession&) = delete;
  RigSession& operator=(const RigSession&) = delete;

  const rig::RigConfig& config() const { return config_; }
  // Whether the config gives α ([site] or [source]): then it is measured before each stack.
  bool measuresAlpha() const { return config_.site || config_.fixed_source; }

  // Opens the config's inclinometer with its zero offset, when α is measured; its error when it
  // cannot (then measure() tries again).
  Status openSensors();
  bool sensorsOpen() const { return sensors_ != nullptr; }

  // The geometry now (`clock`: the state of the clock `time` was read from). kHardware for a tilt
  // outside [faults]; the sensors' error when they cannot read. A measurement that succeeds is
  // kept as lastGeometry().
  Result<rig::RigGeometry> measure(UtcTime time, const std::optional<sun::ClockStatus>& clock);
  // The last geometry measured since the sensors were opened.
  const std::optional<rig::RigGeometry>& lastGeometry() const { return last_geometry_; }
  // The α of the last geometry measured, for a simulated camera's scene (nullopt: none yet).
  std::optional<double> sceneAlphaDeg() const;
  // That α, and the illuminance of its source: the lab lamp's as the config gives it, or the
  // clear-sky direct normal illuminance of the sun at the site then (none for a lamp the config
  // gives none, or a sun below the horizon): what a simulated camera's scene shows.
  capture::SceneState sceneState() const;
  // Records a measurement in `settings`: α and the geometry block, or a block that says why α is
  // unknown.
  static void record(const Result<rig::RigGeometry>& measured, capture::CaptureSettings& settings);
  // After a bracket measured at `geometry`: α and the geometry block for the bracket's middle
  // into the stack (a warning when that fails: the stack keeps the measured α).
  void recordBracketMiddle(capture::CapturedStack& stack, const rig::RigGeometry& geometry,
                           UtcTime bracket_start, UtcTime bracket_end) const;

  // Opens the config's GPIO lines and starts the LED (ready); without [gpio] nothing. Its error
  // when the lines cannot be had: the rig can measure on without them.
  Status openGpio();
  // Stops watching the button, and releases the lines with the LED dark.
  void closeGpio();
  rig::RigIo* io() const { return io_.get(); }
  // Watches the button from a thread of its own until closeGpio(): `on_press` for each debounced
  // press, `on_error` when a read fails (then it waits kButtonRetry and reads again). Both run on
  // that thread. Without a button line nothing.
  void watchButton(std::function<void()> on_press, std::function<void(const Error&)> on_error);
  void show(rig::RigState state);

  // The camera calibration in the config's calibration file, when it holds one.
  Result<std::optional<Calibration>> cameraCalibration() const;

  // For the series: opens the config's [illuminance] instrument, to be sampled during each of
  // its brackets; without one nothing. Its error (naming the config) for a build without
  // libmodbus or an instrument that cannot be set up (a simulated one that cannot listen);
  // reading failures come later, per stack.
  Status openIlluminance();

  // capture::SeriesRig, for `glarecam capture --config`: the press (with on_button), the
  // geometry (the first stack's measured before the camera opened, unless a press came since),
  // the LED. With the button, an inclinometer that cannot read (the rig moving in a gust) shows
  // its fault and waits for the next press instead of ending the session.
  Result<bool> prepareStack(capture::CaptureSettings& settings, std::uint64_t index) override;
  void finishStack(capture::CapturedStack& stack, UtcTime bracket_start,
                   UtcTime bracket_end) override;

 private:
  Result<rig::RigGeometry> read(UtcTime time, const std::optional<sun::ClockStatus>& clock);

  rig::RigConfig config_;
  RigSessionOptions options_;
  std::unique_ptr<rig::RigSensors> sensors_;
  std::optional<rig::RigGeometry> last_geometry_;
  std::set<std::string> logged_warnings_;  // the sensors' standing warnings, logged once
  std::unique_ptr<rig::RigIo> io_;
  std::unique_ptr<rig::StatusLed> led_;
  std::jthread button_thread_;
  rig::OpenedIlluminance illuminance_;
  std::unique_ptr<rig::IlluminanceSampler> illuminance_sampler_;  // before illuminance_ goes
  bool sampling_ = false;                                         // during a bracket of the series
};

// The tilt's plausibility rule: kHardware naming the sensor when `geometry`'s measured tilt lies
// outside [faults.min_tilt_deg, faults.max_tilt_deg].
Status checkPlausibleTilt(const rig::RigGeometry& geometry, const FaultConfig& faults);

}  // namespace glarecam::daemon
